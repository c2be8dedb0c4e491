// Reference shadowing-masking terms: Smith Λ, G1 (one direction) and G2.
//
// G1 argument: NoV = cos(theta_v) of the direction being masked.
// G2 functions return the full G2 (not the visibility G2 / (4 NoL NoV)).
//
// Guards shared by every G1 (seed 000, "Beware roundoff errors in calculating
// the G1 function"):
//   * NoV <= 0      → G1 = 0: θ→π/2 makes tanθ→∞, so Λ→∞ and G1→0; a
//                     direction below the horizon is fully masked.
//   * NoV >= 1      → G1 = 1: a dot product that rounded above 1 is normal
//                     incidence, where nothing is masked (seed 000: "return 1").
//   * tan²θ == 0    → G1 = 1: never divide by tanθ (seed 000: "return 1").
// Parameter ranges (alpha > 0, alpha_p >= 0) are validated by the catalog.
#include "reference/reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "reference/math_util.hpp"

namespace mfv::ref {

using detail::kPi;
using detail::tan2_from_cos;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// χ+ factors of a two-sided G2 built on the half vector: both directions above
// the macro-surface and in front of the facet (VoH = LoH for the exact half
// vector, so one test covers both χ+(v·h) and χ+(l·h)).
bool pair_visible(double NoL, double NoV, double VoH) { return NoL > 0.0 && NoV > 0.0 && VoH > 0.0; }

// Walter et al. 2007, eq. 27; seed 000, "Beckman" G1: rational approximation
// of the Smith-Beckmann G1 in a = cotθ / width.  The constants 3.535, 2.181,
// 2.276, 2.577 and the cut-off 1.6 are the seed's (Walter's) values.
double g1_beckmann_rational(double a) {
  if (a >= 1.6) return 1.0;
  return (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
}

}  // namespace

// ---- Smith Lambda ---------------------------------------------------------

double Lambda_beckmann(double NoV, double alpha) {
  // Heitz 2014, "Understanding the masking-shadowing function", Λ of the
  // Beckmann distribution (Walter et al. 2007, eq. 26, is 1 / (1 + Λ)):
  //   a = 1 / (alpha tanθ),  Λ = (erf(a) − 1)/2 + exp(−a²) / (2 a √π)
  // erf(a) − 1 is written −erfc(a): the same value without the cancellation
  // that erases it for large a.
  if (NoV <= 0.0) return kInf;  // θ→π/2 (or below): Λ→∞
  const double tan2 = tan2_from_cos(NoV);
  if (tan2 == 0.0) return 0.0;  // θ = 0 (NoV >= 1): a = ∞, Λ = 0
  const double a = 1.0 / (alpha * std::sqrt(tan2));
  // a → 0 (tanθ = +inf for NoV below ~1e-162): exp(0)/0 = +inf, Λ = +inf.
  return -0.5 * std::erfc(a) + std::exp(-a * a) / (2.0 * a * std::sqrt(kPi));
}

double Lambda_ggx(double NoV, double alpha) {
  // Heitz 2014, Λ of the GGX distribution (its G1 is Walter et al. 2007,
  // eq. 34):  Λ = (−1 + sqrt(1 + alpha² tan²θ)) / 2
  // Evaluated as x / (2 (1 + sqrt(1 + x))), x = alpha² tan²θ, the same value
  // multiplied through by (1 + sqrt(1 + x)): no cancellation for small x.
  if (NoV <= 0.0) return kInf;  // θ→π/2 (or below): Λ→∞
  const double tan2 = tan2_from_cos(NoV);
  if (tan2 == 0.0) return 0.0;  // θ = 0: Λ = 0
  const double x = alpha * alpha * tan2;
  if (std::isinf(x)) return kInf;  // tanθ overflowed: Λ→∞ (and no inf/inf)
  return x / (2.0 * (1.0 + std::sqrt(1.0 + x)));
}

// ---- G1 -------------------------------------------------------------------

double G1_smith_beckmann(double NoV, double alpha) {
  // Smith 1967 / Heitz 2014: G1 = 1 / (1 + Λ)   (Walter et al. 2007, eq. 26)
  if (NoV <= 0.0) return 0.0;  // θ→π/2: Λ→∞, so G1→0
  if (NoV >= 1.0) return 1.0;  // seed 000: NoV rounded above 1 → G1 = 1
  return 1.0 / (1.0 + Lambda_beckmann(NoV, alpha));
}

double G1_smith_beckmann_approx(double NoV, double alpha) {
  // seed 000, "Beckman" G1 (Walter et al. 2007, eq. 27), a = 1/(alpha_b tanθ)
  if (NoV <= 0.0) return 0.0;  // θ→π/2: a→0 and the rational →0
  if (NoV >= 1.0) return 1.0;  // seed 000: NoV rounded above 1 → G1 = 1
  const double tan2 = tan2_from_cos(NoV);
  if (tan2 == 0.0) return 1.0;  // seed 000: tanθ = 0 → do not divide, G1 = 1
  const double a = 1.0 / (alpha * std::sqrt(tan2));
  return g1_beckmann_rational(a);
}

double G1_smith_phong(double NoV, double alpha_p) {
  // seed 000, "Phong" G1: the Beckmann rational with a = sqrt(alpha_p/2 + 1) / tanθ
  if (NoV <= 0.0) return 0.0;  // θ→π/2: a→0 and the rational →0
  if (NoV >= 1.0) return 1.0;  // seed 000: NoV rounded above 1 → G1 = 1
  const double tan2 = tan2_from_cos(NoV);
  if (tan2 == 0.0) return 1.0;  // seed 000: tanθ = 0 → do not divide, G1 = 1
  const double a = std::sqrt(alpha_p / 2.0 + 1.0) / std::sqrt(tan2);
  return g1_beckmann_rational(a);
}

double G1_smith_ggx(double NoV, double alpha) {
  // seed 000, "GGX"; Walter et al. 2007, eq. 34:
  //   G1 = 2 / (1 + sqrt(1 + alpha² tan²θ))
  if (NoV <= 0.0) return 0.0;  // θ→π/2: tanθ→∞, so G1→0
  if (NoV >= 1.0) return 1.0;  // seed 000: NoV rounded above 1 → G1 = 1
  const double tan2 = tan2_from_cos(NoV);
  if (tan2 == 0.0) return 1.0;  // seed 000: tanθ = 0 → G1 = 1
  // tan2 = +inf (NoV below ~1e-162) gives 2 / inf = 0: the θ→π/2 limit.
  return 2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha * tan2));
}

