// The verdict statistics (host/stats/, docs/statistics.md): quantiles,
// the pooled test's power and false-alarm rate, total uncertainty; the
// planted 1 % energy gain the default suite must fail (mfv check's is in
// tests/test_check.cpp); calibration of the
// total uncertainty over cells whose truth is known.
#include "checks/energy.hpp"
#include "checks/suite.hpp"
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "runtime/integrator.hpp"
#include "stats/normal.hpp"
#include "stats/verdict.hpp"
#include "suite_verdicts.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>

using namespace mfv;
using Catch::Matchers::WithinRel;

namespace {

// P(|z| > 3) under the normal law.
const double kBeyond3 = stats::normal_two_sided_tail(3.0);

}  // namespace

TEST_CASE("Normal and binomial quantiles match tabulated values", "[stats]") {
  CHECK_THAT(stats::normal_two_sided_quantile(0.05), WithinRel(1.959963985, 1e-9));
  CHECK_THAT(stats::normal_upper_quantile(0.05), WithinRel(1.644853627, 1e-9));
  CHECK_THAT(stats::normal_two_sided_quantile(1e-6 / 1e5),
             WithinRel(6.8065, 1e-4));  // the 6.8 at 1e-6 over 10^5 tests
  CHECK_THAT(stats::normal_two_sided_tail(3.0), WithinRel(0.002699796063, 1e-9));
  CHECK_THAT(stats::normal_two_sided_quantile(1e-3), WithinRel(3.290526731, 1e-9));
  // Binomial(100, 0.5): P(X > 65) = 0.00089 <= 1e-3 < P(X > 64) = 0.00176
  CHECK(stats::binomial_upper_bound(100, 0.5, 1e-3) == 65);
  CHECK(stats::binomial_lower_bound(100, 0.5, 1e-3) == 35);
}

TEST_CASE("The float rounding bound is gamma_128 in float plus gamma_n of the double sum", "[stats]") {
  // 128 u / (1 - 128 u), u = 2^-24: 7.63e-6 relative
  CHECK_THAT(stats::float_rounding_bound(1.0, 1, true), WithinRel(7.6294e-6, 1e-4));
  CHECK_THAT(stats::float_rounding_bound(-2.0, 1, true), WithinRel(2 * 7.6294e-6, 1e-4));
  // a float sum of 2^20 values: gamma_n is 2^20 u / (1 - 2^20 u) = 0.0667
  CHECK(stats::float_rounding_bound(1.0, 1 << 20, false) > 0.066);
  CHECK(stats::total_uncertainty(1e-3, -2e-3) == 3e-3);
}

TEST_CASE("The pooled test finds a 1 % gain common to the grid that no single integral shows", "[stats]") {
  // 96 integrals each 1 % high with a standard error of 1 %: every z is 1,
  // far below a Bonferroni threshold; the mean is 1 % with SE 0.1 %, z = 9.8.
  std::vector<stats::Deviation> gain(96, {0.01, 0.01, 0.0}), none(96, {0.0, 0.01, 0.0});
  const double z_single = stats::per_integral_threshold(5e-7, 10000);
  CHECK(0.01 / 0.01 < z_single);
  stats::Pooled up = stats::pooled_test(gain, true, 5e-7, 100);
  CHECK(up.failed);
  CHECK_THAT(up.mean, WithinRel(0.01, 1e-12));
  CHECK_THAT(up.se, WithinRel(0.01 / std::sqrt(96.0), 1e-12));
  CHECK_FALSE(stats::pooled_test(none, true, 5e-7, 100).failed);
  // one-sided: a loss never fails an upper limit; two-sided it does
  std::vector<stats::Deviation> loss(96, {-0.01, 0.01, 0.0});
  CHECK_FALSE(stats::pooled_test(loss, true, 5e-7, 100).failed);
  CHECK(stats::pooled_test(loss, false, 5e-7, 100).failed);
  // a bias bound as large as the gain absorbs it
  std::vector<stats::Deviation> biased(96, {0.01, 0.01, 0.01});
  CHECK_FALSE(stats::pooled_test(biased, true, 5e-7, 100).failed);
  // non-finite deviations fail; an empty group passes
  CHECK(stats::pooled_test({{NAN, 0.01, 0}}, false, 0.01, 1).failed);
  CHECK_FALSE(stats::pooled_test({}, false, 0.01, 1).failed);
}

