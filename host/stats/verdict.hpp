// The statistics behind every verdict (docs/statistics.md): the total
// uncertainty of an estimate, the per-integral test, the pooled test of a
// model x check group, and the split of the run's family-wise false-alarm
// rate between the two families of tests.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mfv::stats {

// ---- total uncertainty ----------------------------------------------------

// A bound on the bias float rounding puts into a Monte Carlo mean of
// non-negative samples (the suite takes the larger of this and the fp64
// twin's measurement, PointResult::rounding_bound).
//
// Each sample is formed in float32 by at most kFloatOps rounded operations
// (the longest catalog path: the sample mapping, D, two Smith Lambdas, F and
// the proposal pdf, a transcendental counted as 4 for OpenCL's 4-ulp budget
// of exp, log, pow, sqrt), so its relative error is at most
// gamma_k = k u / (1 - k u), u = 2^-24 (Higham 2002, Lemma 3.1), and the mean
// of n such samples is off by at most gamma_k E|f| = gamma_k |mean| for
// f >= 0. The sum of the n samples in double (kernels/integrate.cl acc_t)
// adds gamma_n with u = 2^-53 (Higham 2002, eq. 4.4); in float, u = 2^-24.
// 128 operations: 7.6e-6 relative; measured float biases are below 1e-6
// (beckmann_ct82 d_norm: 1.4e-7).
constexpr int kFloatOps = 128;
double float_rounding_bound(double mean, uint64_t samples, bool double_accumulation = true);

// The total uncertainty of an estimate with standard error `se` and a bias
// bounded by `bias` (rounding and documented approximation): se + bias.
// A bias bound adds linearly: with |E dev| <= b, for every k >= 1,
// P(|dev| > k (se + b)) <= P(|N(0, se)| > k se + (k - 1) b) <= P(|Z| > k),
// so z = dev / (se + b) is never wider than the normal law (the calibration
// test checks the share beyond 3).
double total_uncertainty(double se, double bias);

// ---- the families of tests --------------------------------------------------

// The run's family-wise false-alarm rate split between the per-integral
// z-tests and the pooled tests, half each (Bonferroni across the two
// families, then within each): P(any false alarm) <= a/2 + a/2 = a.
struct FamilySplit {
  double per_integral = 0, pooled = 0;
};
FamilySplit split_family_alpha(double family_alpha);

// The z a per-integral test must exceed: two-sided Bonferroni over `tests`
// (an upper-only test at the same threshold has half the false-alarm rate).
double per_integral_threshold(double alpha, size_t tests);

// ---- the pooled test of a group ---------------------------------------------

// One integral's deviation from what a correct model gives.
struct Deviation {
  double dev = 0;   // estimate - expected
  double se = 0;    // its standard error
  double bias = 0;  // bound on its systematic part (rounding + documented tolerance)
};

// The equal-weight mean deviation of a group's integrals, dbar = sum(dev)/n,
// with SE = sqrt(sum se^2)/n (independent streams) and bias bound
// B = sum(bias)/n. Equal weights, not inverse-variance ones: the standard
// errors are estimated from the same samples as the means, and for skewed
// integrands (grazing albedo) a small mean comes with a small SE, so
// weights 1/se^2 would bias dbar downwards by a share of its SE that grows
// like sqrt(n). Against a deviation common to the grid (a 1 % gain) dbar
// keeps the full 1 % while its noise falls like 1/sqrt(n).
struct Pooled {
  size_t n = 0;
  double mean = 0, se = 0, bias = 0;
  double z = 0;          // mean / (se + bias)
  double threshold = 0;  // z the test needed beyond the bias: fail if mean > threshold * se + bias
  bool upper_only = false;
  bool failed = false;
};
// upper_only: the expectation is an upper limit (energy <= 1): one-sided.
// A non-finite deviation fails. n = 0 gives a pooled result that passes.
Pooled pooled_test(const std::vector<Deviation>& devs, bool upper_only, double alpha, size_t pooled_tests);

}  // namespace mfv::stats
