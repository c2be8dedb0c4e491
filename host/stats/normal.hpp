// Normal-law quantiles and tail probabilities for the verdicts (Boost.Math),
// and the binomial bounds the calibration test puts on a count of tails.
#pragma once

#include <cstdint>

namespace mfv::stats {

// z with P(|N(0,1)| > z) = p (two-sided), p in (0, 1].
double normal_two_sided_quantile(double p);
// z with P(N(0,1) > z) = p (one-sided), p in (0, 1).
double normal_upper_quantile(double p);
// P(|N(0,1)| > z).
double normal_two_sided_tail(double z);
// t with P(|T| > t) = p for Student's t with dof degrees of freedom.
double student_t_two_sided_quantile(double p, double dof);
// P(|T| > |t|) for Student's t with dof degrees of freedom (NaN for NaN, 0 for +-inf).
double student_t_two_sided_p(double t, double dof);
// x with P(X > x) = p for chi-squared X with dof degrees of freedom, p in (0, 1).
double chi_squared_upper_quantile(double p, double dof);

// The smallest k with P(Binomial(n, p) > k) <= q: a count of events of
// probability at most p that exceeds it has chance at most q.
uint64_t binomial_upper_bound(uint64_t n, double p, double q);
// The largest k with P(Binomial(n, p) < k) <= q.
uint64_t binomial_lower_bound(uint64_t n, double p, double q);

}  // namespace mfv::stats
