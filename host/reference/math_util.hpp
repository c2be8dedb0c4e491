// Private helpers of the scalar reference (host/reference/*.cpp only).
//
// Small, named guards instead of scattered clamps (STYLE.md, "Edge cases").
#pragma once

#include "util/math_constants.hpp"

#include <algorithm>

namespace mfv::ref::detail {

using ::mfv::kPi;  // util/math_constants.hpp

// Clamp a cosine into [0, 1].  Dot products of unit vectors can round a few
// ULP outside [-1, 1]; the terms below are defined on [0, 1].
inline double saturate(double x) { return std::clamp(x, 0.0, 1.0); }

// sin²θ from cosθ, as (1 − c)(1 + c): for c near 1 the subtraction 1 − c is
// exact (Sterbenz), so this keeps full relative precision where 1 − c² would
// cancel.  c is clamped into [0, 1] first, so the result lies in [0, 1].
inline double sin2_from_cos(double c) {
  c = saturate(c);
  return (1.0 - c) * (1.0 + c);
}

// tan²θ = sin²θ / cos²θ, robust near c = 1 (see sin2_from_cos).  A cosine that
// rounded above 1 is treated as exactly 1, i.e. tan²θ = 0.  Precondition
// c > 0: for c → 0⁺ the result grows to +inf (c² underflows below ~1e-162);
// callers that can reach that range say how they handle it.
inline double tan2_from_cos(double c) {
  c = saturate(c);
  return sin2_from_cos(c) / (c * c);
}

}  // namespace mfv::ref::detail
