// mfv agree over the BTDFs' declared eta range [0.01, 100] (issue 29): near
// the critical angle of a small relative index the float kernel's total-
// internal-reflection test g² = (η - 1)(η + 1) + c² is decided by its
// rounding, so agree's conditioning allowance takes g² within its derived
// float rounding (checks/pointwise.hpp btdf_tir_rounding) and 1 - F at its
// extremes there (reference/btdf.hpp g2_slack). Shown here: the extremes
// bracket 1 - F, the derived bound covers the float rounding of the kernel's
// operations, the two records that failed before pass, and planted bugs
// still fail over the whole range.
#include "agree_options.hpp"
#include "catalog/bsdfs.hpp"
#include "checks/agree.hpp"
#include "checks/pointwise.hpp"
#include "checks/stability.hpp"
#include "device_fixture.hpp"
#include "plants.hpp"
#include "reference/btdf.hpp"

#include <catch2/catch.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <regex>

using namespace mfv;

// The numbers of a worst-point line of mfv stability's BTDF cases
// ("wi=(x, y, z) wo=(x, y, z) pD=a pG=b eta=e ..."), in order.
static std::vector<double> hex_numbers(const std::string& line) {
  std::vector<double> v;
  static const std::regex num("-?0x[0-9a-fA-F.]+p[-+][0-9]+");
  for (auto it = std::sregex_iterator(line.begin(), line.end(), num); it != std::sregex_iterator(); ++it)
    v.push_back(std::strtod(it->str().c_str(), nullptr));
  return v;
}

namespace {

ref::BtdfSpec spec(const char* id, double pd, double pg, double eta) {
  const Bsdf& b = *try_find_bsdf(id);
  return {b.d, b.g, b.form, b.variant, pd, pg, eta};
}

// The kernel's g² (kernels/btdf.cl: flip, s = l + η v, normalize_sum, c = |l·h|,
// T_dielectric's g2) in float on this host, from the float record.
float kernel_g2(const float* l0, const float* v0, float eta) {
  float l[3] = {l0[0], l0[1], l0[2]}, v[3] = {v0[0], v0[1], v0[2]};
  if (l[2] < 0.0f) {
    for (int k = 0; k < 3; ++k) l[k] = -l[k], v[k] = -v[k];
    eta = 1.0f / eta;
  }
  float s[3];
  for (int k = 0; k < 3; ++k) {
    const volatile float p = eta * v[k];  // volatile: no contraction into an FMA on this side either
    s[k] = l[k] + p;
  }
  volatile float n2 = s[0] * s[0];
  n2 = n2 + s[1] * s[1];
  n2 = n2 + s[2] * s[2];
  const float inv = 1.0f / std::sqrt(static_cast<float>(n2));
  float h[3];
  for (int k = 0; k < 3; ++k) h[k] = s[k] * inv;
  if (h[2] < 0.0f)
    for (float& x : h) x = -x;
  volatile float c = l[0] * h[0];
  c = c + l[1] * h[1];
  c = c + l[2] * h[2];
  const float cc = std::min(std::fabs(static_cast<float>(c)), 1.0f);
  const volatile float a = (eta - 1.0f) * (eta + 1.0f);
  const volatile float c2 = cc * cc;
  return a + c2;
}

}  // namespace

TEST_CASE("1 - F at its extremes over the TIR test's rounding brackets 1 - F there", "[reference][btdf]") {
  // Near the critical angle of eta = 0.0102 (leaving, light from above at relative
  // index eta) 1 - F's p half peaks at g = eta^2 c inside the interval: its ends miss it.
  for (double eta : {0.0102, 0.1, 1 / 1.5}) {
    const ref::BtdfSpec s = spec("walter_ggx_correlated", 0.5, 0.5, eta);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int bracketed = 0;
    for (int n = 0; n < 200; ++n) {
      // i above, o below at i.o close to -eta: h_t's facet cosine near the critical one
      const double ci = 0.2 + 0.8 * u(rng), phi = 6.2831853 * u(rng);
      const glm::dvec3 i(std::sqrt(1 - ci * ci) * std::cos(phi), std::sqrt(1 - ci * ci) * std::sin(phi), ci);
      glm::dvec3 m = glm::normalize(i + glm::dvec3(0.01 * (u(rng) - 0.5), 0.01 * (u(rng) - 0.5), 0.0));
      glm::dvec3 o;
      if (!ref::refract(i, m, 1 / eta, o) || o.z >= 0) continue;
      const double slack = btdf_tir_rounding(eta, i, o, false);
      ref::BtdfSpec hi = s, lo = s;
      hi.g2_slack = slack, lo.g2_slack = -slack;
      const double f_hi = ref::btdf(hi, i, o), f_lo = ref::btdf(lo, i, o);
      // 1 - F at facet cosines within the interval: g² = eta² - 1 + c² moves by 2c² b
      const double c = std::fabs(glm::dot(i, ref::half_vector_t(i, o, eta)));
      const double bmax = 0.999 * slack / (2 * c * c + slack);
      for (int k = -50; k <= 50; ++k) {
        ref::BtdfSpec moved = s;
        moved.f_cos_bump = bmax * k / 50.0;
        const double f = ref::btdf(moved, i, o);
        CAPTURE(eta, ci, k, f, f_lo, f_hi);
        CHECK(f <= f_hi * (1 + 1e-12));
        CHECK(f >= f_lo * (1 - 1e-12));
      }
      ++bracketed;
    }
    CHECK(bracketed > 50);
  }
}

