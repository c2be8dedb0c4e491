// Whole models' albedo through model_albedo_values (kernels/model_values.cl),
// specialized per model (runtime/specialize.hpp): the samples of
// `integrate` (estimates equal but for the order of the double sums), and Integrator::run launches the specialized
// kernels where the program has them. A planted specialization that
// evaluates another model than its name says is caught. The whole models'
// reciprocity kernels (kernels/reciprocity.cl) give the generic kernel's
// asymmetries to the bit.
#include "catalog/models.hpp"
#include "checks/integrate.hpp"
#include "device_fixture.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/integrator.hpp"
#include "runtime/specialize.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace mfv;

namespace {

// Every model's first case whose integral the fast path takes (isotropic
// proposal of width > 0), at a normal and a grazing light.
TermSelection model_selection(std::vector<IntegralSpec>& specs) {
  TermSelection sel;
  uint32_t stream = 0;
  for (const Model& m : models()) {
    if (m.cases.empty()) continue;
    const IntegralSpec s = model_spec(IntegralKind::Albedo, m, m.cases.front().p, 0.9);
    if (!(s.width > 0) || s.width_y > 0) continue;
    for (double co : {0.9, 0.05}) {
      specs.push_back(model_spec(IntegralKind::Albedo, m, m.cases.front().p, co));
      specs.back().stream = stream++;
    }
    sel.models.push_back(&m);
  }
  return sel;
}

// iid integrals (no strata): 16384 samples each, seed 5
std::vector<Estimate> run(Integrator& in, const std::vector<IntegralSpec>& specs) { return in.run(specs, 16384, 5); }

}  // namespace

TEST_CASE("whole models' albedo kernels give integrate's estimates", "[integrate][device][model_values]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  std::vector<IntegralSpec> specs;
  const TermSelection sel = model_selection(specs);
  REQUIRE(sel.models.size() >= 10);
  Integrator in(*rt, sel);
  in.set_albedo_fast_path(false);
  const auto a = run(in, specs);
  REQUIRE(in.launched_kernels().empty());
  in.set_albedo_fast_path(true);
  const auto b = run(in, specs);
  REQUIRE(a.size() == b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    INFO("model " << specs[i].model << " cos_l " << specs[i].cos_o << ": integrate " << a[i].mean << " +- "
                  << a[i].stderr_ << ", values " << b[i].mean << " +- " << b[i].stderr_);
    REQUIRE(a[i].samples == b[i].samples);
    CHECK(std::isfinite(a[i].mean));
    // the same float samples, summed in double in another order (work-item
    // sums and a tree in `integrate`, four runs in sum_values; as
    // tests/test_aniso_values.cpp): 16384 values of at most ~10 each sum
    // with relative rounding ~16384 * 2^-53 ~ 2e-12 at worst, far less in
    // practice; the standard error's sum of squares cancels against n mean²
    // (a relative 1e-9 leaves room for that)
    CHECK(std::fabs(a[i].mean - b[i].mean) <= 1e-12 * std::max(1.0, std::fabs(a[i].mean)));
    CHECK(std::fabs(a[i].stderr_ - b[i].stderr_) <= 1e-9 * std::max(1e-6, a[i].stderr_));
  }
  const auto& launched = in.launched_kernels();
  CHECK(launched.count("model_albedo_values") == 0);  // there is no generic kernel (kernels/model_values.cl)
  if (!test::is_pocl(*rt)) return;                    // nor are specializations built there
  for (const Model* m : sel.models) {
    INFO(m->id);
    CHECK(launched.count(fmt::format("model_albedo_values__m{}", m->number())) == 1);
  }
}

TEST_CASE("a model kernel that evaluates another model than its name says is caught (planted)",
          "[integrate][device][model_values][planted]") {
  Runtime* rt = test::device_runtime();
  if (!rt || !test::is_pocl(*rt)) return;  // other drivers build no specializations
  std::vector<IntegralSpec> specs;
  const TermSelection sel = model_selection(specs);
  Integrator generic(*rt, sel);
  const auto a = run(generic, specs);
  const uint32_t lambert = try_find_model("lambert")->number(), eon = try_find_model("eon")->number();
  std::string text = generate_model_specializations(sel.models, false);
  const std::string right = fmt::format("MFV_MODEL_ALBEDO_VALUES(model_albedo_values__m{0}, {0})", eon);
  const size_t at = text.find(right);
  REQUIRE(at != std::string::npos);
  text.replace(at, right.size(), fmt::format("MFV_MODEL_ALBEDO_VALUES(model_albedo_values__m{}, {})", eon, lambert));
  Integrator planted(*rt, build_integrate_program(*rt, sel, text), true);
  const auto b = run(planted, specs);
  size_t differ = 0;
  for (size_t i = 0; i < a.size(); ++i) differ += a[i].mean != b[i].mean;
  CHECK(differ == 2);  // eon's two integrals
}

TEST_CASE("whole models' reciprocity kernels give the generic kernel's asymmetries to the bit",
          "[reciprocity][device][model_values]") {
  // kernels/reciprocity.cl MFV_MODEL_RECIPROCITY_VALUES, specialized per
  // model (PoCL only), against reciprocity_values (a program without the
  // specializations): every case of every model, 4096 pairs each
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  std::vector<IntegralSpec> specs;
  TermSelection sel;
  for (const Model& m : models()) {
    for (const auto& c : m.cases) specs.push_back(model_spec(IntegralKind::DNorm, m, c.p, 1.0));
    if (!m.cases.empty()) sel.models.push_back(&m);
  }
  for (size_t i = 0; i < specs.size(); ++i) specs[i].stream = uint32_t(i);
  REQUIRE(sel.models.size() >= 10);
  Integrator generic(*rt, build_integrate_program(*rt, sel, ""), true);
  sel.reciprocity_per_model = true;  // as a run whose pairs pay for them (model_reciprocity_per_model_pays)
  Integrator specialized(*rt, sel);
  const WorstPairs a = generic.reciprocity(specs, 4096, 7), b = specialized.reciprocity(specs, 4096, 7);
  CHECK(generic.launched_kernels().empty());
  for (size_t i = 0; i < specs.size(); ++i) {
    INFO("model " << specs[i].model << ": generic " << a.worst[i] << " at " << a.at[i] << ", specialized "
                  << b.worst[i] << " at " << b.at[i]);
    CHECK(a.worst[i] == b.worst[i]);  // worst_of reads NaN as +inf
    CHECK(a.at[i] == b.at[i]);
  }
  if (!test::is_pocl(*rt)) return;  // other drivers build no specializations
  for (const Model* m : sel.models) {
    INFO(m->id);
    CHECK(specialized.launched_kernels().count(fmt::format("model_reciprocity_values__m{}", m->number())) == 1);
  }
}
