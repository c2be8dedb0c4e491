// mfv check's double twin of the user's code (issue 28 item 2): the same
// files compiled with every float type double (kernels/user_prelude.cl,
// -DMFV_USER_TWIN) and their floating literals without the f suffix. On
// identical samples, kf - kd is the float rounding of the user's code and
// nothing else: mfv forms directions and cosines in double and rounds them
// once to float (kernels/user_brdf.cl), so it adds no rounding of its own.
// kf - kd bounds each integral's rounding bias as mfv run's twin does for the
// catalog (checks/reference_compare.hpp), and agree judges the twin against
// the claimed model, so that a verdict says "formula error" or "float
// conditioning (within the derived bound)" (docs/cli/check.md).
#pragma once

#include "checks/suite.hpp"
#include "user/user_brdf.hpp"

#include <string>
#include <vector>

namespace mfv {

// `text` (a translated user source) with every decimal floating literal's
// f suffix removed, #define bodies included: the twin computes its
// constants in double. Line for line.
std::string twin_text(const std::string& path, const std::string& text);

// The user's files as the twin reads them.
UserBrdf twin_of(const UserBrdf& u);

// Samples per integral on which kf and kd are compared (as mfv run's twin).
constexpr uint32_t kTwinSamples = 256;

// The rounding bias bound of each integral of `specs` (their streams set
// and stratified as integrated): |mean(kf - kd)| + 3 sd(kf - kd)/sqrt(n) over
// its first n samples (spread over the strata of a stratified one), from
// the float program `f` and the twin `d`, both MFV_DOUBLE builds (their
// sample_values are double). Samples where either is not finite are left
// out: a NaN of the float code fails its integral and the census by itself.
std::vector<double> twin_rounding(Runtime& rt, const cl::Program& f, const cl::Program& d,
                                  const std::vector<IntegralSpec>& specs, uint32_t n, uint64_t seed);

// After judge(): each integral point the twin measured gets a detail that
// names its verdict's cause: a pass whose deviation is beyond noise but
// within the measured rounding, "float conditioning (within the derived
// bound)"; a failure, "formula error" (beyond noise and the rounding).
void explain_twin_verdicts(SuiteReport& rep, double z_threshold);

}  // namespace mfv
