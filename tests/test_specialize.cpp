// The kernels specialized per (D, G) pair (runtime/specialize.hpp) take the
// samples of the generic fast paths and give their estimates to the bit, and
// Integrator::run launches them where the program has them. A planted
// specialization that evaluates another G than its name says is caught. The
// transmission checks' own `integrate` kernels give the generic one's sums.
#include "albedo_spec.hpp"
#include "catalog/bsdfs.hpp"
#include "catalog/catalog.hpp"
#include "catalog/roughness.hpp"
#include "checks/integrate.hpp"
#include "device_fixture.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/specialize.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <tuple>

using namespace mfv;

namespace {

TermSelection three_of_each() {
  TermSelection sel;
  sel.d = {&find_term("ggx"), &find_term("beckmann"), &find_term("phong")};
  sel.g = {&find_term("smith_ggx_correlated"), &find_term("smith_beckmann"), &find_term("smith_phong")};
  sel.f = {&find_term("schlick"), &find_term("none")};
  return sel;
}

// AlbedoMis, masking, stratified d_norm and RQMC albedo integrals over
// several pairs, a mismatched one among them, grazing and normal views.
std::vector<IntegralSpec> mixed_specs() {
  using test::albedo_spec;
  std::vector<IntegralSpec> s;
  uint32_t stream = 0;
  for (auto kind : {IntegralKind::AlbedoMis, IntegralKind::Masking, IntegralKind::AlbedoRqmc}) {
    s.push_back(albedo_spec("ggx", "smith_ggx_correlated", "schlick", 0.3, 0.7, 0.04, 0.0, stream++, kind));
    s.push_back(albedo_spec("beckmann", "smith_beckmann", "none", 0.05, 1e-3, 1.0, 0.0, stream++, kind));
    s.push_back(albedo_spec("phong", "smith_phong", "schlick", 0.8, 0.2, 0.5, 0.3, stream++, kind));
    s.push_back(albedo_spec("ggx", "smith_beckmann", "none", 0.5, 0.05, 1.0, 0.0, stream++, kind));
  }
  for (auto [d, a] : {std::pair<const char*, double>{"ggx", 0.3}, {"beckmann", 1e-3}, {"phong", 0.6}})
    s.push_back(test::d_norm_spec(d, a, stream++));
  return s;
}

std::vector<Estimate> run(Integrator& in, std::vector<IntegralSpec> specs) {
  in.stratify(specs, 16384);
  return in.run(specs, 16384, 11);
}

// Every estimate and standard error of `b` equal to `a`'s to the bit, and finite.
void check_same_bits(const std::vector<Estimate>& a, const char* a_name, const std::vector<Estimate>& b,
                     const char* b_name) {
  REQUIRE(a.size() == b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    INFO("integral " << i << ": " << a_name << " " << a[i].mean << " +- " << a[i].stderr_ << ", " << b_name << " "
                     << b[i].mean << " +- " << b[i].stderr_);
    CHECK(std::isfinite(a[i].mean));
    CHECK(std::memcmp(&a[i].mean, &b[i].mean, sizeof(double)) == 0);
    CHECK(std::memcmp(&a[i].stderr_, &b[i].stderr_, sizeof(double)) == 0);
  }
}

}  // namespace

