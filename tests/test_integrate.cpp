// Integrator::run's fast path for isotropic microfacet albedo integrals
// (kernels/albedo.cl albedo_values + sum_values) takes the samples the
// general `integrate` kernel takes and gives the same estimates: over
// several D x G x F, grazing and normal views, tiny widths, diffuse kd,
// launches split along the sample axis, and later passes (first_index > 0);
// likewise d_norm, masking and mfv energy's RQMC albedo and E_avg.
#include "albedo_spec.hpp"
#include "catalog/catalog.hpp"
#include "catalog/roughness.hpp"
#include "checks/integrate.hpp"
#include "device_fixture.hpp"
#include "runtime/dispatch.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace mfv;

namespace {

IntegralSpec albedo(const std::string& d, const std::string& g, const std::string& f, double alpha, double cos_o,
                    double f0, double kd, uint32_t stream) {
  return test::albedo_spec(d, g, f, alpha, cos_o, f0, kd, stream);
}

void require_same(const std::vector<Estimate>& fast, const std::vector<Estimate>& general) {
  REQUIRE(fast.size() == general.size());
  for (size_t i = 0; i < fast.size(); ++i) {
    INFO("integral " << i << ": fast " << fast[i].mean << " +- " << fast[i].stderr_ << ", general " << general[i].mean
                     << " +- " << general[i].stderr_);
    CHECK(fast[i].samples == general[i].samples);
    // the same float samples, summed in double in another order
    CHECK(std::fabs(fast[i].mean - general[i].mean) <= 1e-12 * std::max(1.0, std::fabs(general[i].mean)));
    CHECK(std::fabs(fast[i].stderr_ - general[i].stderr_) <= 1e-9 * std::max(1e-6, general[i].stderr_));
  }
}

}  // namespace

TEST_CASE("the albedo fast path gives the general kernel's estimates", "[integrate][device]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  TermSelection sel;
  sel.d = {&find_term("ggx"), &find_term("beckmann")};
  sel.g = {&find_term("smith_ggx_correlated"), &find_term("smith_beckmann")};
  sel.f = {&find_term("schlick"), &find_term("none")};
  Integrator in(*rt, sel);
  std::vector<IntegralSpec> specs = {
      albedo("ggx", "smith_ggx_correlated", "schlick", 0.3, 0.7, 0.04, 0.0, 0),
      albedo("ggx", "smith_ggx_correlated", "schlick", 0.01, 1e-3, 0.04, 0.0, 1),  // stiff and grazing
      albedo("ggx", "smith_ggx_correlated", "none", 1e-4, 1.0, 1.0, 0.0, 2),       // near-specular, normal view
      albedo("beckmann", "smith_beckmann", "schlick", 0.5, 0.2, 0.5, 0.3, 3),      // another pair, with kd
      albedo("ggx", "smith_beckmann", "none", 0.8, 0.05, 1.0, 0.0, 4),             // mismatched G
  };
  IntegralSpec masking = specs[0];  // masking: masking_values on the fast path
  masking.check = static_cast<int32_t>(IntegralKind::Masking);
  specs.push_back(masking);

  SECTION("one launch, and a later pass") {
    for (uint64_t first : {uint64_t(0), uint64_t(1) << 20}) {
      in.set_albedo_fast_path(true);
      const auto fast = in.run(specs, 40000, 7, first);
      in.set_albedo_fast_path(false);
      const auto general = in.run(specs, 40000, 7, first);
      require_same(fast, general);
    }
  }
  SECTION("stratified d_norm (d_norm_values + sum_pairs)") {
    std::vector<IntegralSpec> norms;
    for (auto [d, a] : {std::pair<const char*, double>{"ggx", 0.3}, {"beckmann", 1e-3}, {"ggx", 1.5}})
      norms.push_back(test::d_norm_spec(d, a, uint32_t(norms.size() + 1)));
    in.set_albedo_fast_path(true);
    const auto fast = in.run(norms, 1 << 18, 5);
    in.set_albedo_fast_path(false);
    const auto general = in.run(norms, 1 << 18, 5);
    require_same(fast, general);
  }
  SECTION("mfv energy's RQMC albedo and E_avg (albedo_rqmc_values + sum_rqmc)") {
    std::vector<IntegralSpec> rqmc;
    for (size_t i = 0; i < 5; ++i) {
      IntegralSpec a = specs[i], e = specs[i];
      a.check = static_cast<int32_t>(IntegralKind::AlbedoRqmc);
      e.check = static_cast<int32_t>(IntegralKind::EavgRqmc);  // stratified: pairs of strata
      rqmc.push_back(a);
      rqmc.push_back(e);
    }
    in.set_albedo_fast_path(true);
    const auto fast = in.run(rqmc, 40000, 9);
    in.set_albedo_fast_path(false);
    const auto general = in.run(rqmc, 40000, 9);
    REQUIRE(fast.size() == general.size());
    for (size_t i = 0; i < fast.size(); ++i) {
      INFO("integral " << i << ": fast " << fast[i].mean << " B " << fast[i].b_mean << ", general " << general[i].mean
                       << " B " << general[i].b_mean);
      CHECK(fast[i].samples == general[i].samples);
      CHECK(std::fabs(fast[i].mean - general[i].mean) <= 1e-12 * std::max(1.0, std::fabs(general[i].mean)));
      if (i % 2 == 0)  // the split sum's B (albedo), or the strata pairs' standard error (E_avg)
        CHECK(std::fabs(fast[i].b_mean - general[i].b_mean) <= 1e-12 * std::max(1.0, std::fabs(general[i].b_mean)));
      else
        CHECK(std::fabs(fast[i].stderr_ - general[i].stderr_) <= 1e-9 * std::max(1e-6, general[i].stderr_));
    }
  }
  SECTION("an integral larger than one launch (split along its samples)") {
    const std::vector<IntegralSpec> big = {specs[1]};
    in.set_albedo_fast_path(true);
    const auto fast = in.run(big, (uint64_t(1) << 22) + 4096, 3);
    in.set_albedo_fast_path(false);
    const auto general = in.run(big, (uint64_t(1) << 22) + 4096, 3);
    require_same(fast, general);
  }
}