// ---- G2 -------------------------------------------------------------------

double G_implicit(double NoL, double NoV, double, double, double) {
  // seed 000, "A simple approx is: V(L, V) = 1", V = G / (NoL NoV)
  //   ⇒ G = NoL NoV
  if (NoL <= 0.0 || NoV <= 0.0) return 0.0;  // below the horizon
  return NoL * NoV;
}

double G_kelemen(double NoL, double NoV, double, double VoH, double) {
  // seed 000, "Better approx is: V(L, V) ≈ 1/(L·H)²" (Kelemen and
  // Szirmay-Kalos 2001), V = G / (NoL NoV)  ⇒  G = NoL NoV / (L·H)²,
  // with L·H = V·H for the exact half vector.  Not bounded by 1.
  if (!pair_visible(NoL, NoV, VoH)) return 0.0;  // also: never divide by VoH = 0
  return NoL * NoV / (VoH * VoH);
}

double G_cook_torrance(double NoL, double NoV, double NoH, double VoH, double) {
  // seed 003, "The Geometric Term"; seed 004, G; seed 001, "Geometric Term, G"
  // (V-cavity, Torrance-Sparrow 1967 / Cook-Torrance 1982):
  //   G = min(1, 2 (n·h)(n·v) / (v·h), 2 (n·h)(n·l) / (v·h))
  // seed 001 prints "G = (1, G_m, G_s)": the "min" is lost in the slide; 003
  // and 004 have it.  Its two quotients use h·s (= L·H) where 004 uses
  // v·h; both are the same number for the exact half vector.
  if (!pair_visible(NoL, NoV, VoH)) return 0.0;  // also: never divide by VoH = 0
  const double masking = 2.0 * NoH * NoV / VoH;
  const double shadowing = 2.0 * NoH * NoL / VoH;
  return std::min({1.0, masking, shadowing});
}