TEST_CASE("The pooled test keeps its false-alarm rate on skewed integrands with estimated standard errors", "[stats]") {
  // 4000 groups of 32 integrals, each the mean of 256 lognormal samples
  // (heavily skewed, as a grazing albedo), deviation from the true mean,
  // with the SE estimated from the same samples. At alpha = 0.05 per test
  // the count of false alarms must stay within its binomial bound.
  std::mt19937_64 rng(11);
  std::lognormal_distribution<double> ln(0.0, 1.0);
  const double truth = std::exp(0.5);
  const int groups = 4000;
  int two = 0, one = 0;
  for (int g = 0; g < groups; ++g) {
    std::vector<stats::Deviation> d;
    for (int i = 0; i < 32; ++i) {
      double s = 0, ss = 0;
      for (int k = 0; k < 256; ++k) {
        double x = ln(rng);
        s += x;
        ss += x * x;
      }
      double mean = s / 256, var = (ss / 256 - mean * mean) * 256 / 255;
      d.push_back({mean - truth, std::sqrt(var / 256), 0.0});
    }
    two += stats::pooled_test(d, false, 0.05, 1).failed;
    one += stats::pooled_test(d, true, 0.05, 1).failed;
  }
  CAPTURE(two, one);
  CHECK(uint64_t(two) <= stats::binomial_upper_bound(groups, 0.05, 1e-4));
  CHECK(uint64_t(one) <= stats::binomial_upper_bound(groups, 0.05, 1e-4));
  CHECK(uint64_t(two) >= stats::binomial_lower_bound(groups, 0.05, 1e-4));  // not conservative to uselessness
}

TEST_CASE("A D x G x F BRDF with 1 % more energy fails the default suite", "[device][suite][planted]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  SuiteOptions opt;  // default samples
  opt.checks = {"furnace", "energy"};
  opt.models = {"ggx/smith_ggx_correlated"};
  opt.reference_samples = 0;  // the statistics alone
  SuiteReport good = run_suite(*rt, opt);
  CHECK(good.gate_ok());
  test::check_planted_fails("brdf.cl", "return kd * MFV_INV_PI + spec / (R(4.0) * NoL) / NoV;",
                            "return kd * MFV_INV_PI + R(1.01) * spec / (R(4.0) * NoL) / NoV;", opt, "furnace",
                            "ggx/smith_ggx_correlated/none");
}

TEST_CASE("Over cells of known truth the share beyond 3 total uncertainties is what the normal law allows",
          "[device][suite][calibration]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  // Known truth: d_norm of every proper D (= 1), masking of D with its own
  // exact Smith G1 (= 1), closed-form albedos of whole models (Lambert,
  // Oren-Nayar, EON, ...), at tolerance 0. z = dev / (SE + bias bound).
  uint64_t n = 0, beyond3 = 0, sharp = 0, beyond1_sharp = 0;
  for (uint64_t seed : {3}) {
    SuiteOptions opt;
    opt.seed = seed;
    opt.scale = 0.5;  // half the samples: the CI budget; the share beyond 3 does not depend on it
    opt.checks = {"d_norm", "masking", "closed_form"};
    opt.reference_samples = 0;
    SuiteReport rep = run_suite(*rt, opt);
    for (auto& p : rep.points) {
      if (p.bounded || p.expect != Expect::Hold || p.tolerance > 0) continue;
      ++n;
      beyond3 += !(std::fabs(p.z) <= 3);
      if (p.bias < 0.1 * p.stderr_ && p.check != "d_norm") {  // iid, SE-dominated: z ~ N(0, 1/1.1²)
        ++sharp;
        beyond1_sharp += std::fabs(p.z) > 1;
      }
    }
  }
  CAPTURE(n, beyond3, sharp, beyond1_sharp);
  WARN("calibration: " << beyond3 << " of " << n << " known-truth cells beyond 3 total SE; " << beyond1_sharp << " of "
                       << sharp << " SE-dominated cells beyond 1");
  REQUIRE(n > 1000);
  // A count of events of probability <= P(|Z| > 3) exceeds this bound with chance 1e-4.
  CHECK(beyond3 <= stats::binomial_upper_bound(n, kBeyond3, 1e-4));
  // Not inflated: where the SE dominates, |z| > 1 is as common as |Z| > 1.1 (bias <= SE/10).
  REQUIRE(sharp > 200);
  CHECK(beyond1_sharp >= stats::binomial_lower_bound(sharp, stats::normal_two_sided_tail(1.1), 1e-4));
  CHECK(beyond1_sharp <= stats::binomial_upper_bound(sharp, stats::normal_two_sided_tail(1.0), 1e-4));
}