TEST_CASE("The derived float rounding of the BTDF kernel's TIR test covers its float operations",
          "[pointwise][btdf]") {
  // The kernel's float ops on this host (correctly rounded sqrt and division,
  // tighter than OpenCL's 3 and 2.5 ulp that the bound assumes) against the
  // exact g² at the same float numbers, over refracted float records at eta
  // across [0.01, 100], both sides.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0;
  for (int n = 0; n < 200000; ++n) {
    const double eta = std::pow(10.0, -2.0 + 4.0 * u(rng));
    const double ci = std::max(1e-3, u(rng) * u(rng)), phi = 6.2831853 * u(rng);
    glm::dvec3 i(std::sqrt(1 - ci * ci) * std::cos(phi), std::sqrt(1 - ci * ci) * std::sin(phi), ci);
    const double t = 0.3 * u(rng) * u(rng) * u(rng), pm = 6.2831853 * u(rng);
    const glm::dvec3 m(std::sin(t) * std::cos(pm), std::sin(t) * std::sin(pm), std::cos(t));
    const bool below = u(rng) < 0.5;
    glm::dvec3 o;
    if (glm::dot(i, m) <= 0 || !ref::refract(i, m, below ? eta : 1 / eta, o) || o.z >= 0) continue;  // transmitted pairs
    if (below) i = -i, o = -o;
    const float fi[3] = {float(i.x), float(i.y), float(i.z)}, fo[3] = {float(o.x), float(o.y), float(o.z)};
    const float feta = float(eta);
    // the exact g² at the float record, as the reference forms it
    const glm::dvec3 wi(fi[0], fi[1], fi[2]), wo(fo[0], fo[1], fo[2]);
    const double ei = wi.z > 0 ? 1.0 : feta, eo = wo.z > 0 ? 1.0 : feta, rel = eo / ei;
    const glm::dvec3 h = ref::half_vector_t(wi, wo, feta);
    if (!(h.z > 0)) continue;
    const double c = std::min(1.0, std::fabs(glm::dot(wi, h)));
    const double g2 = (rel - 1) * (rel + 1) + c * c;
    const double err = std::fabs(double(kernel_g2(fi, fo, feta)) - g2);
    const double bound = btdf_tir_rounding(feta, wi, wo, false);
    CAPTURE(eta, below, g2, err, bound);
    REQUIRE(err <= bound);
    worst = std::max(worst, err / bound);
  }
  WARN("worst float error of the TIR test's g2 / its derived bound: " << worst);
  CHECK(worst > 0.01);  // the bound is not vacuous: it is within two decades of what happens
}

TEST_CASE("mfv agree passes the BTDF records at eta 94 and 0.0102 that the TIR test's rounding decides",
          "[device][agree][btdf]") {
  // seed 1, 10^6 inputs over [0.01, 100]: the reference 0 (total internal
  // reflection at the record's numbers), the float kernel on the other side
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  struct Rec {
    const char* id;
    float in[6], eta, pd, pg;
  };
  const Rec recs[] = {
      {"walter_blinn_rho_correlated",
       {0x1.f777dp-6f, -0x1.ffbc6ep-1f, -0x1.3081c8p-7f, 0x1.8b103p-1f, 0x1.bf1aa4p-5f, 0x1.447b3ap-1f},
       0x1.779b44p+6f, 0x1.dce02p-1f, 0x1.dcaffap+1f},
      {"walter_ggx_no_eta2",
       {0x1.d0b256p-9f, 0x1.ffc5f6p-1f, 0x1.e40302p-6f, -0x1.f5c33p-1f, -0x1.15caf4p-8f, -0x1.9767e8p-3f},
       0x1.4f0cc8p-7f, 0x1.780084p-10f, 0x1.022122p+3f},
  };
  for (const Rec& r : recs) {
    PointSpec p;
    p.mode = EvalMode::Btdf;
    p.bsdf = try_find_bsdf(r.id);
    p.d = p.bsdf->d, p.g = p.bsdf->g;
    for (int k = 0; k < 6; ++k) p.inputs[k] = r.in[k];
    p.params[0] = r.pd, p.params[1] = r.pg, p.params[2] = r.eta;
    const PointValue v = eval_point(*rt, p, false);
    FloatRecord rec{};
    for (int k = 0; k < 6; ++k) rec[size_t(k)] = r.in[k];
    rec[pw::PW_P0] = r.pd, rec[pw::PW_P0 + 1] = r.pg, rec[pw::PW_P0 + 2] = r.eta;
    const RecordAllowance a = btdf_record_allowance(*p.bsdf, rec.data(), false, 0.0, true);
    CAPTURE(r.id, v.kernel, v.reference, a.allowed);
    CHECK(v.reference == 0.0);
    CHECK(v.kernel > 0.0);               // the kernel past the cut: 1.2e-7 and 1.1e-9 on PoCL 3.1
    CHECK(v.kernel <= a.allowed);        // within what 1 - F reaches over g²'s rounding
    CHECK(a.allowed <= 4.0 * v.kernel);  // and not far above it (measured 2.2x and 2.25x)
  }
}

