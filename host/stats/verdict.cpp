#include "stats/verdict.hpp"

#include "stats/normal.hpp"

#include <algorithm>
#include <cmath>

namespace mfv::stats {
namespace {

// Higham 2002, Lemma 3.1: gamma_k = k u / (1 - k u).
double gamma(double k, double u) { return k * u < 0.5 ? k * u / (1 - k * u) : INFINITY; }

}  // namespace

double float_rounding_bound(double mean, uint64_t samples, bool double_accumulation) {
  const double evaluation = gamma(kFloatOps, 0x1p-24);
  const double accumulation = gamma(double(samples), double_accumulation ? 0x1p-53 : 0x1p-24);
  return (evaluation + accumulation) * std::fabs(mean);
}

double total_uncertainty(double se, double bias) { return se + std::fabs(bias); }

FamilySplit split_family_alpha(double family_alpha) { return {0.5 * family_alpha, 0.5 * family_alpha}; }

double per_integral_threshold(double alpha, size_t tests) {
  return normal_two_sided_quantile(alpha / double(std::max<size_t>(tests, 1)));
}

Pooled pooled_test(const std::vector<Deviation>& devs, bool upper_only, double alpha, size_t pooled_tests) {
  Pooled p;
  p.upper_only = upper_only;
  // Bonferroni over the pooled tests; one-sided tests spend their share on one tail
  const double a = alpha / double(std::max<size_t>(pooled_tests, 1));
  p.threshold = upper_only ? normal_upper_quantile(a) : normal_two_sided_quantile(a);
  p.n = devs.size();
  if (devs.empty()) return p;
  double sum = 0, var = 0, bias = 0;
  for (auto& d : devs) {
    sum += d.dev;
    var += d.se * d.se;
    bias += std::fabs(d.bias);
  }
  const double n = double(devs.size());
  p.mean = sum / n;
  p.se = std::sqrt(var) / n;
  p.bias = bias / n;
  const double u = total_uncertainty(p.se, p.bias);
  p.z = u > 0 ? p.mean / u : (p.mean == 0 ? 0.0 : std::copysign(INFINITY, p.mean));
  const double allowance = p.threshold * p.se + p.bias;
  p.failed = upper_only ? !(p.mean <= allowance) : !(std::fabs(p.mean) <= allowance);
  return p;
}

}  // namespace mfv::stats
