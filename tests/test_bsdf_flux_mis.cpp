// bsdf_furnace's flux estimator (IntegralKind::BsdfFlux, kernels/transmission.cl
// bsdf_flux_mis): visible normals of the GGX shape at i, reflected or
// refracted by the lobe (or, over the whole sphere, by the estimator's own
// Fresnel), Cauchy slopes and the cosine lobe by multi-sample MIS on
// randomized-QMC replicates. The kernel and its double twin
// (host/reference/transmission.cpp flux_mis) agree on identical Philox
// points in every share, lobe and side; run() takes the points
// sample_values takes; the replicates' spread is far below the iid one.
#include "abi/integral.h"
#include "catalog/bsdfs.hpp"
#include "checks/integrate.hpp"
#include "device_fixture.hpp"
#include "reference/reference.hpp"
#include "runtime/dispatch.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace mfv;

namespace {

IntegralSpec flux_spec(const char* bsdf, double alpha, double eta, int side, uint32_t lobe, double mu,
                       uint32_t stream) {
  const Bsdf* b = try_find_bsdf(bsdf);
  REQUIRE(b);
  MicrofacetIntegral mi;
  mi.kind = IntegralKind::BsdfFlux;
  mi.d = b->d, mi.g = b->g;
  mi.pd = alpha, mi.pg = alpha;
  mi.width = alpha;
  mi.cos_o = mu;
  IntegralSpec s = spec_of(mi);
  s.eta = float(eta);
  s.side = side;
  s.bsdf = b->code();
  s.lobe = lobe;
  s.stream = stream;
  return s;
}

TermSelection selection() {
  const Bsdf* b = try_find_bsdf("walter_ggx_correlated");
  TermSelection sel;
  sel.d = {b->d};
  sel.g = {b->g};
  sel.f = {&find_term("none")};
  return sel;
}

}  // namespace

TEST_CASE("bsdf_furnace's flux: kernel and double twin agree on identical points in every share, lobe and side",
          "[integrate][device][transmission][mis]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  Integrator in(*rt, selection());
  const char* c = "walter_ggx_correlated";
  const char* s = "walter_ggx_separable";
  std::vector<IntegralSpec> specs = {
      flux_spec(c, 0.3, 1.5, MFV_SIDE_ABOVE, MFV_LOBE_REFLECT, 0.5, 0),
      flux_spec(c, 0.3, 1.5, MFV_SIDE_ABOVE, MFV_LOBE_TRANSMIT, 0.5, 1),
      flux_spec(c, 0.3, 1.5, MFV_SIDE_ABOVE, MFV_LOBE_ALL, 0.5, 2),  // the side by the estimator's Fresnel
      flux_spec(c, 0.8, 3.0, MFV_SIDE_BELOW, MFV_LOBE_TRANSMIT, 0.9, 3),  // leaving, past the critical angle
      flux_spec(c, 0.8, 3.0, MFV_SIDE_BELOW, MFV_LOBE_ALL, 0.2, 4),
      flux_spec(s, 0.05, 1.33, MFV_SIDE_BELOW, MFV_LOBE_REFLECT, 0.05, 5),  // grazing, near the critical angle
      flux_spec(s, 1e-3, 2.0, MFV_SIDE_ABOVE, MFV_LOBE_TRANSMIT, 1.0, 6),   // sharp, normal incidence
  };
  in.stratify(specs, 1 << 12);
  // 20 points a replicate (16 visible normals, 2 slopes, 2 cosine): 320 values cover 16 replicates and every share
  for (auto& sp : specs) sp.points = 20;
  for (const auto& a : compare_with_reference(in, specs, 320, 5)) {
    INFO("kernel " << a.kernel_mean << " reference " << a.reference_mean);
    CHECK(a.kernel_mean > 0);
    CHECK(a.disagreement < 2e-5);  // float against double on identical points: rounding only (as AlbedoMis)
  }
}

