#include "checks/reference_compare.hpp"

#include "reference/estimators.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mfv {

// The bound on sum |kd - r| over n samples.
//
// kd and r are two double evaluations of one formula on identical inputs.
// Each differs from the exact value by its own rounding, which is the float
// rounding of the same formula scaled by the ratio of unit roundoffs,
// u_d / u_f = 2^-29: the conditioning of a sample (grazing 1/(n.v), a
// near-mirror lobe a few ulps wide, the cancellation in (1 - v.h)^5) is
// the same in both precisions, and kf - kd on the same samples measures it.
// Two terms:
//   K (u_d / u_f) sum |kf - kd|   with K = 2^10: the reference arranges the
//       formula differently from the kernel (other operation order, other
//       cancellation-free forms), which three decades of margin cover; the
//       term is still 2^-19 ~ 2e-6 of the float rounding, so a formula error
//       of 1e-3 (a D scaled by 1.001) exceeds it wherever float rounding is
//       below ~500 % of the value;
//   C u_d max(sum |r|, n 1e-6) / mu   with C = 2^10: a formula of up to
//       2^8 operations rounds each to half an ulp, so 2^8 ulps with a margin
//       of 4, for samples the float kernel happens to round exactly
//       (kf == kd). 1/mu is the conditioning of the fixed direction at
//       cosine mu: the reference forms sin θ = sqrt(1 - mu²), the light or
//       view from it, and divides by n·v, so one rounding of its inputs
//       moves a sample by u_d/mu relative (measured over the default suite:
//       up to 1.2e-11 relative at mu = 1.5e-4, where u_d/mu = 7e-13, in the
//       non-Smith G terms at grazing view). Values below 1e-6 are tested
//       against 1 and cannot change a verdict, so they are compared in
//       absolute terms.
// At mu = 1e-4 the bound is 1.1e-9 relative plus 2e-6 of the float rounding:
// a formula error of 1e-3 exceeds it by six decades.
double derived_formula_bound(double float_rounding_l1, double reference_l1, double mu) {
  constexpr double K = 0x1p10, C = 0x1p10;
  const double conditioning = 1.0 / std::clamp(mu, 1e-4, 1.0);  // the grid's most grazing cosine is 1e-4
  return K * (kDoubleRoundoff / kFloatRoundoff) * float_rounding_l1 + C * kDoubleRoundoff * reference_l1 * conditioning;
}

ReferenceTwin::ReferenceTwin(Runtime& rt, const TermSelection& terms) : rt_(rt) {
  if (!rt.device().fp64) return;
  program_ = rt.build(integrate_sources(), {"MFV_DOUBLE", "MFV_ACC_DOUBLE"}, generate_dispatch(terms), kDispatchBefore);
  available_ = true;
}

namespace {

// |a - b| where equal non-finite values agree and any other non-finite pair is infinitely apart.
double gap(double a, double b) {
  if (std::isfinite(a) && std::isfinite(b)) return std::fabs(a - b);
  return (std::isnan(a) && std::isnan(b)) || a == b ? 0.0 : std::numeric_limits<double>::infinity();
}

}  // namespace

std::vector<TwinAgreement> ReferenceTwin::compare(Integrator& in, const std::vector<IntegralSpec>& specs, uint32_t n,
                                                  uint64_t seed) {
  std::vector<TwinAgreement> out;
  if (n == 0 || specs.empty() || !available_) return out;
  const std::vector<float> kf = in.sample_values(specs, n, seed);
  const std::vector<double> kd = program_sample_values<double>(rt_, program_, specs, n, seed);
  for (size_t j = 0; j < specs.size(); ++j) {
    const ref::IntegralRef r = reference_of(specs[j]);
    const uint64_t stride = r.strata >= n ? r.strata / n : 1;  // as kernels/integrate.cl sample_values
    TwinAgreement a;
    double sf = 0, sd = 0, sr = 0, scale = 0, e_sum = 0, e_sq = 0, e_l1 = 0, worst = -1;
    bool float_finite = true;
    for (uint32_t k = 0; k < n; ++k) {
      const double f = kf[j * n + k], d = kd[j * n + k], rv = ref::sample_value(r, seed, k * stride);
      sf += f;
      sd += d;
      sr += rv;
      if (std::isfinite(rv)) scale += std::fabs(rv);
      if (std::isfinite(f) && std::isfinite(d)) {
        e_sum += f - d;
        e_sq += (f - d) * (f - d);
        e_l1 += std::fabs(f - d);
      } else if (std::isfinite(d)) {
        float_finite = false;  // the float kernel overflowed or gave NaN where its twin did not
      }
      const double g = gap(d, rv);
      a.formula_gap += g;
      if (g > worst) worst = g, a.worst_index = k * stride, a.worst_twin = d, a.worst_reference = rv;
    }
    a.float_mean = sf / n;
    a.double_mean = sd / n;
    a.reference_mean = sr / n;
    // The bias of the float estimate is E[kf - kd]; its mean over n samples
    // has standard error sd/sqrt(n), and 3 of them make an upper bound.
    const double e_mean = e_sum / n, e_var = std::max(0.0, e_sq / n - e_mean * e_mean) * n / std::max(1u, n - 1);
    a.rounding_bound =
        float_finite ? std::fabs(e_mean) + 3 * std::sqrt(e_var / n) : std::numeric_limits<double>::infinity();
    a.formula_bound = derived_formula_bound(e_l1, std::max(scale, n * 1e-6), specs[j].cos_o);
    a.formula_gap /= n;
    a.formula_bound /= n;
    a.ok = a.formula_gap <= a.formula_bound;
    out.push_back(a);
  }
  return out;
}

}  // namespace mfv