template <double (*G1)(double, double)>
double G_smith_separable(double NoL, double NoV, double, double VoH, double width) {
  // seed 000, Smith form G = G1(L, H) G1(V, H) (Heitz 2014, eq. 98: separable, uncorrelated)
  if (!pair_visible(NoL, NoV, VoH)) return 0.0;  // χ+ factors
  return G1(NoL, width) * G1(NoV, width);
}
// The catalog's four (reference.hpp): the Beckmann rational, exact Beckmann, "Phong" and "GGX" G1s of seed 000.
template double G_smith_separable<G1_smith_beckmann_approx>(double, double, double, double, double);
template double G_smith_separable<G1_smith_beckmann>(double, double, double, double, double);
template double G_smith_separable<G1_smith_phong>(double, double, double, double, double);
template double G_smith_separable<G1_smith_ggx>(double, double, double, double, double);

double G_smith_ggx_correlated(double NoL, double NoV, double, double VoH, double alpha) {
  // Heitz 2014, "Understanding the masking-shadowing function", eq. 99
  // (height-correlated):  G2 = 1 / (1 + Λ(ω_o) + Λ(ω_i))
  if (!pair_visible(NoL, NoV, VoH)) return 0.0;  // χ+ factors
  return 1.0 / (1.0 + Lambda_ggx(NoL, alpha) + Lambda_ggx(NoV, alpha));
}

double G_hammon_002(double NoL, double NoV, double, double, double alpha) {
  // seed 002, `geometry` (Hammon 2017's fit to height-correlated Smith-GGX):
  //   V = 0.5 / max(0.01, mix(2 NoL NoV, NoL + NoV, roughness)),
  //   mix(a, b, t) = a (1 − t) + b t (GLSL), and G = 4 NoL NoV V.
  // The seed squares its roughness before the call, so its `roughness`
  // argument is already the width alpha.  The seed takes |N·L|, |N·V|
  // (mirroring back faces); this reference returns 0 below the horizon like
  // every other G2.  0.01 is the seed's floor on the denominator.
  if (NoL <= 0.0 || NoV <= 0.0) return 0.0;  // below the horizon
  const double a = 2.0 * NoL * NoV;
  const double b = NoL + NoV;
  const double mixed = a * (1.0 - alpha) + b * alpha;
  const double V = 0.5 / std::max(0.01, mixed);
  return 4.0 * NoL * NoV * V;
}

double G_hammon_clamped(double NoL, double NoV, double, double, double alpha) {
  // Hammon 2017, "PBR Diffuse Lighting for GGX+Smith Microsurfaces",
  // "Approximating G2": G2 ~ 0.5 / lerp(2 |n.l||n.v|, |n.l| + |n.v|, alpha)
  // as the visibility V = G2 / (4 |n.l||n.v|), so G = 4 (n.l)(n.v) V.
  // The engine's clamp: the fit's cosines floored at 1e-4 (n.v -> 0 would
  // make V grow without bound at alpha = 0), all cosines at most 1.
  if (NoL <= 0.0 || NoV <= 0.0) return 0.0;  // below the horizon
  const double l = std::min(NoL, 1.0), v = std::min(NoV, 1.0);
  const double fl = std::max(l, 1e-4), fv = std::max(v, 1e-4);
  const double lerp = 2.0 * fl * fv + (fl + fv - 2.0 * fl * fv) * alpha;
  return 4.0 * l * v * (0.5 / lerp);
}

// ---- Anisotropic Smith ---------------------------------------------------
// Heitz 2014, "Understanding the masking-shadowing function", anisotropic
// distributions: stretching the microsurface by (1/ax, 1/ay) maps it onto
// the isotropic one of width 1, so the anisotropic Λ(ω) is the isotropic Λ at
// the projected width α_o = sqrt(cos²φ ax² + sin²φ ay²) of ω's azimuth φ.
// Tangent frame t = +x, b = +y, n = +z. Directions need not be unit.

