// Reference microfacet distributions D(h), argument NoH = cos(theta_h).
//
// Normalisation convention (reference.hpp): ∫_H D(m) (m·n) dω_m = 1.
// Every D returns 0 for NoH <= 0 (the χ+(m·n) factor: no facet faces away
// from the macro-surface), and treats a cosine that rounded above 1 as exactly
// 1 (tan²θ = 0), so D(1 + ε) == D(1) and nothing turns into NaN.
//
// Parameter ranges (alpha > 0, alpha_p >= 0, rho > 0, m > 0) are validated at
// the catalog boundary, not here; the reference evaluates the formula as the
// source writes it.
#include "reference/reference.hpp"
#include "reference/d_log_cos.hpp"

#include <cmath>

#include "reference/math_util.hpp"

namespace mfv::ref {

using detail::kPi;
using detail::saturate;
using detail::sin2_from_cos;
using detail::tan2_from_cos;

double D_phong(double NoH, double alpha_p) {
  // seed 000, "Phong": D_p = (alpha_p + 2) / (2π) (N·H)^alpha_p
  // (seed 003, "Blinn Microfacet Distribution", derives the same constant
  //  c = (e + 2) / 2π from ∫ D cosθ dω = 1.)
  if (NoH <= 0.0) return 0.0;  // χ+(m·n)
  const double c = saturate(NoH);
  return (alpha_p + 2.0) / (2.0 * kPi) * std::pow(c, alpha_p);
}

double D_beckmann(double NoH, double alpha) {
  // seed 000, "Beckman"; Walter et al. 2007, eq. 25:
  //   D_b = exp(-tan²θ / alpha²) / (π alpha² cos⁴θ)
  if (NoH <= 0.0) return 0.0;  // χ+(m·n)
  const double c = saturate(NoH);
  const double tan2 = tan2_from_cos(c);  // 0 at c = 1, +inf as c → 0
  const double e = std::exp(-tan2 / (alpha * alpha));
  // θ→π/2: exp(-tan²θ/α²) vanishes faster than cos⁴θ, so D→0.  Returning
  // here also avoids 0/0 once cos⁴θ underflows.
  if (e == 0.0) return 0.0;
  const double c2 = c * c;
  // At c = 1: e = 1 and c2 * c2 = 1, so this is exactly 1 / (π alpha²).
  return e / ((kPi * (alpha * alpha)) * (c2 * c2));
}

double D_ggx(double NoH, double alpha) {
  // Walter et al. 2007, eq. 33; seed 000, "GGX":
  //   D_g = alpha² / (π cos⁴θ (alpha² + tan²θ)²)
  //       = 1 / (π alpha² [cos⁴θ (1 + tan²θ/alpha²)²])
  //       = 1 / (π alpha² (cos²θ + sin²θ/alpha²)²)
  // The last form has no tan²θ, hence no singularity at θ = π/2 (where it
  // tends to alpha²/π), and it is exactly 1/(π alpha²) at NoH = 1 because
  // sin²θ = (1 − c)(1 + c) is exactly 0 there.  Seed 000's second form,
  // alpha² / (π (c²(alpha² − 1) + 1)²), loses that: (alpha² − 1) + 1 rounds
  // (≈200 ULP of D at alpha = 0.05, NoH = 1).
  if (NoH <= 0.0) return 0.0;  // χ+(m·n)
  const double c = saturate(NoH);
  const double k = c * c + sin2_from_cos(c) / (alpha * alpha);
  return 1.0 / ((kPi * (alpha * alpha)) * (k * k));
}

double D_ggx_cs(double cos2, double sin2, double alpha) {
  // Walter et al. 2007, eq. 33, in the last form of D_ggx above:
  //   D_g = 1 / (π alpha² (cos²θ + sin²θ/alpha²)²)
  // with cos²θ and sin²θ taken as given (each to full relative precision)
  // instead of sin²θ = (1 − c)(1 + c) from a cosine that rounded.
  if (!(cos2 > 0.0)) return 0.0;  // χ+(m·n)
  const double k = cos2 + sin2 / (alpha * alpha);
  return 1.0 / ((kPi * (alpha * alpha)) * (k * k));
}

double D_beckmann_cs(double cos2, double sin2, double alpha) {
  // Walter et al. 2007, eq. 25, as D_beckmann above with tan²θ = sin²θ/cos²θ
  // from sin²θ given to full relative precision: near the peak of a narrow
  // lobe (alpha 1e-4 and below) tan²θ/alpha² from (1 − c)(1 + c) carries
  // a relative error of u/(1 − c), which the exponent turns into an error
  // of D ~ u/alpha².
  if (!(cos2 > 0.0)) return 0.0;  // χ+(m·n)
  const double e = std::exp(-(sin2 / cos2) / (alpha * alpha));
  if (e == 0.0) return 0.0;  // θ→π/2: the exponential wins, D→0 (no 0/0)
  return e / ((kPi * (alpha * alpha)) * (cos2 * cos2));
}

double D_beckmann_ct82_cs(double cos2, double sin2, double m) {
  // seed 001 as written (known bad, see D_beckmann_ct82), from cos²θ and sin²θ given apart
  if (!(cos2 > 0.0)) return 0.0;  // χ+(m·n)
  const double e = std::exp(-(sin2 / cos2) / (m * m));
  if (e == 0.0) return 0.0;
  return e / ((4.0 * (m * m)) * (cos2 * cos2));
}

// log cos θ from cos² and sin²: ½ log1p(−sin²) near the normal, where 1 − cos
// has lost the small angle (pow(c, e) there carries a relative error e·u),
// ½ log(cos²) elsewhere.
double log_cos_cs(double cos2, double sin2) { return sin2 < 0.5 ? 0.5 * std::log1p(-sin2) : 0.5 * std::log(cos2); }

double D_phong_lc(double log_cos, double alpha_p) {
  // seed 000, "Phong", as D_phong with (N·H)^alpha_p = exp(alpha_p log cos θ)
  return (alpha_p + 2.0) / (2.0 * kPi) * std::exp(alpha_p * log_cos);
}

double D_phong_cs(double cos2, double sin2, double alpha_p) {
  // seed 000, "Phong": D_phong_lc at log cos θ from cos²θ and sin²θ
  if (!(cos2 > 0.0)) return 0.0;  // χ+(m·n)
  return D_phong_lc(log_cos_cs(std::min(cos2, 1.0), sin2), alpha_p);
}

double D_blinn_rho_lc(double log_cos, double rho) {
  // seed 004 "blinn version", as D_blinn_rho with (h·n)^e = exp(e log cos θ)
  const double exponent = 2.0 / (rho * rho) - 2.0;
  return std::exp(exponent * log_cos) / (kPi * (rho * rho));
}

double D_blinn_rho_cs(double cos2, double sin2, double rho) {
  // seed 004 "blinn version": D_blinn_rho_lc at log cos θ from cos²θ and sin²θ
  if (!(cos2 > 0.0)) return 0.0;  // χ+(m·n)
  return D_blinn_rho_lc(log_cos_cs(std::min(cos2, 1.0), sin2), rho);
}

RefDlc d_of_log_cos(RefDcs cs) {
  if (cs == D_phong_cs) return D_phong_lc;
  if (cs == D_blinn_rho_cs) return D_blinn_rho_lc;
  return nullptr;
}

double D_blinn_rho(double NoH, double rho) {
  // seed 004, Cook-Torrance "blinn version":
  //   D = (h·n)^(2/rho² − 2) / (π rho²)
  // This is D_phong with alpha_p = 2/rho² − 2: (alpha_p + 2)/(2π) = 1/(π rho²),
  // so it is normalised.  For rho > 1 the exponent is negative (but > −2) and
  // D grows without bound toward θ = π/2, while staying integrable.
  if (NoH <= 0.0) return 0.0;  // χ+(m·n)
  const double c = saturate(NoH);
  const double exponent = 2.0 / (rho * rho) - 2.0;
  return std::pow(c, exponent) / (kPi * (rho * rho));
}

double D_beckmann_ct82(double NoH, double m) {
  // seed 001, "Use Beckmann distribution instead", as written:
  //   D(δ) = exp(-(tan δ / m)²) / (4 m² cos⁴δ)
  // KNOWN BAD (kept on purpose, catalog expected-fail): the constant is 4
  // where seed 000 / Walter eq. 25 have π, so D_beckmann_ct82 =
  // (π/4) D_beckmann and ∫ D cosθ dω = π/4 ≈ 0.785 instead of 1.
  if (NoH <= 0.0) return 0.0;  // χ+(m·n)
  const double c = saturate(NoH);
  const double tan2 = tan2_from_cos(c);
  const double e = std::exp(-tan2 / (m * m));
  if (e == 0.0) return 0.0;  // θ→π/2: the exponential wins, D→0 (no 0/0)
  const double c2 = c * c;
  return e / ((4.0 * (m * m)) * (c2 * c2));
}

}  // namespace mfv::ref

