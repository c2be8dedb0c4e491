// The pointwise harness shared by mfv agree, mfv eval, mfv stability and the
// census and agreement of mfv check: the record layout (kernels/abi/
// pointwise.h, the same header the kernels include) and one accounting of a
// kernel value against its double reference: ULPs, relative error and the
// conditioning allowance (what the exact function itself moves when its
// inputs move by a rounding). The inputs are in checks/pointwise_inputs.hpp.
#pragma once

#include "abi/pointwise.h"

#include <array>
#include <cmath>
#include <functional>

#include <glm/vec3.hpp>

namespace mfv {

// One record as the float harnesses (agree, eval, check) hold it.
using FloatRecord = std::array<float, pw::PW_RECORD>;

// The kernel's value in a float record: the float part plus the float
// remainder a double build stores beside it.
inline double record_value(const float* r) {
  double k = r[pw::PW_VALUE];
  return std::isfinite(k) ? k + r[pw::PW_VALUE_LO] : k;
}

// The unit of rounding of the format: 2^-23 (float) or 2^-52 (double).
inline double rounding_unit(bool fp64) { return fp64 ? 0x1p-52 : 0x1p-23; }
// The smallest normal number of the format.
double min_normal(bool fp64);
// ULP of a float (or double) at |x|: the spacing of the format just above |x|.
double ulp_of(double x, bool fp64);

// The error of a kernel value against the reference: the absolute
// difference, in ULPs of the reference, and relative to it. Equal infinities
// differ by 0; a NaN on either side is an infinite error.
struct PointError {
  double diff = 0, ulps = 0, rel = 0;
};
PointError point_error(double kernel, double reference, bool fp64);

// The error of a sweep point where a result may be non-finite (the error
// curves of mfv stability): both finite, the ULPs; equal non-finite values
// 0; otherwise, or a negative value where the reference is not, infinite.
double sweep_ulps(double kernel, double reference, bool fp64);

// Conditioning allowance: the largest |f(inputs moved) - reference| when
// input j alone moves by b = ±units·rounding_unit (moved(j, b) gives f
// there; a NaN it returns is skipped). No format can do better than the
// exact function does on inputs one rounding away, so an error within twice
// this is the input's, not the formula's.
double input_sensitivity(int inputs, double units, bool fp64, const std::function<double(int, double)>& moved,
                         double reference);

// The float rounding of the BTDF kernel's total-internal-reflection test
// g² = (η - 1)(η + 1) + c² (kernels/btdf.cl T_dielectric, c = |i·h|, η the
// relative index after its flip) against the exact g² at the record's
// numbers, to first order in the unit roundoff u (2^-24; 2^-53 in float64),
// with the accuracy OpenCL grants its builtins (sqrt 3 ulp, division 2.5 ulp,
// an ulp being at most 2u relative):
//   η = fl(1/η_rec) when light comes from below:      relative 5u
//   s = fl(i + fl(η o)) componentwise:                 |Δs| ≤ u |s| + 6u η |o|
//   h = s · fl(1/sqrt(Σ s²)), each product rounded:    a common scale 1.5u + 6u + 5u
//                                                      and u per component
//   c = fl(i·h) (three products, two sums):            3u
//   so |Δc| ≤ u (5 + 12.5 c + 6 η / |s|)   (|Δs|/|s| tilts h; |i|, |o| = 1 + O(u))
//   g² = fl(fl(fl(η-1) fl(η+1)) + fl(c c)):
//        |Δg²| ≤ 3u |η² - 1| + 10u η² + u c² + u |g²| + 2c |Δc|.
// Near the critical angle of a small η (c² ≈ 1 - η²) the exact g² is
// (η o·h)², 1e-9 at η ≈ 0.01 (η² c ≈ 1e-4): the rounding (≈ 39u = 2.3e-6)
// decides on which side of the cut the kernel lands, and how far (issue 29:
// at η 94 and 0.0102 the reference was 0, total internal reflection, and the
// kernel 1.2e-7 and 1.1e-9). The double reference at a float64 kernel's
// inputs rounds as much again: twice the bound there.
// eta_rec: the record's η (η_below/η_above); wi, wo: its directions, as the
// reference evaluates them.
double btdf_tir_rounding(double eta_rec, const glm::dvec3& wi, const glm::dvec3& wo, bool fp64);

}  // namespace mfv