namespace {
glm::dvec3 unit(const glm::dvec3& v) { return v / std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }
glm::dvec3 slice_dir(double NoV) {
  const double c = std::clamp(NoV, -1.0, 1.0);
  return {std::sqrt(std::max(0.0, (1.0 - c) * (1.0 + c))), 0.0, c};
}
}  // namespace

double alpha_projected(const glm::dvec3& v, double ax, double ay) {
  const double s2 = v.x * v.x + v.y * v.y;
  if (s2 == 0.0) return ax;  // at the normal the azimuth is undefined (and tanθ = 0)
  const double cos2phi = v.x * v.x / s2, sin2phi = v.y * v.y / s2;  // apart: 1 − cos²φ cancels near φ = 0
  return std::sqrt(cos2phi * ax * ax + sin2phi * ay * ay);
}

// a = 1 / (α_o tanθ) of a direction, tanθ from its own components (a cosine
// near 1 would lose sin²θ); +inf at the normal, 0 at the horizon.
double cot_over_width(const glm::dvec3& v, double ax, double ay) {
  const glm::dvec3 u = unit(v);
  const double s = std::sqrt(u.x * u.x + u.y * u.y);
  if (s == 0.0) return kInf;
  return std::max(u.z, 0.0) / (alpha_projected(v, ax, ay) * s);
}

double Lambda_ggx_aniso(const glm::dvec3& v, double ax, double ay) {
  // Heitz 2014: Λ = (−1 + sqrt(1 + 1/a²)) / 2, as x / (2 (1 + sqrt(1 + x))), x = 1/a²
  const double a = cot_over_width(v, ax, ay);
  if (a == 0.0) return kInf;  // at or below the horizon
  const double x = 1.0 / (a * a);
  return std::isinf(x) ? kInf : x / (2.0 * (1.0 + std::sqrt(1.0 + x)));
}

double Lambda_beckmann_aniso(const glm::dvec3& v, double ax, double ay) {
  // Heitz 2014 / Walter et al. 2007: Λ = (erf(a) − 1)/2 + exp(−a²) / (2 a √π), erf − 1 = −erfc
  const double a = cot_over_width(v, ax, ay);
  if (a == 0.0) return kInf;
  if (std::isinf(a)) return 0.0;
  return -0.5 * std::erfc(a) + std::exp(-a * a) / (2.0 * a * std::sqrt(kPi));
}

double G1_smith_ggx_aniso(const glm::dvec3& v, double ax, double ay) {
  // G1 = 1 / (1 + Λ(α_o)), Walter et al. 2007 eq. 34 at the projected width
  return 1.0 / (1.0 + Lambda_ggx_aniso(v, ax, ay));
}

double G1_smith_beckmann_aniso(const glm::dvec3& v, double ax, double ay) {
  return 1.0 / (1.0 + Lambda_beckmann_aniso(v, ax, ay));
}

double G1_smith_ggx_aniso_slice(double NoV, double alpha) {
  return NoV <= 0.0 ? 0.0 : G1_smith_ggx_aniso(slice_dir(NoV), alpha, alpha);
}
double G1_smith_beckmann_aniso_slice(double NoV, double alpha) {
  return NoV <= 0.0 ? 0.0 : G1_smith_beckmann_aniso(slice_dir(NoV), alpha, alpha);
}

double G_smith_ggx_aniso(const glm::dvec3& l, const glm::dvec3& v, double VoH, double ax, double ay) {
  // separable Smith (Walter et al. 2007 eq. 23) with the anisotropic G1
  if (!pair_visible(l.z, v.z, VoH)) return 0.0;  // χ+ factors
  return G1_smith_ggx_aniso(l, ax, ay) * G1_smith_ggx_aniso(v, ax, ay);
}

double G_smith_beckmann_aniso(const glm::dvec3& l, const glm::dvec3& v, double VoH, double ax, double ay) {
  if (!pair_visible(l.z, v.z, VoH)) return 0.0;  // χ+ factors
  return G1_smith_beckmann_aniso(l, ax, ay) * G1_smith_beckmann_aniso(v, ax, ay);
}