TEST_CASE("bsdf_furnace's flux: run() takes sample_values' points and its replicate spread is far below the iid one",
          "[integrate][device][transmission][mis]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  Integrator in(*rt, selection());
  std::vector<IntegralSpec> one = {
      flux_spec("walter_ggx_correlated", 0.3, 1.5, MFV_SIDE_ABOVE, MFV_LOBE_TRANSMIT, 0.5, 0)};
  const auto est = in.run(one, 1 << 12, 9);
  const uint32_t n = in.mis_points(1 << 12);
  in.stratify(one, 1 << 12);
  const auto all = in.sample_values(one, n * kMisReplicates, 9);
  double sum = 0, sq = 0;
  for (float v : all) sum += v, sq += double(v) * v;
  const double mean = sum / all.size(), sd = std::sqrt(sq / all.size() - mean * mean);
  CHECK(est[0].samples == uint64_t(n) * kMisReplicates);
  CHECK(est[0].dof == kMisReplicates - 1);
  CHECK(std::fabs(est[0].mean - mean) < 1e-6);
  // the points' own spread over sqrt(N) is what an iid estimate of these points would report; the
  // replicates' (the verdict's) is measured 40-100x below it here (RQMC on a smooth integrand)
  INFO("replicate SE " << est[0].stderr_ << ", iid SE of the same points " << sd / std::sqrt(double(all.size())));
  CHECK(est[0].stderr_ < 0.1 * sd / std::sqrt(double(all.size())));
}

TEST_CASE("bsdf_furnace's flux at eta = 100 and 1/100: the smooth limit E_R = F(mu), E_T = 1 - F(mu) within total SE",
          "[integrate][device][transmission][mis]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  Integrator in(*rt, selection());
  std::vector<IntegralSpec> specs;
  const double mus[] = {0.05, 0.3, 1.0};
  for (int side : {MFV_SIDE_ABOVE, MFV_SIDE_BELOW})
    for (double mu : mus)
      for (uint32_t lobe : {MFV_LOBE_REFLECT, MFV_LOBE_TRANSMIT})
        specs.push_back(flux_spec("walter_ggx_correlated", 1e-4, 100.0, side, lobe, mu, uint32_t(specs.size())));
  const auto est = in.run(specs, 1 << 14, 3);
  for (size_t j = 0; j < specs.size(); ++j) {
    const IntegralSpec& s = specs[j];
    const double mu = s.cos_o, eta = s.side == MFV_SIDE_ABOVE ? 100.0 : 0.01;
    const double F = ref::F_dielectric(mu, eta, 0.0), closed = s.lobe == MFV_LOBE_REFLECT ? F : 1.0 - F;
    // the smooth interface less the masking at alpha = 1e-4 (4 Lambda(mu), as the smooth-limit test of
    // test_transmission_checks.cpp) and, under total internal reflection, the D's tail past the critical
    // angle (E_T <= 1e-6 here: facets tilted by ~0.01 at alpha = 1e-4); t(31) at 1e-4 two-sided: 4.6
    const double a = mu / (1e-4 * std::sqrt(std::max(1e-300, 1.0 - mu * mu)));
    const double lambda = mu >= 1.0 ? 0.0 : 0.5 * (std::sqrt(1.0 + 1.0 / (a * a)) - 1.0);
    CAPTURE(mu, eta, s.lobe, closed, est[j].mean, est[j].stderr_);
    REQUIRE(std::isfinite(est[j].mean));
    CHECK(std::fabs(est[j].mean - closed) <= 4.6 * est[j].stderr_ + 4.0 * lambda + (F == 1.0 ? 1e-6 : 0.0) + 1e-6);
  }
  // the double twin on the same points (every share): h_t = -(i + eta o) stays well conditioned at
  // |eta - 1| >> 0, so kernel and twin agree to rounding
  for (auto& sp : specs) sp.points = 20;
  for (const auto& a : compare_with_reference(in, specs, 320, 5)) {
    INFO("kernel " << a.kernel_mean << " reference " << a.reference_mean);
    CHECK(a.disagreement < 2e-5);
  }
}