TEST_CASE("kernels specialized per term pair give the generic kernels' estimates, to the bit", "[integrate][device]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  const std::vector<IntegralSpec> specs = mixed_specs();
  TermSelection sel = three_of_each();
  Integrator generic(*rt, sel);
  sel.specialized = fast_path_pairs(specs);
  REQUIRE(sel.specialized.size() == 4 + 3);  // four (D, G) pairs, and the d_norm integrals' three Ds
  Integrator specialized(*rt, sel);
  const auto a = run(generic, specs), b = run(specialized, specs);
  REQUIRE(a.size() == b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    INFO("integral " << i << ": generic " << a[i].mean << " +- " << a[i].stderr_ << ", specialized " << b[i].mean
                     << " +- " << b[i].stderr_);
    CHECK(std::memcmp(&a[i].mean, &b[i].mean, sizeof(double)) == 0);
    CHECK(std::memcmp(&a[i].stderr_, &b[i].stderr_, sizeof(double)) == 0);
  }
  // the generic program launched only generic kernels; the specialized one,
  // where PoCL inlines the terms, one kernel per pair and check
  for (auto& k : generic.launched_kernels()) CHECK(k.find("__") == std::string::npos);
  if (!test::is_pocl(*rt)) return;
  const int ggx = term_index(find_term("ggx")), corr = term_index(find_term("smith_ggx_correlated"));
  const int beckmann = term_index(find_term("beckmann"));
  const auto& launched = specialized.launched_kernels();
  for (auto name : {fmt::format("albedo_mis_values__g{}", corr), fmt::format("albedo_mis_df__d{}", ggx),
                    fmt::format("masking_values__g{}", corr), fmt::format("masking_d__d{}", ggx),
                    fmt::format("albedo_rqmc_values__d{}_g{}", ggx, corr),
                    fmt::format("d_norm_values__d{}", beckmann)}) {
    INFO(name);
    CHECK(launched.count(name) == 1);
  }
  for (auto base : {"albedo_mis_values", "albedo_mis_df", "masking_values", "masking_d", "albedo_rqmc_values", "d_norm_values"}) {
    INFO(base);
    CHECK(launched.count(base) == 0);
  }
}

TEST_CASE("a specialized kernel that evaluates another G than its pair's is caught (planted)",
          "[integrate][device][planted]") {
  Runtime* rt = test::device_runtime();
  if (!rt || !test::is_pocl(*rt)) return;  // other drivers build no specializations
  const std::vector<IntegralSpec> specs = mixed_specs();
  TermSelection sel = three_of_each();
  sel.specialized = fast_path_pairs(specs);
  Integrator generic(*rt, three_of_each());
  const auto a = run(generic, specs);
  const int ggx = term_index(find_term("ggx")), corr = term_index(find_term("smith_ggx_correlated"));
  const int separable = term_index(find_term("smith_beckmann")), beckmann = term_index(find_term("beckmann"));
  // (the kernel as generated, as planted, the integrals it serves in mixed_specs): a kernel
  // per pair serves one integral; albedo_mis_values__g<corr> and masking_values__g<corr> the
  // one AlbedoMis or masking integral with that G; albedo_mis_df__d<ggx> and masking_d__d<ggx>
  // the two AlbedoMis or masking integrals with D ggx
  const std::tuple<std::string, std::string, size_t> plants[] = {
      {fmt::format("MFV_ALBEDO_MIS_VALUES(albedo_mis_values__g{}, {})", corr, corr),
       fmt::format("MFV_ALBEDO_MIS_VALUES(albedo_mis_values__g{}, {})", corr, separable), 1},
      {fmt::format("MFV_ALBEDO_MIS_DF(albedo_mis_df__d{}, {})", ggx, ggx),
       fmt::format("MFV_ALBEDO_MIS_DF(albedo_mis_df__d{}, {})", ggx, beckmann), 2},
      {fmt::format("MFV_MASKING_VALUES(masking_values__g{}, {})", corr, corr),
       fmt::format("MFV_MASKING_VALUES(masking_values__g{}, {})", corr, separable), 1},
      {fmt::format("MFV_MASKING_D(masking_d__d{}, {})", ggx, ggx),
       fmt::format("MFV_MASKING_D(masking_d__d{}, {})", ggx, beckmann), 2},
      {fmt::format("MFV_ALBEDO_RQMC_VALUES(albedo_rqmc_values__d{}_g{}, {}, {})", ggx, corr, ggx, corr),
       fmt::format("MFV_ALBEDO_RQMC_VALUES(albedo_rqmc_values__d{}_g{}, {}, {})", ggx, corr, ggx, separable), 1},
  };
  for (const auto& [right, wrong, served] : plants) {
    INFO(wrong);
    std::string text = generate_specializations(sel.specialized);
    const size_t at = text.find(right);
    REQUIRE(at != std::string::npos);
    text.replace(at, right.size(), wrong);
    Integrator planted(*rt, build_integrate_program(*rt, sel, text), true);
    const auto b = run(planted, specs);
    size_t differ = 0;
    for (size_t i = 0; i < a.size(); ++i) differ += a[i].mean != b[i].mean;
    CHECK(differ == served);  // the integrals of that kernel
  }
}