double G_smith_ggx_aniso_slice(double NoL, double NoV, double, double VoH, double alpha) {
  if (!pair_visible(NoL, NoV, VoH)) return 0.0;
  return G_smith_ggx_aniso(slice_dir(NoL), slice_dir(NoV), VoH, alpha, alpha);
}
double G_smith_beckmann_aniso_slice(double NoL, double NoV, double, double VoH, double alpha) {
  if (!pair_visible(NoL, NoV, VoH)) return 0.0;
  return G_smith_beckmann_aniso(slice_dir(NoL), slice_dir(NoV), VoH, alpha, alpha);
}

}  // namespace mfv::ref

// ---- Sheen --------------------------------------------------------------------

namespace mfv::ref {

namespace {
// Estevez and Kulla 2017, "Production Friendly Microfacet Sheen BRDF", §3:
// their fit of ln Λ for the Charlie D, L(x) = a/(1 + b x^c) + d x + e, with
// the coefficients of α = 0 and α = 1 (their table) interpolated in (1 − α)²,
// as KHR_materials_sheen "Sheen visibility" writes it:
// mix(p(α = 1), p(α = 0), (1 − α)²).
double charlie_L(double x, double alpha) {
  const double t = (1.0 - alpha) * (1.0 - alpha);
  auto mix = [t](double at1, double at0) { return at1 * (1.0 - t) + at0 * t; };
  const double a = mix(21.5473, 25.3245), b = mix(3.82987, 3.32435), c = mix(0.19823, 0.16801);
  const double d = mix(-1.97760, -1.27393), e = mix(-4.32054, -4.85967);
  return a / (1.0 + b * std::pow(x, c)) + d * x + e;
}
}  // namespace

double Lambda_charlie(double NoV, double alpha) {
  // Λ(cosθ) = exp(L(cosθ)) for cosθ < 0.5, exp(2 L(0.5) − L(1 − cosθ))
  // above (Estevez and Kulla 2017 §3, which mirrors the fit about 0.5 for
  // the near-normal half). A cosine that rounded above 1 is the normal.
  if (NoV <= 0.0) return std::numeric_limits<double>::infinity();  // grazing: fully masked
  const double c = std::min(NoV, 1.0);
  return c < 0.5 ? std::exp(charlie_L(c, alpha)) : std::exp(2.0 * charlie_L(0.5, alpha) - charlie_L(1.0 - c, alpha));
}

double G1_charlie(double NoV, double alpha) {
  if (NoV <= 0.0) return 0.0;
  return 1.0 / (1.0 + Lambda_charlie(NoV, alpha));
}

double G_charlie_sheen(double NoL, double NoV, double, double VoH, double alpha) {
  // KHR_materials_sheen "Sheen visibility" (the Charlie visibility the spec
  // recommends): V = 1 / ((1 + Λ(n·v) + Λ(n·l)) 4 (n·v)(n·l)), so
  // G = 4 (n·l)(n·v) V = 1 / (1 + Λ(l) + Λ(v)): Heitz 2014 eq. 99's
  // height-correlated form with the Charlie Λ.
  if (NoL <= 0.0 || NoV <= 0.0 || VoH <= 0.0) return 0.0;
  return 1.0 / (1.0 + Lambda_charlie(NoL, alpha) + Lambda_charlie(NoV, alpha));
}

double G_neubelt_sheen(double NoL, double NoV, double, double, double) {
  // Neubelt and Pettineo 2013, "Crafting a Next-Gen Material Pipeline for
  // The Order: 1886" (SIGGRAPH course), the cloth BRDF's visibility after
  // Ashikhmin and Premoze 2007: V = 1 / (4 (n.l + n.v - (n.l)(n.v))).
  // G = 4 (n.l)(n.v) V; cosines that rounded above 1 count as 1.
  if (NoL <= 0.0 || NoV <= 0.0) return 0.0;  // below the horizon
  const double l = std::min(NoL, 1.0), v = std::min(NoV, 1.0);
  const double V = 1.0 / (4.0 * (l + v - l * v));
  return 4.0 * l * v * V;
}

}  // namespace mfv::ref
