// Reference Fresnel terms of one colour channel, argument VoH = cos(theta_i)
// on the facet (= LoH for the exact half vector).  VoH is clamped into [0, 1]
// first (saturate): a dot product may round a few ULP outside it.
//
// Parameter ranges (f0 in [0, 1], eta > 0, n > 0, k >= 0) are validated by
// the catalog.
#include "reference/reference.hpp"

#include <cmath>
#include <complex>

#include "reference/math_util.hpp"

namespace mfv::ref {

using detail::saturate;

double F_none(double, double, double) {
  // No Fresnel: every facet reflects all light (F ≡ 1), for furnace tests.
  return 1.0;
}

double F_schlick(double VoH, double f0, double) {
  // seed 000, "Schlick's approximation"; seed 001; seed 004 (Schlick 1994):
  //   F = f0 + (1 − f0)(1 − cosθ)^5
  // Exact at both ends in double: F(1) = f0, and F(0) = f0 + (1 − f0) = 1
  // (the rounding error of 1 − f0 is at most half an ULP of 1, which the
  // sum rounds away).
  const double c = saturate(VoH);
  const double m = 1.0 - c;
  const double m2 = m * m;
  return f0 + (1.0 - f0) * (m2 * m2 * m);
}

double F_dielectric(double VoH, double eta, double) {
  // seed 003, "Fresnel's Law" (Snell form, unpolarised light), with
  // eta = eta_t / eta_i after dividing numerator and denominator by eta_i:
  //   sinθt = sinθi / eta;   sinθt >= 1 → total internal reflection, F = 1
  //   r_perp = (cosθi − eta cosθt) / (cosθi + eta cosθt)
  //   r_par  = (eta cosθi − cosθt) / (eta cosθi + cosθt)
  //   F = (r_perp² + r_par²) / 2
  // (seed 003 calls these r_p and r_L; the pair is what matters.)
  // Seed 001's closed g/c form has typos: its g² reads "η^{2+}c² + 1" (the
  // sign of the 1 is wrong) and its inner denominator is c(g − c) − 1; the
  // correct closed form is seed 000's, g² = η² − 1 + c² with c(g − c) + 1.
  // This reference uses the Snell form instead, so seed 000's closed form
  // stays an independent check (tests/test_reference_terms.cpp).
  //
  // Snell's law is evaluated as
  //   eta² cos²θt = eta² − sin²θi = (eta − 1)(eta + 1) + cos²θi,
  // the same quantity as 1 − sin²θt times eta², but without the cancellation
  // of 1 − sin²θi near grazing or of eta² − 1 near eta = 1 (so eta = 1 gives
  // cosθt == cosθi and F == 0 exactly).  sinθt >= 1 ⇔ this is <= 0.
  const double cos_i = saturate(VoH);
  if (cos_i == 0.0) return 1.0;  // θi = π/2: r_perp = r_par = −1 for every eta ≠ 1
  const double eta2_cos2_t = (eta - 1.0) * (eta + 1.0) + cos_i * cos_i;
  if (eta2_cos2_t <= 0.0) return 1.0;  // sinθt >= 1: total internal reflection
  const double eta_cos_t = std::sqrt(eta2_cos2_t);
  const double cos_t = eta_cos_t / eta;
  const double r_perp = (cos_i - eta_cos_t) / (cos_i + eta_cos_t);
  const double r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (r_perp * r_perp + r_par * r_par);
}

double F_conductor(double VoH, double n, double k) {
  // Fresnel equations for a complex index eta = n + i k (Born & Wolf,
  // "Principles of Optics", sec. 14.2; the complex continuation of seed
  // 003's Snell form):
  //   sinθt = sinθi / eta,  cosθt = sqrt(1 − sin²θt)  (principal branch)
  //   r_s = (cosθi − eta cosθt) / (cosθi + eta cosθt)
  //   r_p = (eta cosθi − cosθt) / (eta cosθi + cosθt)
  //   F = (|r_s|² + |r_p|²) / 2
  // 1 − sin²θt is evaluated as ((eta − 1)(eta + 1) + cos²θi) / eta², the
  // same complex number (hence the same principal root) without cancellation
  // near grazing or near eta = 1; see F_dielectric.  With k = 0 and n < 1
  // beyond the critical angle it is a negative real, cosθt is imaginary and
  // |r_s| = |r_p| = 1: total internal reflection needs no branch here.
  using complex = std::complex<double>;
  const double cos_i = saturate(VoH);
  if (cos_i == 0.0) return 1.0;  // θi = π/2: r_s = r_p = −1 for every eta ≠ 1
  const complex eta(n, k);
  const complex cos2_t = ((eta - 1.0) * (eta + 1.0) + cos_i * cos_i) / (eta * eta);
  const complex cos_t = std::sqrt(cos2_t);
  const complex r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const complex r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (std::norm(r_s) + std::norm(r_p));
}

double F_schlick_f90(double VoH, double f0, double f90) {
  // Schlick 1994's approximation with the grazing reflectance f90 in place of 1:
  //   F = f0 + (f90 − f0)(1 − cosθ)^5
  // From the larger end's side: f0 + (f90 − f0) w for f90 >= f0 (both terms
  // >= 0), else f90 + (f0 − f90)(1 − w), where 1 − w = −expm1(5 log1p(−c))
  // keeps its digits as c -> 0 (then F -> f90 and nothing cancels).
  const double c = saturate(VoH);
  const double w = std::pow(1.0 - c, 5.0);
  if (f90 >= f0) return f0 + (f90 - f0) * w;
  return f90 + (f0 - f90) * -std::expm1(5.0 * std::log1p(-c));
}

double F_schlick_sg(double VoH, double f0, double) {
  // Karis 2013, "Real Shading in Unreal Engine 4", Specular BRDF, Fresnel: Schlick's
  // with the spherical-Gaussian fit of (1 − cosθ)^5 (Lagarde 2012):
  //   F = f0 + (1 − f0) 2^((−5.55473 cosθ − 6.98316) cosθ)
  const double c = saturate(VoH);
  return f0 + (1.0 - f0) * std::exp2((-5.55473 * c - 6.98316) * c);
}

}  // namespace mfv::ref