namespace {

// The transmission checks' iid integrals (masking_t and bsdf_avg) of the rough dielectric `bsdf`.
IntegralSpec bsdf_spec(IntegralKind kind, const char* bsdf, double alpha, double eta, double mu, uint32_t stream) {
  const Bsdf* b = try_find_bsdf(bsdf);
  REQUIRE(b);
  MicrofacetIntegral mi;
  mi.kind = kind;
  mi.d = b->d, mi.g = b->g;
  mi.pd = native_from_alpha(b->d->roughness, alpha), mi.pg = native_from_alpha(b->g->roughness, alpha);
  mi.width = alpha;
  mi.cos_o = mu;
  IntegralSpec s = spec_of(mi);
  s.eta = float(eta);
  s.bsdf = b->code();
  s.stream = stream;
  return s;
}

std::vector<IntegralSpec> bsdf_specs() {
  std::vector<IntegralSpec> s;
  uint32_t stream = 0;
  for (const char* b : {"walter_ggx_correlated", "walter_beckmann_separable"})
    for (double alpha : {0.05, 0.5}) {
      s.push_back(bsdf_spec(IntegralKind::MaskingT, b, alpha, 1.5, 0.3, stream++));
      s.push_back(bsdf_spec(IntegralKind::MaskingT, b, alpha, 1.5, 0.95, stream++));
      s.push_back(bsdf_spec(IntegralKind::BsdfAvg, b, alpha, 1.33, 1.0, stream++));
    }
  return s;
}

TermSelection bsdf_selection() {
  TermSelection sel;
  for (const char* b : {"walter_ggx_correlated", "walter_beckmann_separable"}) {
    sel.d.push_back(try_find_bsdf(b)->d);
    sel.g.push_back(try_find_bsdf(b)->g);
  }
  sel.f = {&find_term("none")};
  sel.g1 = true;
  return sel;
}

}  // namespace

TEST_CASE("the transmission checks' own integrate kernels give the generic integrate's sums, to the bit",
          "[integrate][device][transmission]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  const std::vector<IntegralSpec> specs = bsdf_specs();
  Integrator in(*rt, bsdf_selection());
  in.set_albedo_fast_path(false);  // `integrate` alone
  const auto a = run(in, specs);
  in.set_albedo_fast_path(true);
  const auto b = run(in, specs);
  check_same_bits(a, "generic", b, "the check's own");
  if (!test::is_pocl(*rt)) return;  // other drivers build no specializations
  for (auto name : {"integrate_masking_t", "integrate_bsdf_avg"}) {
    INFO(name);
    CHECK(in.launched_kernels().count(name) == 1);
  }
  // Planted: masking_t's kernel on bsdf_avg's case moves the masking_t integrals, and only them.
  std::string text = generate_check_kernels();
  const std::string right = "MFV_INTEGRATE_IID(integrate_masking_t, masking_t_value)";
  const size_t at = text.find(right);
  REQUIRE(at != std::string::npos);
  text.replace(at, right.size(), "MFV_INTEGRATE_IID(integrate_masking_t, bsdf_avg_value)");
  Integrator planted(*rt, build_integrate_program(*rt, bsdf_selection(), text), true);
  const auto c = run(planted, specs);
  for (size_t i = 0; i < a.size(); ++i) {
    INFO("integral " << i);
    CHECK((a[i].mean != c[i].mean) == (specs[i].check == MFV_CHECK_MASKING_T));
  }
}

namespace {

// AlbedoMis integrals of ggx/smith_ggx_correlated (grazing and normal views, a near-mirror
// width, F and a diffuse part) and one of another pair, which the one-pair kernel must not take.
std::vector<IntegralSpec> one_pair_specs() {
  using test::albedo_spec;
  constexpr auto kind = IntegralKind::AlbedoMis;
  return {albedo_spec("ggx", "smith_ggx_correlated", "schlick", 0.3, 0.7, 0.04, 0.0, 0, kind),
          albedo_spec("ggx", "smith_ggx_correlated", "none", 1e-3, 1e-3, 1.0, 0.0, 1, kind),
          albedo_spec("ggx", "smith_ggx_correlated", "schlick", 0.9, 1.0, 0.5, 0.3, 2, kind),
          albedo_spec("beckmann", "smith_beckmann", "none", 0.5, 0.5, 1.0, 0.0, 3, kind)};
}

TermSelection one_pair_selection() {
  TermSelection sel = three_of_each();
  sel.specialized = {{term_index(find_term("ggx")), term_index(find_term("smith_ggx_correlated"))}};
  return sel;
}

}  // namespace

