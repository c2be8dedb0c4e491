// The rough dielectric BTDF (Walter et al. 2007): the double reference's
// physics (generalized reciprocity, transmission masking, the Jacobian
// against the facet-space truth, the smooth and index-matched limits), the
// known-bad variants failing them, and the kernel agreeing with the reference.
#include "abi/bsdf.h"
#include "agree_options.hpp"
#include "catalog/bsdfs.hpp"
#include "catalog/roughness.hpp"
#include "checks/agree.hpp"
#include "checks/transmission_truth.hpp"
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "numeric/quadrature.hpp"
#include "reference/btdf.hpp"
#include "reference/reference.hpp"
#include "run_mfv.hpp"

#include <catch2/catch.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <random>

using namespace mfv;

namespace {

ref::BtdfSpec spec_of(const Bsdf& b, double alpha, double eta) {
  return {b.d, b.g, b.form, b.variant, native_from_alpha(b.d->roughness, alpha),
          native_from_alpha(b.g->roughness, alpha), eta};
}

glm::dvec3 dir_xz(double c) { return {std::sqrt((1.0 - c) * (1.0 + c)), 0.0, c}; }

// The largest violation of f_t(i,o)/η_o² = f_t(o,i)/η_i² over random pairs on
// opposite sides and over pairs refracted through a facet near the normal
// (where the lobe is), grazing and near-critical ones included, in units of
// the double reference's own rounding there: the Snell form of 1 - F from the
// other side cancels in η² - 1 + c² where that side's facet cosine is small,
// to 64 ε / min(|i·h|, |o·h|)² relative. Values below the normal range
// (subnormal: a sharp lobe's far tail) carry no relative precision and are skipped.
double worst_reciprocity(const ref::BtdfSpec& s) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0;
  for (int k = 0; k < 4000; ++k) {
    const double phi = 2 * M_PI * u(rng);
    double ci = k % 7 == 0 ? 1e-3 * u(rng) : u(rng);  // one in seven grazing
    glm::dvec3 i(std::sqrt(1 - ci * ci) * std::cos(phi), std::sqrt(1 - ci * ci) * std::sin(phi), ci);
    if (k % 2) i = -i;
    glm::dvec3 o;
    if (k % 3 == 0) {  // random, on the other side
      const double co = u(rng), po = 2 * M_PI * u(rng);
      o = glm::dvec3(std::sqrt(1 - co * co) * std::cos(po), std::sqrt(1 - co * co) * std::sin(po), -co);
      if (i.z < 0) o = -o;
    } else {  // refracted through a facet near the normal (near-critical when leaving)
      const double th = 0.5 * u(rng), ph = 2 * M_PI * u(rng);
      glm::dvec3 m(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
      if (glm::dot(i, m) < 0) m = -m;
      const double eta_i = i.z > 0 ? 1.0 : s.eta, eta_o = i.z > 0 ? s.eta : 1.0;
      if (!ref::refract(i, m, eta_i / eta_o, o)) continue;  // total internal reflection
    }
    const double eta_i = i.z > 0 ? 1.0 : s.eta, eta_o = o.z > 0 ? 1.0 : s.eta;
    const double a = ref::btdf(s, i, o) / (eta_o * eta_o), b = ref::btdf(s, o, i) / (eta_i * eta_i);
    if (std::max(a, b) < 1e-300) continue;
    const glm::dvec3 h = ref::half_vector_t(i, o, s.eta);
    const double c = std::min(std::fabs(glm::dot(i, h)), std::fabs(glm::dot(o, h)));
    const double bound = 64 * 0x1p-52 / (c * c);
    worst = std::max(worst, std::fabs(a - b) / std::max(a, b) / bound);
  }
  return worst;
}

// E_T(i) = ∫ f_t(i, o) |o·n| do over the outgoing directions, by a product
// Gauss-Legendre rule in (cos θ_o, φ) on o's hemisphere: the BTDF as it is
// evaluated, Jacobian included (the facet-space truth has no Jacobian).
double transmitted_over_o(const ref::BtdfSpec& s, const glm::dvec3& i) {
  const GaussRule g = gauss_legendre(16);
  const int panels_c = 48, panels_p = 24;
  double sum = 0;
  for (int pc = 0; pc < panels_c; ++pc)
    for (int a = 0; a < 16; ++a) {
      const double c = (pc + 0.5 * (g.x[a] + 1)) / panels_c, wc = 0.5 * g.w[a] / panels_c;
      for (int pp = 0; pp < panels_p; ++pp)
        for (int b = 0; b < 16; ++b) {
          const double p = M_PI * (pp + 0.5 * (g.x[b] + 1)) / panels_p, wp = M_PI * 0.5 * g.w[b] / panels_p;
          const double sn = std::sqrt((1 - c) * (1 + c));
          glm::dvec3 o(sn * std::cos(p), sn * std::sin(p), i.z > 0 ? -c : c);
          sum += 2 * wc * wp * ref::btdf(s, i, o) * c;  // φ ∈ [0, π], symmetric about the xz-plane
        }
    }
  return sum;
}

const ProductRule kTruthRule{16, 4, 8, 1e-10};

}  // namespace