TEST_CASE("Over eta in [0.01, 100] mfv agree still fails a BTDF kernel with the wrong index or critical angle",
          "[device][agree][btdf][planted]") {
  if (!test::device_runtime()) return;
  for (const test::Plant* plant : {&test::kBtdfLeavingEtaNotInverted, &test::kBtdfFresnelEtaInverted,
                                   &test::kBtdfCriticalAngleShifted}) {
    const test::PlantedKernelDir dir = test::planted(*plant);
    Runtime rt = dir.runtime();
    const AgreeReport rep =
        run_agree(rt, test::agree_options({"BTDF walter_ggx_correlated", "BTDF walter_beckmann_separable"}, 20000));
    REQUIRE(rep.results.size() == 2);
    CAPTURE(plant->name);
    test::check_every_case_fails(rep);
  }
}

TEST_CASE("mfv stability sweeps the BTDFs at eta 0.01 and 100 and their worst error is the TIR test's rounding",
          "[device][stability][btdf]") {
  // The declared range's ends (catalog/bsdfs.hpp): refracted pairs at 0.01 and
  // 100, near-critical ones at 0.01. Leaving eta = 100 (relative 0.01) every
  // refracted pair has g² = (eta o.h)² <= 1e-4, which the kernel forms as
  // c² - (1 - eta²): its rounding moves 1 - F by up to 3e-3 relative there.
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  StabilityOptions opt;  // the BTDF cases come with the combinations
  opt.models = false;
  opt.only = {"BTDF walter_ggx_correlated", "BTDF walter_beckmann_separable", "BTDF walter_phong_correlated"};
  const StabilityReport rep = run_stability(*rt, opt);
  REQUIRE(rep.cases.size() == 3);
  CHECK(rep.gate_pass());
  for (const StabilityCase& c : rep.cases) {
    CAPTURE(c.name);
    CHECK(c.stable);
    for (const RegionResult& r : c.regions) {
      CAPTURE(r.region, r.worst, r.max_rel);
      CHECK(r.nan + r.inf + r.negative + r.breaks == 0);
      if (r.region == "refracted") CHECK(r.what.find("0.01, 100}") != std::string::npos);
      if (r.region == "near_critical") CHECK(r.what.find("0.1, 0.01}") != std::string::npos);
      if (r.region != "refracted") continue;
      // the worst point: its error within what 1 - F moves over g² +- the derived rounding
      const std::vector<double> v = hex_numbers(r.worst);
      REQUIRE(v.size() >= 11);  // wi, wo, pD, pG, eta, kernel, reference
      const glm::dvec3 wi(v[0], v[1], v[2]), wo(v[3], v[4], v[5]);
      const Bsdf& b = *try_find_bsdf(c.name.substr(5));
      ref::BtdfSpec s{b.d, b.g, b.form, b.variant, v[6], v[7], v[8]};
      const double f = ref::btdf(s, wi, wo);
      CHECK(f == v[10]);
      CHECK(v[8] == 100.0);  // the worst is at the range's end
      s.g2_slack = btdf_tir_rounding(v[8], wi, wo, false);
      const double hi = ref::btdf(s, wi, wo);
      s.g2_slack = -s.g2_slack;
      const double lo = ref::btdf(s, wi, wo);
      CAPTURE(f, lo, hi);
      CHECK(r.max_rel > 1e-3);  // measured 3.07e-3 on PoCL 3.1
      CHECK(r.max_rel <= std::max(hi / f - 1, 1 - lo / f));
    }
  }
}