TEST_CASE("Over the furnace's cells of known truth the share beyond 3 replicate SEs is what Student's t allows",
          "[device][suite][calibration][mis]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  // The furnace's albedo integrals (AlbedoMis: MIS on Owen-scrambled Sobol
  // replicates, SE from 32 replicates) against the double reference's
  // quadrature (checks/furnace_truth.hpp) at default samples, three D x G
  // pairs, grazing to normal views. z = dev / (SE + bias + quadrature error);
  // the SE has 31 degrees of freedom.
  SuiteOptions opt;
  opt.seed = 5;
  opt.checks = {"furnace"};
  opt.models = {"ggx/smith_ggx_correlated", "beckmann/smith_beckmann", "ggx/smith_ggx"};
  opt.reference_samples = 0;
  SuiteReport rep = run_suite(*rt, opt);
  uint64_t n = 0, beyond3 = 0, beyond1 = 0;
  for (auto& p : rep.points) {
    if (!p.known || p.expect != Expect::Hold || p.dof == 0) continue;
    const double z = (p.estimate - p.known_value) / (p.stderr_ + p.bias + p.known_error);
    ++n;
    beyond3 += !(std::fabs(z) <= 3);
    beyond1 += std::fabs(z) > 1;
  }
  CAPTURE(n, beyond3, beyond1);
  WARN("furnace calibration: " << beyond3 << " of " << n << " known-truth cells beyond 3 total SE, " << beyond1
                               << " beyond 1");
  REQUIRE(n > 500);
  const double t3 = stats::student_t_two_sided_p(3.0, kMisReplicates - 1);
  CHECK(beyond3 <= stats::binomial_upper_bound(n, t3, 1e-4));
  // not inflated to uselessness: |z| > 1 at least as common as |t| > 1.5 (a bias bound and quadrature
  // error that dominated the SE would push the share far below)
  CHECK(beyond1 >= stats::binomial_lower_bound(n, stats::student_t_two_sided_p(1.5, kMisReplicates - 1), 1e-4));
}

TEST_CASE("mfv energy's pilot-sized estimates have honest standard errors against EON's closed form",
          "[device][energy][calibration]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  // EON's albedo is known exactly (Portsmouth et al. 2025); with adaptive
  // stopping 5 of 96 cells were beyond 3 SE (worst 5.4).
  uint64_t n = 0, beyond3 = 0;
  for (uint64_t seed : {1, 2, 3}) {
    EnergyOptions o;
    o.tables = false;
    o.models = {"eon"};
    o.seed = seed;
    o.reference_samples = 0;
    EnergyReport rep = run_energy(*rt, o);
    for (auto& me : rep.models)
      for (size_t m = 0; m < me.E.size(); ++m) {
        const double truth = me.point.model->ref_albedo(rep.mu[m], me.point.p.data());
        const double u = stats::total_uncertainty(me.E[m].se, stats::float_rounding_bound(truth, me.points[m]));
        ++n;
        // the replicate SE has R - 1 = 7 degrees of freedom: Student t, not normal
        beyond3 += std::fabs(me.E[m].mean - truth) / u > 3;
      }
  }
  CAPTURE(n, beyond3);
  REQUIRE(n >= 96);
  // P(|t_7| > 3) = 0.0199
  CHECK(beyond3 <= stats::binomial_upper_bound(n, stats::student_t_two_sided_p(3.0, 7), 1e-4));
}