TEST_CASE("a program of one term pair runs AlbedoMis in one kernel, with the three kernels' estimates to the bit",
          "[integrate][device]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  const std::vector<IntegralSpec> specs = one_pair_specs();
  Integrator generic(*rt, three_of_each()), one_pair(*rt, one_pair_selection());
  const auto a = run(generic, specs), b = run(one_pair, specs);
  check_same_bits(a, "three kernels", b, "one pair");
  if (!test::is_pocl(*rt)) return;  // other drivers build no specializations
  const int ggx = term_index(find_term("ggx")), corr = term_index(find_term("smith_ggx_correlated"));
  const auto& launched = one_pair.launched_kernels();
  CHECK(launched.count(fmt::format("albedo_mis_pair__d{}_g{}", ggx, corr)) == 1);
  CHECK(launched.count(fmt::format("albedo_mis_df__d{}", ggx)) == 0);   // the pair's integrals took one kernel
  CHECK(launched.count("albedo_mis_values") == 1);                      // the other pair's, the three generic ones
  // a program of several pairs (the full suite) has no one-pair kernel: its cold compile stays one per D and G
  TermSelection two = one_pair_selection();
  two.specialized.push_back({term_index(find_term("beckmann")), term_index(find_term("smith_beckmann"))});
  CHECK(generate_specializations(two.specialized).find("MFV_ALBEDO_MIS_PAIR") == std::string::npos);
  CHECK(generate_specializations(one_pair_selection().specialized).find("MFV_ALBEDO_MIS_PAIR") != std::string::npos);
}

TEST_CASE("a one-pair AlbedoMis kernel that evaluates another D or G than its pair's is caught (planted)",
          "[integrate][device][planted]") {
  Runtime* rt = test::device_runtime();
  if (!rt || !test::is_pocl(*rt)) return;  // other drivers build no specializations
  const std::vector<IntegralSpec> specs = one_pair_specs();
  const TermSelection sel = one_pair_selection();
  Integrator right_program(*rt, sel);
  const auto a = run(right_program, specs);
  const int ggx = term_index(find_term("ggx")), corr = term_index(find_term("smith_ggx_correlated"));
  const int separable = term_index(find_term("smith_beckmann")), beckmann = term_index(find_term("beckmann"));
  const std::string right = fmt::format("MFV_ALBEDO_MIS_PAIR(albedo_mis_pair__d{}_g{}, {}, {})", ggx, corr, ggx, corr);
  for (const std::string& wrong :
       {fmt::format("MFV_ALBEDO_MIS_PAIR(albedo_mis_pair__d{}_g{}, {}, {})", ggx, corr, beckmann, corr),
        fmt::format("MFV_ALBEDO_MIS_PAIR(albedo_mis_pair__d{}_g{}, {}, {})", ggx, corr, ggx, separable)}) {
    INFO(wrong);
    std::string text = generate_specializations(sel.specialized);
    const size_t at = text.find(right);
    REQUIRE(at != std::string::npos);
    text.replace(at, right.size(), wrong);
    Integrator planted(*rt, build_integrate_program(*rt, sel, text), true);
    const auto b = run(planted, specs);
    size_t differ = 0;
    for (size_t i = 0; i < a.size(); ++i) differ += a[i].mean != b[i].mean;
    CHECK(differ == 3);  // the pair's three integrals, not the other pair's
  }
}

