// Named plants: one defect per bug, planted in a copy of kernels/
// (test::PlantedKernelDir) by replacing `from` with `to` in `file`, and
// reused by every test that shows a check catching it.
#pragma once

#include "kernel_dir.hpp"

#include <string>

namespace mfv::test {

struct Plant {
  const char* name;
  const char* file;
  const char* from;
  const char* to;
};

// GGX's D without its horizon test: n.h <= 0 gives a value, not 0 (issue 27:
// the integrals never sample such h, so only mfv run's pointwise kinds,
// agree and stability, see it).
inline const Plant kGgxNoHorizon = {
    "D_ggx without its horizon test", "terms_d.cl",
    "  real d = R(1.0) / (MFV_PI * a2 * k * k);\n  return NoH <= R(0.0) ? R(0.0) : d;",
    "  real d = R(1.0) / (MFV_PI * a2 * k * k);\n  return d;"};

// G_smith_ggx_correlated's horizon select written `<= 0 ? 0 : g` (the form
// before issue 31's fix): the same floats, but LLVM's SLP pass pairs it with
// D's horizon select and the albedo_mis/albedo_rqmc kernels of every D with
// this G stay scalar, on AVX2 and AVX-512 (tests/test_vectorize_targets.cpp).
inline const Plant kGgxCorrelatedHorizonPaired = {
    "G_smith_ggx_correlated's horizon select as <= 0 ? 0 : g", "terms_g.cl",
    "  return fmin(fmin(NoL, NoV), VoH) > R(0.0) ? g : R(0.0);",
    "  return fmin(fmin(NoL, NoV), VoH) <= R(0.0) ? R(0.0) : g;"};

// G_kelemen's two quotients multiplied as they come, (NoL / VoH) * (NoV /
// VoH) (the form before issue 31's fix): the same floats, but on haswell
// (AVX2) LLVM's SLP pass packs the two divisions into one <2 x float>
// division and every albedo kernel of a program with this G stays scalar
// there, while AVX-512 vectorizes them (tests/test_vectorize_targets.cpp).
inline const Plant kKelemenQuotientsPaired = {
    "G_kelemen's two quotients as one product of two divisions", "terms_g.cl",
    "  real qv = VoH <= R(0.0) ? R(0.0) : NoV / VoH;\n  real g = (NoL / VoH) * qv;",
    "  real g = (NoL / VoH) * (NoV / VoH);"};

// Charlie's G as it was before issue 31 (kernels/terms_g.cl): Lambda_charlie
// evaluating charlie_L at c and at 1 - c, and G1_charlie's and
// G_charlie_sheen's horizon tests as early returns. The same floats, but the
// masking and AlbedoMis kernels of charlie_sheen (masking_values__g23,
// albedo_mis_values__g23) stay scalar on AVX2 while AVX-512 vectorizes them
// (tests/test_vectorize_targets.cpp). With Λ's one L, the early returns
// alone no longer do (measured 6 December 2026).
inline const Plant kCharlieEarlyReturns = {
    "Lambda_charlie's two L's, G1_charlie's and G_charlie_sheen's horizon tests as early returns", "terms_g.cl",
    "  bool low = c < R(0.5);\n  real l = charlie_L(low ? c : R(1.0) - c, alpha);\n"
    "  return mfv_exp(low ? l : R(2.0) * charlie_L(R(0.5), alpha) - l);\n}\n\n"
    "static inline real G1_charlie(real NoV, real alpha) {\n"
    "  // select form: an early return here kept this G's masking and AlbedoMis\n"
    "  // kernels scalar on AVX2 (8-wide on AVX-512; docs/performance.md). At and\n"
    "  // below the horizon Λ is ∞ and g is 0 already; the select says so.\n"
    "  real g = R(1.0) / (R(1.0) + Lambda_charlie(NoV, alpha));\n  return NoV <= R(0.0) ? R(0.0) : g;\n}\n\n"
    "static inline real G_charlie_sheen(real NoL, real NoV, real NoH, real VoH, real alpha) {\n"
    "  // KHR_materials_sheen \"Sheen visibility\" (Charlie): V = 1/((1 + Λ(v) + Λ(l)) 4 (n·v)(n·l)),\n"
    "  // returned as G = 4 (n·l)(n·v) V = 1/(1 + Λ(l) + Λ(v))\n  // select form, as G1_charlie's\n"
    "  real g = R(1.0) / (R(1.0) + (Lambda_charlie(NoL, alpha) + Lambda_charlie(NoV, alpha)));  // symmetric in l, v "
    "to the bit\n  return ((NoL <= R(0.0)) | (NoV <= R(0.0)) | (VoH <= R(0.0))) ? R(0.0) : g;",
    "  return c < R(0.5) ? mfv_exp(charlie_L(c, alpha))\n"
    "                    : mfv_exp(R(2.0) * charlie_L(R(0.5), alpha) - charlie_L(R(1.0) - c, alpha));\n}\n\n"
    "static inline real G1_charlie(real NoV, real alpha) {\n"
    "  if (NoV <= R(0.0)) return R(0.0);\n  return R(1.0) / (R(1.0) + Lambda_charlie(NoV, alpha));\n}\n\n"
    "static inline real G_charlie_sheen(real NoL, real NoV, real NoH, real VoH, real alpha) {\n"
    "  if (NoL <= R(0.0) || NoV <= R(0.0) || VoH <= R(0.0)) return R(0.0);\n"
    "  return R(1.0) / (R(1.0) + (Lambda_charlie(NoL, alpha) + Lambda_charlie(NoV, alpha)));"};

// G_neubelt_sheen with each cosine clamped first, min(NoL, 1) and min(NoV, 1)
// (the form before issue 31's fix, kernels/terms_g.cl): the same floats, but
// LLVM's SLP pass packs the two clamps into a 2-lane vector, and the generic
// kernels of a program with this G (albedo_values, albedo_mis_values,
// reciprocity_values_microfacet) stay scalar on AVX2 while AVX-512
// vectorizes them (tests/test_vectorize_targets.cpp).
inline const Plant kNeubeltClampsPaired = {
    "G_neubelt_sheen's cosines clamped side by side", "terms_g.cl",
    "  real hi = min(fmax(NoL, NoV), R(1.0));\n  real lo = min(fmin(NoL, NoV), hi);\n"
    "  real den = (lo + hi) - lo * hi;\n  real g = (lo / den) * hi;",
    "  real l = min(NoL, R(1.0)), v = min(NoV, R(1.0));\n  real den = (l + v) - l * v;\n"
    "  real g = (min(l, v) / den) * max(l, v);"};

// model_albedo_value_c's test of the sampled direction as the early return
// it was before (kernels/model_values.cl): the same floats, but the return
// before eval_model reads the parameters leaves their loads conditional,
// LLVM sinks them into the branch (a masked gather on haswell), and
// model_albedo_values__m1 (Lambert) stays scalar on AVX2 while AVX-512
// vectorizes it (tests/test_vectorize_targets.cpp).
inline const Plant kModelAlbedoEarlyReturn = {"model_albedo_value_c's horizon test as an early return",
                                              "model_values.cl", "  real hx, hy, hz;\n  real oh",
                                              "  if (iz <= R(0.0)) return R(0.0);\n  real hx, hy, hz;\n  real oh"};

// The whole-model albedo kernels drawing with mfv_philox, not
// mfv_philox_split (kernels/model_values.cl): the same bits, but in the
// branch-free model code LLVM's SLP pass pairs Philox's two 64-bit products
// into a <2 x i64> multiply, and model_albedo_values__m1 stays scalar on
// AVX-512 while AVX2 vectorizes it (tests/test_vectorize_targets.cpp).
inline const Plant kModelAlbedoPhiloxPaired = {
    "the whole-model albedo kernels drawing with mfv_philox", "model_values.cl",
    "  MFV_SAMPLE_VALUES_DRAWN(NAME, mfv_philox_split,", "  MFV_SAMPLE_VALUES_DRAWN(NAME, mfv_philox,"};

// above_horizons's test as fmin(lz, vz) <= 0 (the form first tried): the
// same floats, but in a reciprocity kernel f(a, b) and f(b, a) then test
// fmin(b.z, a.z) and fmin(a.z, b.z), which LLVM does not merge and its SLP
// pass packs into a 2-lane vector: model_reciprocity_values__m1 (Lambert)
// goes scalar on both targets (tests/test_vectorize_targets.cpp).
inline const Plant kHorizonsFmin = {"above_horizons as fmin(lz, vz) <= 0", "models.cl",
                                    "  return ((lz <= R(0.0)) | (vz <= R(0.0))) ? R(0.0) : f;",
                                    "  return fmin(lz, vz) <= R(0.0) ? R(0.0) : f;"};

// Phong's lobe through the library's log1p again, not mfv_log1p
// (kernels/models.cl model_phong): an out-of-line SLEEF call, which keeps
// model_albedo_values__m6 and __m7 (phong_004, phong_normalized) scalar on
// both targets (tests/test_vectorize_targets.cpp).
inline const Plant kPhongLibraryLog1p = {"Phong's lobe through the library's log1p", "models.cl",
                                         "mfv_exp(p[1] * mfv_log1p(R(-0.5) * d2))",
                                         "mfv_exp(p[1] * log1p(R(-0.5) * d2))"};

// EON's E_FON at l in the same block as at v (kernels/models.cl model_eon):
// the same floats, but LLVM's SLP pass pairs the two evaluations into 2-lane
// vectors, and model_albedo_values__m3 goes scalar on both targets
// (tests/test_vectorize_targets.cpp).
inline const Plant kEonFonPaired = {"EON's two E_FON in one block", "models.cl",
                                    "  if (r == r) e_l = eon_E_fon(l.z, r);", "  e_l = eon_E_fon(l.z, r);"};

// Ward's exponent as the sum of two separate squares (kernels/models.cl
// ward_exp): a 2-lane reduction for LLVM's SLP pass, which keeps
// model_albedo_values__m9 (ward_004) scalar on AVX2 while AVX-512
// vectorizes it (tests/test_vectorize_targets.cpp).
inline const Plant kWardSquaresPaired = {"Ward's exponent as two separate squares", "models.cl",
                                         "  return exp(-(tx * tx + ty * ty) / (h.z * h.z));",
                                         "  return exp(-(sqr(tx) + sqr(ty)) / (h.z * h.z));"};

// oren_nayar's two clamps min(l.z, 1) and min(v.z, 1) side by side, as before
// issue 31's fix (kernels/models.cl model_oren_nayar): the same floats, but
// LLVM's SLP pass pairs them into one <2 x float> compare and select, and
// model_albedo_values__m2 stays scalar on AVX2 while AVX-512 vectorizes it
// (tests/test_vectorize_targets.cpp).
inline const Plant kOrenNayarClampsPaired = {
    "oren_nayar's two clamps side by side", "models.cl",
    "  real cr = min(v.z, R(1.0));\n  bool l_lower = l.z < cr;\n"
    "  real si2 = l.x * l.x + l.y * l.y, sr2 = v.x * v.x + v.y * v.y;  // sin² from the components\n"
    "  real sin_a = sqrt(l_lower ? si2 : sr2);\n"
    "  real sin_b = sqrt(l_lower ? sr2 : si2), cos_b = min(max(cr, l.z), R(1.0));",
    "  real ci = min(l.z, R(1.0)), cr = min(v.z, R(1.0));\n"
    "  real si2 = l.x * l.x + l.y * l.y, sr2 = v.x * v.x + v.y * v.y;  // sin² from the components\n"
    "  real sin_a = sqrt(ci < cr ? si2 : sr2);\n"
    "  real sin_b = sqrt(ci < cr ? sr2 : si2), cos_b = max(ci, cr);"};

// The whole-model reciprocity kernel taking f(b, a) as it comes, not f(b, a) +
// 0 (kernels/reciprocity.cl MFV_MODEL_RECIPROCITY_VALUES): the same floats,
// but reciprocity_asym's operations on the two values are isomorphic pairs
// from which LLVM's SLP pass pairs both evaluations into 2-lane vectors:
// model_reciprocity_values__m4 (toon_diffuse) stays scalar on AVX2 and
// model_reciprocity_values__m11 (cook_torrance_004) on both targets
// (tests/test_vectorize_targets.cpp).
inline const Plant kModelReciprocityPaired = {"the whole-model reciprocity kernel's two evaluations paired",
                                              "reciprocity.cl", "eval_model(MODEL, b, a, p) + R(0.0),",
                                              "eval_model(MODEL, b, a, p),"};

// gltf_sheen's two table lookups in one form (kernels/model_gltf.cl
// model_gltf_sheen, without fabs): the same floats, but LLVM's SLP pass
// pairs them into 2-lane vectors, and its kernel stays scalar.
inline const Plant kSheenLookupsPaired = {"gltf_sheen's two table lookups paired", "model_gltf.cl",
                                          "R(1.0) - max3 * fabs(sheen_E(NoL, sa)));",
                                          "R(1.0) - max3 * sheen_E(NoL, sa));"};

// model_gltf without MFV_ALWAYS_INLINE, as before issue 31's glTF
// reciprocity kernels: called twice in a whole-model reciprocity kernel (and
// through gltf_clearcoat, _clearcoat_aniso and _sheen), LLVM keeps it out of
// line, and the call keeps those four kernels scalar on both targets.
inline const Plant kGltfOutOfLine = {"model_gltf left to the inliner", "model_gltf.cl",
                                     "static inline MFV_ALWAYS_INLINE real model_gltf(",
                                     "static inline real model_gltf("};

// gltf_transmission's two halves as two calls of one thin-walled lobe, as
// they were before (kernels/model_gltf.cl): the reflected half at v and the
// transmitted half at v mirrored below. The same floats, but LLVM's SLP pass
// pairs the two calls' selects and their sum into 2-lane vectors, and the
// model's reciprocity kernel stays scalar on AVX2. The new body is left
// after the planted return, unreached.
inline const Plant kTransmissionHalvesPaired = {
    "gltf_transmission's two halves as two calls", "model_gltf.cl",
    "static inline MFV_ALWAYS_INLINE real model_gltf_transmission(real3 l, real3 v, const real* p) {\n",
    "static inline MFV_ALWAYS_INLINE real gltf_thin_walled(real lx, real ly, real lz, real vx, real vy, real vz,\n"
    "                                                      const real* p) {\n"
    "  real alpha = p[0], metallic = p[1], base = p[2], f0 = p[3], transmission = p[4];\n"
    "  bool below = vz < R(0.0);\n"
    "  real3 l = (real3)(lx, ly, lz), lm = (real3)(vx, vy, fabs(vz));\n"
    "  real NoL = l.z, NoV = lm.z, s2, VoH;\n"
    "  real3 h = half_vector(l, lm, &s2, &VoH);\n"
    "  real x = R(1.0) - VoH, fw = x * x * x * x * x, fr = f0 + (R(1.0) - f0) * fw;\n"
    "  real spec = over_4_cosines(D_ggx(h.z, s2, alpha) * G_smith_ggx_correlated(NoL, NoV, h.z, VoH, alpha),\n"
    "                             NoL, NoV);\n"
    "  real through = (R(1.0) - metallic) * (R(1.0) - fr) * transmission * base * spec;\n"
    "  real dielectric = (R(1.0) - fr) * (R(1.0) - transmission) * base * MFV_INV_PI + fr * spec;\n"
    "  real metal = (base + (R(1.0) - base) * fw) * spec;\n"
    "  real f = below ? through : (R(1.0) - metallic) * dielectric + metallic * metal;\n"
    "  return no_half_vector(NoL, NoV, VoH) ? R(0.0) : f;\n"
    "}\n"
    "static inline MFV_ALWAYS_INLINE real model_gltf_transmission(real3 l, real3 v, const real* p) {\n"
    "  return above_horizons(l.z, v.z, gltf_thin_walled(l.x, l.y, l.z, v.x, v.y, v.z, p) +\n"
    "                                      gltf_thin_walled(l.x, l.y, l.z, v.x, v.y, -v.z, p));\n"};

// Lambda_ggx_aniso's α²sin² as two separate squares, as before issue 31:
// LLVM's SLP pass pairs them, and the anisotropic glTF models' kernels stay
// scalar on AVX2.
inline const Plant kLambdaAnisoSquaresPaired = {"Lambda_ggx_aniso's two squares paired", "terms_g.cl",
                                                "  real q = tx * tx + ty * ty;",
                                                "  real q = sqr(tx) + sqr(ty);"};

// The rough dielectric BTDF with eta_o in place of eta_o^2 in the numerator
// of Walter et al. 2007 eq. 21 (kernels/btdf.cl): a correct catalog entry's
// transmitted flux off by a factor eta (issue 29: bsdf_furnace sees it).
inline const Plant kBtdfEtaNotSquared = {"the BTDF with eta_o in place of eta_o^2", "btdf.cl",
                                         "variant == MFV_BTDF_BAD_NO_ETA2 ? R(1.0) : eta * eta;",
                                         "variant == MFV_BTDF_BAD_NO_ETA2 ? R(1.0) : eta;"};

// smith_ggx's G1 with half its Λ (kernels/terms_g.cl): it under-masks GGX's D,
// from above and from below (issue 29: transmission_masking sees it).
inline const Plant kGgxG1HalfLambda = {"smith_ggx's G1 with half its Lambda", "terms_g.cl",
                                       "return R(1.0) / (R(1.0) + Lambda_ggx(NoV, alpha));",
                                       "return R(1.0) / (R(1.0) + R(0.5) * Lambda_ggx(NoV, alpha));"};

// GGX's D with pi written as 3.1416 (kernels/terms_d.cl): every GGX value
// off by 2.3e-6 relative, which no statistic sees; the same-sample reference
// comparison does, also at the near-mirror grazing point where its bound
// reads the lobe term 2^-46 / (mu w) (checks/reference_compare.cpp: 1.06e-6
// at alpha 1e-4, view cosine 1.35e-4).
inline const Plant kGgxPiRounded = {"D_ggx with pi rounded to 3.1416", "terms_d.cl",
                                    "real d = R(1.0) / (MFV_PI * a2 * k * k);",
                                    "real d = R(1.0) / (R(3.1416) * a2 * k * k);"};

// bsdf_furnace's proposal refracting with the relative index inverted
// (kernels/transmission.cl, flux_mis_direction: eta where Walter et al. 2007
// eq. 40 takes η_i/η_o = 1/eta): its draws no longer follow flux_mis_pdf
// (issue 29: mfv samplers' sphere chi-square sees it).
inline const Plant kFluxRefractEtaInverted = {"bsdf_furnace's proposal refracting with eta inverted",
                                              "transmission.cl", "real kk = R(1.0) / eta, t2",
                                              "real kk = eta, t2"};

// The rough dielectric BTDF's flip for light from below (kernels/btdf.cl)
// keeping eta where it must take 1/eta: leaving a medium treated as entering
// it (issue 29: mfv agree over eta in [0.01, 100] sees it).
inline const Plant kBtdfLeavingEtaNotInverted = {"the BTDF's flip keeping eta for light from below", "btdf.cl",
                                                 "    eta = R(1.0) / eta;\n  }", "  }"};

// 1 - F of the BTDF at the inverted relative index (kernels/btdf.cl):
// the Fresnel from the wrong side, its critical angle where the other side's
// would be (issue 29: mfv agree over eta in [0.01, 100] sees it).
inline const Plant kBtdfFresnelEtaInverted = {"the BTDF's 1 - F at 1/eta", "btdf.cl",
                                              "T_dielectric(variant == MFV_BTDF_BAD_F_AT_N ? lz : IoH, eta)",
                                              "T_dielectric(variant == MFV_BTDF_BAD_F_AT_N ? lz : IoH, R(1.0) / eta)"};

// The BTDF's total-internal-reflection test g² = η² - 1 + c² off by 1e-5
// (kernels/btdf.cl T_dielectric): a critical cosine moved by 5e-6 at
// eta = 0.01, about 170 float roundings of g² where its derived rounding
// bound is about 40 (issue 29: mfv agree's TIR allowance does not hide it).
inline const Plant kBtdfCriticalAngleShifted = {"the BTDF's TIR test off by 1e-5 in g^2", "btdf.cl",
                                                "real g2 = (eta - R(1.0)) * (eta + R(1.0)) + c * c;",
                                                "real g2 = (eta - R(1.0)) * (eta + R(1.0)) + c * c - R(1e-5);"};

// The rough dielectric BSDF's reflection lobe (kernels/transmission.cl
// bsdf_reflect_c) with Schlick's F, F0 = ((eta - 1)/(eta + 1))², in place
// of the exact dielectric Fresnel: F != 0 at eta = 1 (issue 29:
// bsdf_furnace's index-matched points see it).
inline const Plant kBsdfReflectSchlick = {
    "the BSDF's reflection lobe with Schlick's F", "transmission.cl", "real F = R(1.0) - T_dielectric(IoH, eta);",
    "real f0 = sqr((eta - R(1.0)) / (eta + R(1.0)));\n  real F = f0 + (R(1.0) - f0) * pown(R(1.0) - IoH, 5);"};

inline PlantedKernelDir planted(const Plant& p) { return PlantedKernelDir(p.file, p.from, p.to); }

}  // namespace mfv::test
