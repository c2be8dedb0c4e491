// Scalar double-precision reference for every catalog term (docs/design.md §2).
//
// Written from the seeds' formulas (../shared/seeds/) and the cited papers,
// independently of kernels/: agreement between the two is the evidence.
// Conventions shared with the kernels:
//   * local shading frame, n = +z; all directions point away from the surface;
//   * D(m) is normalised so that  ∫ D(m) (m·n) dm = 1  over the hemisphere;
//   * G terms return the full G2 (not the visibility G2 / (4 NoL NoV));
//   * every term takes its *native* parameter (alpha, alpha_p, rho, m, eta...);
//     conversions from the shared width alpha live in host/catalog/roughness.hpp.
#pragma once

#include <glm/vec3.hpp>

namespace mfv::ref {

// ---- D: microfacet distributions, argument NoH = cos(theta_h) -------------
double D_phong(double NoH, double alpha_p);    // seed 000 "Phong", seed 003 Blinn
double D_beckmann(double NoH, double alpha);   // seed 000 "Beckman"
double D_ggx(double NoH, double alpha);        // seed 000 "GGX"
double D_blinn_rho(double NoH, double rho);    // seed 004 Cook-Torrance "blinn version"
double D_beckmann_ct82(double NoH, double m);  // seed 001, as written (known bad)
// GGX from cos²θ and sin²θ given apart (e.g. from a half vector's components),
// for θ below ~1e-8 where a double cosine no longer resolves 1 − cosθ.
double D_ggx_cs(double cos2, double sin2, double alpha);
// Beckmann and seed 001's form likewise: tan²θ = sin²θ / cos²θ without 1 − cos²θ.
double D_beckmann_cs(double cos2, double sin2, double alpha);
double D_beckmann_ct82_cs(double cos2, double sin2, double m);
// Phong and seed 004's rho form: (n·h)^e = exp((e/2) log1p(−sin²θ)) near the peak.
double D_phong_cs(double cos2, double sin2, double alpha_p);
double D_blinn_rho_cs(double cos2, double sin2, double rho);
// Estevez and Kulla 2017 "Charlie" sheen: (2 + 1/α) sin^(1/α)θ / (2π), α in (0, 1]
double D_charlie(double NoH, double alpha);
double D_charlie_cs(double cos2, double sin2, double alpha);

// ---- Anisotropic D, tangent frame t = +x, b = +y, n = +z ------------------
// m: the microfacet normal (need not be unit: it is made unit first); ax, ay:
// the widths along t and b. The *_slice forms are the one-width view the
// generic checks take (m in the xz-plane, ay = ax): equal to D_ggx/D_beckmann.
double D_ggx_aniso(const glm::dvec3& m, double ax, double ay);       // Heitz 2014; Burley 2012 app. B
double D_beckmann_aniso(const glm::dvec3& m, double ax, double ay);  // Heitz 2014
double D_ggx_aniso_slice(double NoH, double alpha);
double D_beckmann_aniso_slice(double NoH, double alpha);

// ---- Smith Lambda and G1 (one direction), argument NoV = cos(theta_v) -----
double Lambda_beckmann(double NoV, double alpha);  // exact, with erf
double Lambda_ggx(double NoV, double alpha);
double G1_smith_beckmann(double NoV, double alpha);         // 1 / (1 + Lambda)
double G1_smith_beckmann_approx(double NoV, double alpha);  // seed 000 rational
double G1_smith_phong(double NoV, double alpha_p);          // seed 000, a = sqrt(ap/2+1)/tan
double G1_smith_ggx(double NoV, double alpha);              // seed 000 "GGX"
// Estevez and Kulla 2017's fitted Λ of the Charlie sheen D (KHR_materials_sheen "Sheen visibility")
double Lambda_charlie(double NoV, double alpha);
double G1_charlie(double NoV, double alpha);  // 1 / (1 + Lambda_charlie)

// Anisotropic Smith: the isotropic Λ at the projected width
// α_o = sqrt(cos²φ ax² + sin²φ ay²) of the direction v's azimuth φ (Heitz 2014).
double alpha_projected(const glm::dvec3& v, double ax, double ay);
double Lambda_ggx_aniso(const glm::dvec3& v, double ax, double ay);
double Lambda_beckmann_aniso(const glm::dvec3& v, double ax, double ay);
double G1_smith_ggx_aniso(const glm::dvec3& v, double ax, double ay);
double G1_smith_beckmann_aniso(const glm::dvec3& v, double ax, double ay);
double G1_smith_ggx_aniso_slice(double NoV, double alpha);
double G1_smith_beckmann_aniso_slice(double NoV, double alpha);

// ---- G2: shadowing-masking for the pair, all return G (not visibility) ----
// Arguments: NoL, NoV, NoH, VoH (= LoH for the exact half vector), param.
double G_implicit(double NoL, double NoV, double NoH, double VoH, double unused);
double G_kelemen(double NoL, double NoV, double NoH, double VoH, double unused);
double G_cook_torrance(double NoL, double NoV, double NoH, double VoH, double unused);
// Smith's separable form of a G1 above: G = G1(l) G1(v) (seed 000's "Smith
// form G = G1(L, H) G1(V, H)"; Heitz 2014, eq. 98: separable, uncorrelated),
// 0 unless both directions are above the surface and in front of the facet.
template <double (*G1)(double NoV, double width)>
double G_smith_separable(double NoL, double NoV, double NoH, double VoH, double width);
inline constexpr auto G_smith_beckmann_approx = &G_smith_separable<G1_smith_beckmann_approx>;  // Walter 2007, eq. 27
inline constexpr auto G_smith_beckmann = &G_smith_separable<G1_smith_beckmann>;  // G1 exact: Walter 2007, eq. 26
inline constexpr auto G_smith_phong = &G_smith_separable<G1_smith_phong>;        // seed 000 "Phong"; width alpha_p
inline constexpr auto G_smith_ggx = &G_smith_separable<G1_smith_ggx>;            // seed 000 "GGX"; Walter 2007, eq. 34
double G_smith_ggx_correlated(double NoL, double NoV, double NoH, double VoH, double alpha);
double G_hammon_002(double NoL, double NoV, double NoH, double VoH, double alpha);
// KHR_materials_sheen's Charlie visibility times 4 NoL NoV: 1 / (1 + Λ(l) + Λ(v))
double G_charlie_sheen(double NoL, double NoV, double NoH, double VoH, double alpha);
// Hammon 2017's fit of height-correlated Smith-GGX, the fit's cosines floored at 1e-4
double G_hammon_clamped(double NoL, double NoV, double NoH, double VoH, double alpha);
// Neubelt and Pettineo 2013's cloth (sheen) visibility times 4 NoL NoV: NoL NoV / (NoL + NoV - NoL NoV)
double G_neubelt_sheen(double NoL, double NoV, double NoH, double VoH, double unused);
// Anisotropic separable Smith G1(l) G1(v) (directions l, v; VoH for the χ+ test).
double G_smith_ggx_aniso(const glm::dvec3& l, const glm::dvec3& v, double VoH, double ax, double ay);
double G_smith_beckmann_aniso(const glm::dvec3& l, const glm::dvec3& v, double VoH, double ax, double ay);
double G_smith_ggx_aniso_slice(double NoL, double NoV, double NoH, double VoH, double alpha);
double G_smith_beckmann_aniso_slice(double NoL, double NoV, double NoH, double VoH, double alpha);

// ---- F: Fresnel reflectance of one colour channel, argument VoH ----------
double F_none(double VoH, double unused0, double unused1);
double F_schlick(double VoH, double f0, double unused);
double F_dielectric(double VoH, double eta, double unused);  // eta = eta_t / eta_i
double F_conductor(double VoH, double n, double k);          // complex index n + i k
double F_schlick_f90(double VoH, double f0, double f90);      // Schlick with the grazing value f90
double F_schlick_sg(double VoH, double f0, double unused);    // Karis 2013's spherical-Gaussian Schlick

}  // namespace mfv::ref