TEST_CASE("The microfacet reciprocity kernel takes a launch only where its compile pays, with the generic "
          "kernel's asymmetries to the bit",
          "[device][specialize][reciprocity]") {
  // Integrator::reciprocity: isotropic microfacet integrals go to
  // reciprocity_values_microfacet from kMicrofacetReciprocityPairs pairs a
  // launch, otherwise to reciprocity_values; both draw the same pairs and
  // evaluate the same BRDF, so the worst asymmetry and its pair agree
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  std::vector<IntegralSpec> specs = mixed_specs();
  for (auto& s : specs) s.check = static_cast<int32_t>(IntegralKind::DNorm), s.strata = 0;  // kind ignored
  const uint32_t pairs = 4096;
  REQUIRE(uint64_t(specs.size()) * pairs < kMicrofacetReciprocityPairs);
  Integrator small(*rt, three_of_each()), forced(*rt, three_of_each());
  forced.set_microfacet_reciprocity_from(0);
  const WorstPairs a = small.reciprocity(specs, pairs, 7), b = forced.reciprocity(specs, pairs, 7);
  CHECK(small.launched_kernels().count("reciprocity_values_microfacet") == 0);
  CHECK(forced.launched_kernels().count("reciprocity_values_microfacet") == 1);
  for (size_t i = 0; i < specs.size(); ++i) {
    INFO("integral " << i << ": generic " << a.worst[i] << " at " << a.at[i] << ", microfacet " << b.worst[i]
                     << " at " << b.at[i]);
    CHECK(a.worst[i] > 0);
    CHECK(a.worst[i] == b.worst[i]);
    CHECK(a.at[i] == b.at[i]);
  }
  // a launch that holds the threshold's pairs takes the microfacet kernel
  Integrator large(*rt, three_of_each());
  large.set_microfacet_reciprocity_from(uint64_t(specs.size()) * pairs);
  large.reciprocity(specs, pairs, 7);
  CHECK(large.launched_kernels().count("reciprocity_values_microfacet") == 1);
}

TEST_CASE("A pair's RQMC albedo kernel is specialized only where an RQMC integral of the pair asks for it",
          "[specialize]") {
  // fast_path_pairs marks the pairs with an AlbedoRqmc or EavgRqmc integral;
  // generate_specializations gives albedo_rqmc_values only to those (mfv
  // run has none: one front-end compile fewer per pair on a cold run)
  using test::albedo_spec;
  const std::vector<IntegralSpec> mis_only = {
      albedo_spec("ggx", "smith_ggx_correlated", "schlick", 0.3, 0.7, 0.04, 0.0, 0, IntegralKind::AlbedoMis),
      albedo_spec("beckmann", "smith_beckmann", "none", 0.05, 0.5, 1.0, 0.0, 1, IntegralKind::Masking)};
  const std::vector<TermPair> none = fast_path_pairs(mis_only);
  REQUIRE(none.size() == 2);
  for (const TermPair& p : none) CHECK_FALSE(p.rqmc);
  CHECK(generate_specializations(none).find("MFV_ALBEDO_RQMC_VALUES") == std::string::npos);
  CHECK(generate_specializations(none).find("MFV_ALBEDO_MIS_VALUES") != std::string::npos);
  std::vector<IntegralSpec> one = mis_only;
  one.push_back(albedo_spec("ggx", "smith_ggx_correlated", "schlick", 0.5, 0.5, 0.04, 0.0, 2, IntegralKind::AlbedoRqmc));
  const std::vector<TermPair> marked = fast_path_pairs(one);
  REQUIRE(marked.size() == 2);
  const int ggx = term_index(find_term("ggx")), corr = term_index(find_term("smith_ggx_correlated"));
  const int beckmann = term_index(find_term("beckmann")), separable = term_index(find_term("smith_beckmann"));
  const std::string text = generate_specializations(marked);
  CHECK(text.find(fmt::format("albedo_rqmc_values__d{}_g{},", ggx, corr)) != std::string::npos);
  CHECK(text.find(fmt::format("albedo_rqmc_values__d{}_g{},", beckmann, separable)) == std::string::npos);
  // a selection that asks for a pair's RQMC kernel keeps it when merged with one that does not
  TermSelection a, b;
  a.specialized = none;
  b.specialized = marked;
  a.add(b);
  REQUIRE(a.specialized.size() == 2);
  for (const TermPair& p : a.specialized) CHECK(p.rqmc == (p.d == ggx && p.g == corr));
  // a pair given by hand (mfv energy's tables, bench --case) keeps its RQMC kernel
  CHECK(TermPair{ggx, corr}.rqmc);
}