TEST_CASE("The rough dielectric BTDFs obey generalized reciprocity f_t(i,o)/eta_o^2 = f_t(o,i)/eta_i^2",
          "[reference][btdf]") {
  for (auto& b : bsdfs()) {
    if (b.variant == MFV_BTDF_BAD_NO_ETA2 || b.variant == MFV_BTDF_BAD_F_AT_N || b.variant == MFV_BTDF_BAD_JACOBIAN)
      continue;  // the planted bugs that break reciprocity (below)
    for (double alpha : {0.05, 0.3, 1.0})
      for (double eta : {1.5, 1 / 1.5, 1.33, 3.0}) {
        CAPTURE(b.id, alpha, eta);
        CHECK(worst_reciprocity(spec_of(b, alpha, eta)) <= 1);
      }
  }
}

TEST_CASE("Dropping eta_o^2, taking F at n.i or the Jacobian (i.h + o.h)^2 breaks generalized reciprocity",
          "[reference][btdf][planted]") {
  for (const char* id : {"walter_ggx_no_eta2", "walter_ggx_f_at_n", "walter_ggx_jacobian_sum"}) {
    CAPTURE(id);
    CHECK(worst_reciprocity(spec_of(*try_find_bsdf(id), 0.3, 1.5)) > 1e6);
  }
}

TEST_CASE("Transmission masking: the G1 of each Smith D conserves projected area below the surface",
          "[reference][btdf]") {
  // ∫ G1(o, m) max(0, -o·m) D(m) dm = |o·n| for o below (Heitz 2014 eq. 19, transmitted side)
  auto masking = [](const Bsdf& b, double alpha, double cos_o) {
    const ref::BtdfSpec s = spec_of(b, alpha, 1.5);
    const glm::dvec3 o = -dir_xz(cos_o);
    return integrate_normals(
               [&](const glm::dvec3& m) {
                 const double om = glm::dot(o, m);
                 if (om >= 0) return 0.0;  // χ+(o·m / o·n), o·n < 0
                 const double D = b.d->ref_d_cs ? b.d->ref_d_cs(m.z * m.z, m.x * m.x + m.y * m.y, s.pd)
                                                : b.d->ref_d(m.z, s.pd);
                 return b.g->ref_g1(-o.z, s.pg) * -om * D;
               },
               kTruthRule)
               .value /
           cos_o;
  };
  for (const char* id : {"walter_ggx_correlated", "walter_beckmann_separable"})
    for (double alpha : {0.1, 0.5, 1.0})
      for (double c : {0.05, 0.3, 0.9}) {
        CAPTURE(id, alpha, c);
        CHECK(std::fabs(masking(*try_find_bsdf(id), alpha, c) - 1) < 1e-5);
      }
  // planted: Beckmann's G1 with GGX's D under-masks (the ratio is above 1 at grazing)
  CHECK(masking(*try_find_bsdf("walter_ggx_beckmann_g1"), 0.5, 0.05) > 1.02);
}

TEST_CASE("E_T over outgoing directions equals the facet-space truth: Walter's Jacobian", "[reference][btdf]") {
  for (const char* id : {"walter_ggx_correlated", "walter_beckmann_separable"})
    for (double eta : {1.5, 1 / 1.5})
      for (double c : {0.95, 0.5}) {
        const ref::BtdfSpec s = spec_of(*try_find_bsdf(id), 0.5, eta);
        const double over_o = transmitted_over_o(s, dir_xz(c));
        const BsdfFlux truth = bsdf_flux_truth(s, c, false, kTruthRule);
        CAPTURE(id, eta, c, over_o, truth.transmitted, truth.reflected);
        CHECK(std::fabs(over_o - truth.transmitted) < 2e-3);
        CHECK(truth.reflected + truth.transmitted <= 1.0);
        // from below at 1/eta is from above at eta (one flip)
        const ref::BtdfSpec flipped = spec_of(*try_find_bsdf(id), 0.5, 1 / eta);
        const BsdfFlux below = bsdf_flux_truth(flipped, c, true, kTruthRule);
        CHECK_THAT(below.transmitted, Catch::Matchers::WithinRel(truth.transmitted, 1e-12));
      }
  // planted: the Jacobian with (i.h + o.h)^2 and the incident side counted move E_T
  for (const char* id : {"walter_ggx_jacobian_sum", "walter_ggx_same_side"}) {
    const ref::BtdfSpec s = spec_of(*try_find_bsdf(id), 0.5, 1.5);
    const double over_o = transmitted_over_o(s, dir_xz(0.5));
    const BsdfFlux truth = bsdf_flux_truth(s, 0.5, false, kTruthRule);
    CAPTURE(id, over_o, truth.transmitted);
    CHECK(std::fabs(over_o - truth.transmitted) > 0.02);
  }
}

