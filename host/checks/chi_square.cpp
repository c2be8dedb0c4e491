#include "checks/chi_square.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mfv {
namespace {

// P(a, x) by its series, for x < a + 1 (Numerical Recipes eq. 6.2.5).
double gamma_p_series(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < 1000000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::fabs(term) < std::fabs(sum) * 1e-15) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) by Lentz's continued fraction, for x >= a + 1 (NR eq. 6.2.7).
double gamma_q_fraction(double a, double x) {
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 1000000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::fabs(del - 1.0) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

double chi_square_upper_tail(double x, int dof) {
  if (dof <= 0) return 1.0;
  if (!(x > 0)) return x == 0 ? 1.0 : 0.0;  // NaN statistic: no fit
  const double a = 0.5 * dof, hx = 0.5 * x;
  return hx < a + 1.0 ? 1.0 - gamma_p_series(a, hx) : gamma_q_fraction(a, hx);
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
