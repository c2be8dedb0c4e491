// mfv samplers: the chi-square machinery, the pdf quadratures, the
// reference samplers against their pdfs, and the device samplers passing and
// failing on planted defects (PlantedKernelDir).
#include "checks/chi_square.hpp"
#include "checks/samplers.hpp"
#include "kernel_dir.hpp"
#include "plants.hpp"
#include "numeric/quadrature.hpp"
#include "run_mfv.hpp"
#include "abi/integral.h"
#include "reference/estimators.hpp"

#include <glm/geometric.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace mfv;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

TEST_CASE("chi-square upper tail and Sidak level match tabulated values", "[samplers]") {
  // 95% quantiles of the chi-square distribution (Abramowitz & Stegun table 26.8)
  CHECK_THAT(chi_square_upper_tail(3.841459, 1), WithinRel(0.05, 1e-5));
  CHECK_THAT(chi_square_upper_tail(18.307038, 10), WithinRel(0.05, 1e-5));
  CHECK_THAT(chi_square_upper_tail(124.342113, 100), WithinRel(0.05, 1e-5));
  CHECK_THAT(chi_square_upper_tail(2.0, 2), WithinRel(std::exp(-1.0), 1e-12));  // Q(1, x/2) = e^(-x/2)
  CHECK(chi_square_upper_tail(0.0, 5) == 1.0);
  CHECK(chi_square_upper_tail(std::nan(""), 5) == 0.0);  // a NaN statistic is no fit
  CHECK_THAT(sidak_level(0.01, 1), WithinRel(0.01, 1e-12));
  CHECK_THAT(sidak_level(0.01, 14), WithinRel(1.0 - std::pow(0.99, 1.0 / 14), 1e-12));
}

TEST_CASE("chi-square test pools low expectations and rejects impossible cells", "[samplers]") {
  std::vector<double> e{1, 1, 1, 1, 1, 1000, 1000}, o{2, 0, 1, 1, 1, 990, 1009};
  ChiSquare t = chi_square_test(o, e);
  CHECK(t.dof == 2);  // five cells pooled into one of expectation 5, then 3 cells - 1
  CHECK(t.p_value > 0.5);
  e.push_back(0);
  o.push_back(1);
  CHECK(!chi_square_test(o, e).impossible.empty());
}

TEST_CASE("Gauss-Legendre rules are exact for polynomials of degree 2n-1", "[samplers]") {
  const GaussRule g = gauss_legendre(7);
  double s = 0;
  for (size_t i = 0; i < g.x.size(); ++i) s += g.w[i] * (std::pow(g.x[i], 12) + g.x[i]);
  CHECK_THAT(s, WithinRel(2.0 / 13.0, 1e-13));
}

TEST_CASE("every sampler's pdf integrates to 1, stiff and grazing included", "[samplers]") {
  std::vector<SamplerCase> cases = default_sampler_cases();
  // roughness -> 0 and views at the horizon: the quadrature must still resolve the lobe
  cases.push_back({Sampler::Mixture, 1e-3, 1});
  cases.push_back({Sampler::Slopes, 1e-3, 1});
  cases.push_back({Sampler::Vis, 1e-2, 1e-3});
  cases.push_back({Sampler::Vis, 1e-3, 1});
  // bsdf_furnace's sphere proposal at grazing light and a narrow lobe, both sides
  cases.push_back({Sampler::Flux, 0.05, 0.9, 1.5});
  cases.push_back({Sampler::Flux, 0.3, 0.05, 1 / 1.5});
  cases.push_back({Sampler::Flux, 0.3, 0.05, 3.0});
  for (const auto& c : cases) {
    INFO(sampler_name(c.sampler) << " w=" << c.width << " cos_o=" << c.cos_o << " eta=" << c.eta);
    const double lost = sampler_lost_mass(c);
    CAPTURE(lost);
    CHECK_THAT(sampler_pdf_total(c) + lost, WithinAbs(1.0, 1e-6));
    if (c.sampler == Sampler::Flux) CHECK(lost > 0.0);  // a sub-probability: facets facing away, TIR, ...
    else CHECK(lost == 0.0);
  }
}

TEST_CASE("the sphere proposal's integral fails with eta^2 dropped from the refraction's Jacobian",
          "[samplers][transmission]") {
  // The lost mass is written from the sampler's steps over the normals, the
  // density of o from Walter et al. 2007 eq. 17: a wrong Jacobian in the
  // density does not cancel against it. Planted: eq. 17 without its η_o²
  // (the refracted shares of flux_mis_pdf over η²; the cosine lobe kept).
  const SamplerCase c{Sampler::Flux, 0.3, 0.7, 1.5};
  const glm::dvec3 i(std::sqrt(1 - 0.49), 0, 0.7);
  auto wrong = [&](const glm::dvec3& o) {
    const double q = ref::flux_mis_pdf(i, o, c.width, c.eta, MFV_LOBE_ALL);
    if (o.z >= 0) return q;
    const double cosine = 0.5 / 32 * -o.z / M_PI;  // the defensive cosine lobe's share below
    return cosine + (q - cosine) / (c.eta * c.eta);
  };
  const double lost = sampler_lost_mass(c), right = sampler_pdf_total(c), planted = flux_pdf_total(c, wrong);
  CAPTURE(lost, right, planted);
  CHECK_THAT(right + lost, WithinAbs(1.0, 1e-6));
  CHECK(std::fabs(planted + lost - 1.0) > 1e-2);
}