TEST_CASE("The smooth limit gives E_R = F and E_T = 1 - F, total internal reflection included", "[reference][btdf]") {
  const Bsdf& b = *try_find_bsdf("walter_ggx_correlated");
  for (double eta : {1.5, 1 / 1.5})
    for (double c : {0.9, 0.5, 0.3}) {  // 1/1.5 at cos 0.5 and 0.3: beyond the critical angle (cos 0.745)
      const BsdfFlux r = bsdf_flux_truth(spec_of(b, 1e-4, eta), c, false, kTruthRule);
      const double F = ref::F_dielectric(c, eta, 0);
      CAPTURE(eta, c, F, r.reflected, r.transmitted);
      CHECK(std::fabs(r.reflected - F) < 1e-3);
      CHECK(std::fabs(r.transmitted - (1 - F)) < 1e-3);
    }
}

TEST_CASE("Hemispherical averages obey T_avg(1/eta) = T_avg(eta)/eta^2", "[reference][btdf]") {
  // T_avg = 2 ∫ E_T(μ) μ dμ, Gauss-Legendre in μ; exact in a correct model
  // (the flux form's reciprocity), smooth and rough alike.
  const GaussRule g = gauss_legendre(24);
  auto t_avg = [&](const ref::BtdfSpec& s) {
    double sum = 0;
    for (int k = 0; k < 24; ++k) {
      const double mu = 0.5 * (g.x[k] + 1);
      sum += g.w[k] * 0.5 * 2 * mu * bsdf_flux_truth(s, mu, false, ProductRule{12, 3, 8, 1e-9}).transmitted;
    }
    return sum;
  };
  const Bsdf& b = *try_find_bsdf("walter_ggx_correlated");
  for (double alpha : {0.2, 0.6})
    for (double eta : {1.5}) {
      const double in = t_avg(spec_of(b, alpha, eta)), out = t_avg(spec_of(b, alpha, 1 / eta));
      CAPTURE(alpha, eta, in, out);
      CHECK(std::fabs(out - in / (eta * eta)) < 2e-3 * in);
    }
}

TEST_CASE("Index matched (eta = 1): the rough BTDF is 0 off the straight-through Dirac, F = 0", "[reference][btdf]") {
  const ref::BtdfSpec s = spec_of(*try_find_bsdf("walter_ggx_correlated"), 0.5, 1.0);
  for (double c : {0.9, 0.5}) {
    const glm::dvec3 i = dir_xz(c);
    CHECK(ref::btdf(s, i, glm::normalize(-i + glm::dvec3(0.1, 0.05, 0))) == 0.0);
    CHECK(ref::btdf(s, i, -i) == 0.0);  // h_t degenerate: the Dirac itself is no BTDF value
    CHECK(bsdf_flux_truth(s, c, false, kTruthRule).reflected == 0.0);
  }
}

TEST_CASE("Every rough dielectric BTDF kernel agrees with its double reference on identical inputs",
          "[device][agree][btdf]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  AgreeOptions opt = test::agree_options({"BTDF "}, 20000);
  AgreeReport rep = run_agree(*rt, opt);
  REQUIRE(rep.results.size() == bsdfs().size());
  test::check_every_case_passes(rep);
}

TEST_CASE("Agreement catches a BTDF kernel whose Jacobian is off", "[device][agree][btdf][planted]") {
  if (!test::device_runtime()) return;
  const test::PlantedKernelDir dir("btdf.cl", "sqr(IoH + OoH) : len * len;", "sqr(IoH + OoH) : len * len * R(1.001);");
  Runtime rt = dir.runtime();
  AgreeReport rep = run_agree(rt, test::agree_options({"BTDF walter_ggx_correlated", "BTDF walter_beckmann_separable"}, 5000));
  REQUIRE(rep.results.size() == 2);
  test::check_every_case_fails(rep);
}


TEST_CASE("mfv eval evaluates a rough dielectric BTDF on the device and in the reference", "[cli][btdf]") {
  if (!test::device_runtime()) return;
  // i from above at 45 degrees, o its refraction through n at eta = 1.5 (sin 28.1 degrees)
  const test::Run r = test::run_mfv(
      "eval walter_ggx_correlated --alpha 0.3 --param eta=1.5 --wi 0.70710678,0,0.70710678 --wo -0.47140452,0,-0.88191710");
  REQUIRE(r.code == 0);
  CHECK(r.out.find("kernel") != std::string::npos);
  CHECK(r.out.find("reference") != std::string::npos);
  const test::Run bad = test::run_mfv("eval walter_ggx_correlated --param eta=200 --wi 0,0,1 --wo 0,0,-1");
  CHECK(bad.code == 2);
  CHECK(bad.out.find("mfv: error: walter_ggx_correlated.eta = 200 is out of range") != std::string::npos);
}
