// mfv check: what its integrals can conclude (issue 28 item 3). An estimate
// that rests on a handful of effective samples (a narrow lobe the proposal
// never reached: 0.008 ± 0.008 for a D that integrates to 1.0074) is
// "inconclusive", neither pass nor fail; and each upper-limit check states
// the gain it detects with probability 0.95 (docs/cli/check.md "Power").
#pragma once

#include "checks/suite.hpp"

#include <cstdint>
#include <string>

namespace mfv {

// Kish's effective sample size of a mean `mean` ± `se` over n samples,
// n m² / (m² + n se²) (= (m / se)² for large n: the estimate's own squared
// signal-to-noise ratio); n where se = 0 (every sample equal).
double effective_samples(double mean, double se, uint64_t n);

// Below this many effective samples an integral is inconclusive: its
// relative standard error exceeds 1/4, so the mean rests on a few draws and
// its standard error is itself an estimate from those few (the z-test's
// normal approximation does not hold). Correct models over mfv check's
// grids measure 100 and more (docs/cli/check.md).
constexpr double kMinEffectiveSamples = 16;

// An estimate this small against the expected value (with its standard
// error) is negligible however few samples carry it: with a few hits of a
// lobe the estimate is of the lobe's order, so the lobe cannot move a
// verdict (f0 = 0 at normal view: E ~ 1e-9 on a handful of samples).
constexpr double kNegligible = 1e-3;

// Marks the integral points of rep.points[first..] below the minimum
// inconclusive, unless negligible, with their reason in `detail`. Before
// judge().
void mark_inconclusive(SuiteReport& rep, size_t first);

// Per-point sample sizing (issue 28): the samples an upper-limit point needs
// so that a 5 % gain at it is detected with probability 0.95 at the
// per-integral threshold z. Its pass of n samples measured the standard
// error se, which falls as 1/sqrt(n), so n ((z + 1.645) se / (0.05 |E| - b))^2,
// b its float rounding bound, rounded up to n times a power of 2. n where the
// pass already has the power; at most kMaxSizing n, which a gain the bias
// alone hides (b >= 0.05 |E|), or a lobe the estimator does not reach, is
// also given (the power statement then names the point).
constexpr uint64_t kMaxSizing = 64;
uint64_t samples_for_power(const PointResult& p, double z);

// After judge(): for the upper-limit checks (furnace, energy), the gain each
// detects with probability 0.95 at the run's threshold, (z + 1.645) SE +
// bias, at its least powerful point, and at how many points a 5 % gain is
// detected so; one line per check.
std::string power_statement(const SuiteReport& rep);

}  // namespace mfv