TEST_CASE("reference samplers pass the chi-square test and a 10 percent wrong width fails it", "[samplers]") {
  SamplersOptions opt;
  opt.samples = 1u << 18;
  const double level = sidak_level(0.01, int(default_sampler_cases().size()));
  for (const auto& c : default_sampler_cases()) {
    if (c.sampler == Sampler::Cosine) continue;
    INFO(sampler_name(c.sampler) << " w=" << c.width << " cos_o=" << c.cos_o << " eta=" << c.eta);
    const auto draws = reference_draws(c, opt.samples, 3);
    const SamplerResult ok = test_draws(c, draws, opt, level);
    CAPTURE(ok.chi2, ok.dof, ok.p_value, ok.lost);
    CHECK(ok.fit_ok);
    CHECK((ok.lost == 0) == (c.sampler != Sampler::Flux));  // the sphere proposal loses draws (its lost mass)
    SamplerCase wrong = c;  // the pdf of another width than the draws'
    wrong.width *= 1.1;
    CHECK(!test_draws(wrong, draws, opt, level).fit_ok);
  }
}

namespace {
std::string line_starting(const std::string& out, const std::string& prefix) {
  size_t p = out.find("\n" + prefix);
  if (p == std::string::npos) return "";
  return out.substr(p + 1, out.find('\n', p + 1) - p - 1);
}

// mfv samplers on device draws only, with `from` replaced by `to` in estimators.cl (the proposals).
mfv::test::Run planted_samplers(const std::string& from, const std::string& to) {
  const mfv::test::PlantedKernelDir dir("estimators.cl", from, to);
  return mfv::test::run_mfv("--kernel-dir " + dir.path() + " samplers --samples 262144 --device-only");
}
}  // namespace

TEST_CASE("mfv samplers passes on the device and planted sampler defects fail it", "[samplers][cli]") {
  auto ok = mfv::test::run_mfv("samplers --samples 262144");
  INFO(ok.out);
  REQUIRE(ok.code == 0);
  CHECK(ok.out.find("22 of 22 sampler tests pass") != std::string::npos);

  // the Cauchy slopes' inverse CDF turned into GGX's (sqrt(u/(1-u))): pdf_m no longer matches
  auto bad = planted_samplers("sqrt(u_r * (R(2.0) - u_r))", "sqrt(u_r * (R(1.0) - u_r))");
  INFO(bad.out);
  CHECK(bad.code == 1);
  // both mixtures and the slopes alone fail; the cosine lobe and visible normals still pass
  // (the sphere proposal's defensive slopes, 1/32 of its draws, fail it at eta 1.5:
  // measured p 8e-12 at w = 0.3, 6e-4 at w = 0.8 against the level 9e-4, so not counted here)
  CHECK(bad.out.find("of 11 sampler tests pass") != std::string::npos);
  for (const char* f : {"mixture            0.2", "mixture            0.8", "cauchy_slopes"})
    CHECK(line_starting(bad.out, f).find("FAIL") != std::string::npos);
  CHECK(line_starting(bad.out, "cosine").find("pass") != std::string::npos);
  CHECK(line_starting(bad.out, "visible_normals").find("pass") != std::string::npos);

  // visible normals drawn for the unstretched view (a classic slip): vis_pdf_i no longer matches
  // (sample_vis_c is sample_vis_aniso_c at wx = wy = w)
  auto bad2 = planted_samplers("real ox = wx * vx, oy = wy * vy, oz = vz;", "real ox = vx, oy = vy, oz = vz;");
  INFO(bad2.out);
  CHECK(bad2.code == 1);
  // at w = 1 stretching is the identity, so only the two w = 0.3 cases can see it, and the
  // sphere proposal's 4 cases (15/16 of their draws are visible normals)
  CHECK(bad2.out.find("5 of 11 sampler tests pass") != std::string::npos);

  // the sphere proposal refracting with eta inverted: its 4 cases fail (chi2 1.9e5 to 4.4e6), no other
  const auto& plant = mfv::test::kFluxRefractEtaInverted;
  const mfv::test::PlantedKernelDir dir = mfv::test::planted(plant);
  auto bad3 = mfv::test::run_mfv("--kernel-dir " + dir.path() + " samplers --samples 262144 --device-only");
  INFO(plant.name << "\n" << bad3.out);
  CHECK(bad3.code == 1);
  CHECK(bad3.out.find("7 of 11 sampler tests pass") != std::string::npos);
  CHECK(line_starting(bad3.out, "bsdf_flux_sphere").find("FAIL") != std::string::npos);
}
