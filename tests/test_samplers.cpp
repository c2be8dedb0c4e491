// mfv samplers: the chi-square machinery, the pdf quadratures, the
// reference samplers against their pdfs, and the device samplers passing and
// failing on planted defects (PlantedKernelDir).
#include "checks/chi_square.hpp"
#include "checks/samplers.hpp"
#include "kernel_dir.hpp"
#include "numeric/quadrature.hpp"
#include "run_mfv.hpp"

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
  for (const auto& c : cases) {
    INFO(sampler_name(c.sampler) << " w=" << c.width << " cos_o=" << c.cos_o);
    CHECK_THAT(sampler_pdf_total(c), WithinAbs(1.0, 1e-6));
  }
}

TEST_CASE("reference samplers pass the chi-square test and a 10 percent wrong width fails it", "[samplers]") {
  SamplersOptions opt;
  opt.samples = 1u << 18;
  const double level = sidak_level(0.01, 8);
  for (const auto& c : default_sampler_cases()) {
    if (c.sampler == Sampler::Cosine) continue;
    INFO(sampler_name(c.sampler) << " w=" << c.width << " cos_o=" << c.cos_o);
    const auto draws = reference_draws(c, opt.samples, 3);
    const SamplerResult ok = test_draws(c, draws, opt, level);
    CHECK(ok.fit_ok);
    CHECK(ok.lost == 0);
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
  CHECK(ok.out.find("14 of 14 sampler tests pass") != std::string::npos);

  // the Cauchy slopes' inverse CDF turned into GGX's (sqrt(u/(1-u))): pdf_m no longer matches
  auto bad = planted_samplers("sqrt(u_r * (R(2.0) - u_r))", "sqrt(u_r * (R(1.0) - u_r))");
  INFO(bad.out);
  CHECK(bad.code == 1);
  // both mixtures and the slopes alone fail; the cosine lobe and visible normals still pass
  CHECK(bad.out.find("4 of 7 sampler tests pass") != std::string::npos);
  CHECK(line_starting(bad.out, "cosine").find("pass") != std::string::npos);
  CHECK(line_starting(bad.out, "cauchy_slopes").find("FAIL") != std::string::npos);

  // visible normals drawn for the unstretched view (a classic slip): vis_pdf_i no longer matches
  // (sample_vis_c is sample_vis_aniso_c at wx = wy = w)
  auto bad2 = planted_samplers("real ox = wx * vx, oy = wy * vy, oz = vz;", "real ox = vx, oy = vy, oz = vz;");
  INFO(bad2.out);
  CHECK(bad2.code == 1);
  // at w = 1 stretching is the identity, so only the two w = 0.3 cases can see it
  CHECK(bad2.out.find("5 of 7 sampler tests pass") != std::string::npos);
}
