#include "checks/pointwise.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mfv {

double min_normal(bool fp64) { return fp64 ? std::numeric_limits<double>::min() : std::numeric_limits<float>::min(); }

double ulp_of(double x, bool fp64) {
  double a = std::fabs(x);
  int mant = fp64 ? 52 : 23;
  double tiny = fp64 ? std::numeric_limits<double>::denorm_min() : std::numeric_limits<float>::denorm_min();
  if (!std::isfinite(a)) return std::numeric_limits<double>::infinity();
  if (a < min_normal(fp64)) return tiny;
  int e;
  std::frexp(a, &e);  // a = m 2^e, m in [0.5, 1)
  return std::ldexp(1.0, e - 1 - mant);
}

PointError point_error(double kernel, double reference, bool fp64) {
  PointError e;
  e.diff = kernel == reference ? 0.0 : std::fabs(kernel - reference);
  e.ulps = e.diff / ulp_of(reference, fp64);
  e.rel = e.diff / std::max(std::fabs(reference), std::numeric_limits<double>::min());
  if (std::isnan(kernel) || std::isnan(reference)) e.ulps = e.rel = std::numeric_limits<double>::infinity();
  return e;
}

double sweep_ulps(double kernel, double reference, bool fp64) {
  const double inf = std::numeric_limits<double>::infinity();
  if (kernel < 0 && reference >= 0) return inf;
  if (!std::isfinite(kernel) || !std::isfinite(reference)) return kernel == reference ? 0.0 : inf;
  return std::fabs(kernel - reference) / ulp_of(reference, fp64);
}

double input_sensitivity(int inputs, double units, bool fp64, const std::function<double(int, double)>& moved,
                         double reference) {
  const double b = units * rounding_unit(fp64);
  double dev = 0;
  for (int j = 0; j < inputs; ++j)
    for (double s : {b, -b}) dev = std::max(dev, std::fabs(moved(j, s) - reference));  // a NaN leaves dev
  return dev;
}

}  // namespace mfv
