#include "checks/pointwise.hpp"

#include "reference/btdf.hpp"

#include <glm/geometric.hpp>

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

// The bound and its derivation: checks/pointwise.hpp.
double btdf_tir_rounding(double eta_rec, const glm::dvec3& wi, const glm::dvec3& wo, bool fp64) {
  const double u = 0.5 * rounding_unit(fp64);
  const double ei = wi.z > 0 ? 1.0 : eta_rec, eo = wo.z > 0 ? 1.0 : eta_rec, eta = eo / ei;
  const glm::dvec3 h = ref::half_vector_t(wi, wo, eta_rec);
  const double s = glm::length(wi + eta * wo);  // |η_i i + η_o o| / η_i: the kernel's s after its flip
  if (!(s > 0.0)) return 0.0;                    // h_t degenerate: the BTDF is 0 there, on both sides
  const double c = std::min(1.0, std::fabs(glm::dot(wi, h)));
  const double g2 = (eta - 1.0) * (eta + 1.0) + c * c;
  const double dc = u * (5.0 + 12.5 * c + 6.0 * eta / s);
  const double dg2 = u * (3.0 * std::fabs((eta - 1.0) * (eta + 1.0)) + 10.0 * eta * eta + c * c + std::fabs(g2)) +
                     2.0 * c * dc;
  return (fp64 ? 2.0 : 1.0) * dg2;
}

}  // namespace mfv
