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

}  // namespace mfv
