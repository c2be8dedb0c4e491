// Chi-square goodness of fit of a histogram against expected cell counts,
// pooling cells of low expectation, as pbrt-v4 (util/check ChiSquareTest) and
// Mitsuba 3 (mitsuba.chi2) test their samplers.
#pragma once

#include <string>
#include <vector>

namespace mfv {

struct ChiSquare {
  double statistic = 0;
  int dof = 0;
  double p_value = 1;      // P(χ²_dof >= statistic)
  std::string impossible;  // non-empty: samples fell where the expectation is zero (fails outright)
};

// observed[k] and expected[k] are counts over the same cells. Cells below
// `min_expected` are pooled (smallest expectations first) until the pool
// reaches it; a cell of zero expectation holding more than n·1e-5 samples
// makes the test fail outright (pbrt-v4's rule).
ChiSquare chi_square_test(const std::vector<double>& observed, const std::vector<double>& expected,
                          double min_expected = 5.0);

// Upper tail of the chi-square distribution: Q(dof/2, x/2), the regularized
// incomplete gamma function (series / continued fraction, Numerical Recipes §6.2).
double chi_square_upper_tail(double x, int dof);

// Šidák: the per-test level that keeps the family-wise rate at `alpha` over
// `tests` independent tests, 1 - (1 - alpha)^(1/tests).
double sidak_level(double alpha, int tests);

}  // namespace mfv
