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
// Three terms:
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
//   L u_d max(sum |r|, n 1e-6) / (mu w)   with L = 2^7, where the sample
//       forms its half vector from a sampled light i and the fixed view o
//       and reads a lobe of width w (lobe_width): the one place where the
//       reference is worse conditioned than the kernel, so kf - kd cannot
//       show it. The kernel forms h = (i + o)/|i + o| once and reads both
//       the BRDF's D and the proposal's density at it (albedo_mis_microfacet,
//       albedo_mis_general), so at a near-mirror lobe, where the proposal's
//       D_w is the BRDF's D, their ratio cancels any rounding of h. The
//       reference reads the proposal's density at normalize(i + o)
//       (reference/estimators.cpp albedo_mis) but the BRDF makes i and o
//       unit first (reference/brdf.cpp shading_from, for float inputs), so
//       the BRDF's half vector is another rounding of i + o. Derivation
//       (GGX, Walter et al. 2007 eq. 33 in t = tan θ_h / w:
//       D ∝ (1 + t²)^-2 / cos⁴θ_h): the tangent part of s = i + o is
//       |s_t| = s_z tan θ_h with s_z = i_z + o_z > mu wherever i_z > 0;
//       each of i, o is unit to ~3u and its renormalization rounds ~2.5u
//       more, so the two s_t differ by δs_t <= 10 u_d (|i|, |o| = 1, and
//       i_x + o_x is exact where they nearly cancel); t moves by
//       δt = δs_t / (s_z w) < 10 u_d / (mu w), and ln D by
//       4t/(1 + t²) δt <= 2 δt, which the proposal's D_w at the other h does
//       not cancel: a relative error of at most 20 u_d / (mu w) per sample,
//       so L = 2^7 > 20 with a margin of 6 (it also covers Beckmann's
//       2t δt, whose weight t e^-t² (1 + t²)² on a GGX-shaped proposal is
//       at most 1.75x GGX's). Measured (tests/test_trust_reference.cpp,
//       near-mirror scene, GGX at alpha 1e-4, mu = 1.35e-4, seed 1: the
//       twin within 3e-12 of a 50-digit evaluation of the same formula, the
//       reference 2.8e-9 on average and up to 2.45e-8 relative, 1.6
//       u_d / ((o·h) w)): the mean is 1/340 of this term, and the first two
//       terms alone read 1.0007 x. At (mu, w) = (1e-4, 1e-4) the term is
//       1.4e-6 relative: a formula error of 1e-5 still exceeds it (plant
//       kGgxPiRounded, 2.3e-6, fails that point); at w = 0.01 it is 1.4e-8.
// At mu = 1e-4 and a wide lobe the bound is 1.1e-9 relative plus 2e-6 of the
// float rounding: a formula error of 1e-3 exceeds it by six decades.
double derived_formula_bound(double float_rounding_l1, double reference_l1, double mu, double lobe_width) {
  constexpr double K = 0x1p10, C = 0x1p10, L = 0x1p7;
  const double m = std::clamp(mu, 1e-4, 1.0);  // the grid's most grazing cosine is 1e-4
  const double lobe = lobe_width > 0 ? L / lobe_width : 0.0;
  return K * (kDoubleRoundoff / kFloatRoundoff) * float_rounding_l1 + (C + lobe) * kDoubleRoundoff * reference_l1 / m;
}

// The narrowest width of the lobe whose half vector a sample forms from a
// sampled light and the fixed view (derived_formula_bound's w); 0 for the
// kinds whose sample is the half vector itself (d_norm and the masking
// furnaces integrate over h) and for a spec with no declared width.
double lobe_width_of(const IntegralSpec& s) {
  const auto k = static_cast<IntegralKind>(s.check);
  if (k == IntegralKind::DNorm || k == IntegralKind::Masking || k == IntegralKind::MaskingT) return 0.0;
  const double wx = s.width, wy = s.width_y > 0 ? s.width_y : s.width;
  return std::min(wx, wy) > 0 ? std::min(wx, wy) : 0.0;
}

ReferenceTwin::ReferenceTwin(Runtime& rt, const TermSelection& terms)
    : rt_(rt), terms_(terms), available_(rt.device().fp64) {}

void ReferenceTwin::build() {
  if (!program_())
    program_ =
        rt_.build(integrate_sources(), {"MFV_DOUBLE", "MFV_ACC_DOUBLE"}, generate_dispatch(terms_), kDispatchBefore);
}

int ReferenceTwin::build_ahead(const IntegralSpec& spec, uint64_t seed) {
  if (!available_ || program_()) return 0;
  build();
  program_sample_values<double>(rt_, program_, {spec}, 1, seed);
  return 1;
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
  build();
  rt_.await(HandOver::SampleValues);  // a compile-ahead child's compile of the float sample_values
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
    a.formula_bound = derived_formula_bound(e_l1, std::max(scale, n * 1e-6), specs[j].cos_o, lobe_width_of(specs[j]));
    a.formula_gap /= n;
    a.formula_bound /= n;
    a.ok = a.formula_gap <= a.formula_bound;
    out.push_back(a);
  }
  return out;
}

}  // namespace mfv
