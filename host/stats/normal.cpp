#include "stats/normal.hpp"

#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/special_functions/beta.hpp>

#include <algorithm>
#include <cmath>

namespace mfv::stats {

double normal_two_sided_quantile(double p) {
  // P(|Z| > z) = p  <=>  z = Q(p / 2), Q the upper quantile (complement of the CDF)
  return normal_upper_quantile(0.5 * std::min(p, 1.0));
}

double student_t_two_sided_quantile(double p, double dof) {
  // P(|T| > t) = p  <=>  t = upper quantile of T at p / 2
  const double q = 0.5 * std::min(p, 1.0);
  if (q >= 0.5) return 0;
  return boost::math::quantile(boost::math::complement(boost::math::students_t_distribution<double>(dof), q));
}

double chi_squared_upper_quantile(double p, double dof) {
  return boost::math::quantile(boost::math::complement(boost::math::chi_squared_distribution<double>(dof), p));
}

double student_t_two_sided_p(double t, double dof) {
  if (std::isnan(t)) return NAN;
  if (std::isinf(t)) return 0.0;
  // P(|T_dof| > |t|) = I_{dof/(dof+t²)}(dof/2, 1/2), the regularized incomplete beta
  return boost::math::ibeta(dof / 2, 0.5, dof / (dof + t * t));
}

double normal_upper_quantile(double p) {
  if (p >= 0.5) return p >= 1 ? -INFINITY : -normal_upper_quantile(1 - p);
  return boost::math::quantile(boost::math::complement(boost::math::normal_distribution<double>(), p));
}

double normal_two_sided_tail(double z) {
  if (!std::isfinite(z)) return std::isnan(z) ? z : 0.0;
  return 2 * boost::math::cdf(boost::math::complement(boost::math::normal_distribution<double>(), std::fabs(z)));
}

uint64_t binomial_upper_bound(uint64_t n, double p, double q) {
  // P(X > k) = 1 - CDF(k), decreasing in k: the first k where it is <= q
  boost::math::binomial_distribution<double> b(double(n), p);
  uint64_t k = 0;
  while (k < n && boost::math::cdf(boost::math::complement(b, double(k))) > q) ++k;
  return k;
}

uint64_t binomial_lower_bound(uint64_t n, double p, double q) {
  // P(X < k) = CDF(k - 1), increasing in k: the last k where it is <= q
  boost::math::binomial_distribution<double> b(double(n), p);
  uint64_t k = 0;
  while (k < n && boost::math::cdf(b, double(k)) <= q) ++k;
  return k;
}

}  // namespace mfv::stats
