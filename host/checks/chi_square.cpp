#include "checks/chi_square.hpp"

#include <fmt/format.h>
#include <boost/math/special_functions/gamma.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mfv {
double chi_square_upper_tail(double x, int dof) {
  if (dof <= 0) return 1.0;
  if (!(x > 0)) return x == 0 ? 1.0 : 0.0;  // NaN statistic: no fit
  if (std::isinf(x)) return 0.0;
  // P(chi²_k > x) = Q(k/2, x/2), the regularized upper incomplete gamma (Boost.Math)
  return boost::math::gamma_q(0.5 * dof, 0.5 * x);
}

double sidak_level(double alpha, int tests) { return -std::expm1(std::log1p(-alpha) / std::max(tests, 1)); }

ChiSquare chi_square_test(const std::vector<double>& observed, const std::vector<double>& expected,
                          double min_expected) {
  ChiSquare r;
  std::vector<size_t> order(expected.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });
  const double n = std::accumulate(observed.begin(), observed.end(), 0.0);
  double pooled_obs = 0, pooled_exp = 0;
  for (size_t k : order) {
    const double o = observed[k], e = expected[k];
    if (e <= 0.0) {
      if (o > n * 1e-5 && r.impossible.empty())
        r.impossible = fmt::format("{:g} samples in a cell of zero expectation", o);
      pooled_obs += o;
    } else if (e < min_expected || (pooled_exp > 0 && pooled_exp < min_expected)) {
      pooled_obs += o;  // pool the smallest expectations until the pool reaches min_expected
      pooled_exp += e;
    } else {
      r.statistic += (o - e) * (o - e) / e;
      ++r.dof;
    }
  }
  if (pooled_exp > 0) {
    r.statistic += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
    ++r.dof;
  }
  r.dof -= 1;  // the counts sum to n
  r.p_value = r.impossible.empty() ? chi_square_upper_tail(r.statistic, r.dof) : 0.0;
  return r;
}

}  // namespace mfv