// ---- Anisotropic D ----------------------------------------------------------
// Tangent frame t = +x, b = +y, n = +z (seed 004's Ward: h·t over α_t, h·b
// over α_b). Written with the angles of m, as the papers write them.

namespace mfv::ref {
namespace {

// cos²θ, sin²θ and cos²φ of a direction, after making it unit.
struct Angles {
  double cos2, sin2, cos2phi, sin2phi;  // sin²φ apart: 1 − cos²φ cancels near φ = 0
};
Angles angles_of(const glm::dvec3& m_in) {
  const glm::dvec3 m = m_in / std::sqrt(m_in.x * m_in.x + m_in.y * m_in.y + m_in.z * m_in.z);
  const double s2 = m.x * m.x + m.y * m.y;
  return {m.z * m.z, s2, s2 > 0.0 ? m.x * m.x / s2 : 1.0, s2 > 0.0 ? m.y * m.y / s2 : 0.0};
}

// The slope ellipse's factor cos²φ/ax² + sin²φ/ay².
double ellipse(const Angles& a, double ax, double ay) { return a.cos2phi / (ax * ax) + a.sin2phi / (ay * ay); }

glm::dvec3 slice_normal(double NoH) {
  const double c = saturate(NoH);
  return {std::sqrt(sin2_from_cos(c)), 0.0, c};
}

}  // namespace

double D_ggx_aniso(const glm::dvec3& m, double ax, double ay) {
  // Heitz 2014 (anisotropic GGX); Burley 2012 appendix B, GTR2 aniso:
  //   D = 1 / (π ax ay cos⁴θ (1 + tan²θ (cos²φ/ax² + sin²φ/ay²))²)
  //     = 1 / (π ax ay (cos²θ + sin²θ (cos²φ/ax² + sin²φ/ay²))²)
  // (multiplied through by cos⁴θ: no tan²θ, finite at θ = π/2).
  if (m.z <= 0.0) return 0.0;  // χ+(m·n)
  const Angles a = angles_of(m);
  const double k = a.cos2 + a.sin2 * ellipse(a, ax, ay);
  return 1.0 / (kPi * ax * ay * k * k);
}

double D_beckmann_aniso(const glm::dvec3& m, double ax, double ay) {
  // Heitz 2014 (anisotropic Beckmann):
  //   D = exp(-tan²θ (cos²φ/ax² + sin²φ/ay²)) / (π ax ay cos⁴θ)
  if (m.z <= 0.0) return 0.0;  // χ+(m·n)
  const Angles a = angles_of(m);
  const double e = std::exp(-(a.sin2 / a.cos2) * ellipse(a, ax, ay));
  if (e == 0.0) return 0.0;  // θ→π/2: the exponential wins, D→0 (no 0/0)
  return e / (kPi * ax * ay * a.cos2 * a.cos2);
}

double D_ggx_aniso_slice(double NoH, double alpha) {
  return NoH <= 0.0 ? 0.0 : D_ggx_aniso(slice_normal(NoH), alpha, alpha);
}
double D_beckmann_aniso_slice(double NoH, double alpha) {
  return NoH <= 0.0 ? 0.0 : D_beckmann_aniso(slice_normal(NoH), alpha, alpha);
}

}  // namespace mfv::ref

// ---- Sheen ------------------------------------------------------------------

namespace mfv::ref {

double D_charlie_cs(double cos2, double sin2, double alpha) {
  // Estevez and Kulla 2017, "Production Friendly Microfacet Sheen BRDF",
  // eq. 2 (KHR_materials_sheen "Sheen distribution", alphaG = sheenRoughness):
  //   D(m) = (2 + 1/α) sin^(1/α)θ / (2π)
  // Normalised: ∫ D cosθ dω = (2 + 1/α) ∫_0^1 s^(1/α + 1) ds = 1 (s = sinθ).
  // sin^(1/α)θ = (sin²θ)^(1/(2α)); the mass sits at grazing m (fibres), none
  // at the normal (D = 0 there for every α < ∞).
  if (!(cos2 > 0.0)) return 0.0;  // χ+(m·n)
  return (2.0 + 1.0 / alpha) * std::pow(std::min(sin2, 1.0), 0.5 / alpha) / (2.0 * kPi);
}

double D_charlie(double NoH, double alpha) {
  if (NoH <= 0.0) return 0.0;  // χ+(m·n)
  const double c = saturate(NoH);
  return D_charlie_cs(c * c, sin2_from_cos(c), alpha);
}

}  // namespace mfv::ref
