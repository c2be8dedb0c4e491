// The glTF 2.0 metallic-roughness BRDF, one colour channel, as a whole model
// of the catalog (host/catalog/models.cpp, id "gltf"; issue 7). The generated
// eval_model calls it where a program selects it. Needs terms_d.cl,
// terms_g.cl and models.cl. Reference twin: host/reference/model_gltf.cpp.
//
// Sources: glTF 2.0 specification, Appendix B (B.3.2 specular_brdf = D·Vis
// with the GGX D and the height-correlated Smith G; B.3.3 diffuse_brdf;
// B.3.4 conductor_fresnel and fresnel_mix; B.3.5 material = mix(dielectric,
// metal, metallic)), with KHR_materials_specular's fresnel_mix(f0_color, ior,
// weight, base, layer) = (1 - weight·max(fr)) base + weight·fr·layer and
// KHR_materials_ior's f0 = ((ior - 1)/(ior + 1))².
//
// Parameters p[0..5]:
//   alpha    = roughness²
//   metallic
//   base     = baseColor of this channel
//   f0       = min(f0_ior · specularColor, 1) of this channel (dielectric F0)
//   f0_max   = the largest f0 over the three channels: Schlick's fr grows with
//              f0, so max over channels of fr is fr at f0_max
//   weight   = specularFactor
//   alpha_b  = KHR_materials_anisotropy: the width along b = +y, alpha along
//              t = +x being then alpha_t = mix(roughness², 1, strength²) and
//              alpha_b = roughness²; 0 = isotropic (the path of glTF 2.0 as is)
// The tangent frame is the anisotropy direction's: anisotropyRotation turns
// that direction about n, i.e. the whole (l, v) plane, so the BRDF in its own
// frame does not depend on it (see host/scene/scene.cpp).
// Either direction below the horizon (a NaN cosine compares as there), or no
// half vector (v·h not above 0, NaN included): where the glTF models are 0.
static inline MFV_ALWAYS_INLINE bool no_half_vector(real NoL, real NoV, real VoH) {
  return (NoL <= R(0.0)) | (NoV <= R(0.0)) | !(VoH > R(0.0));
}

static inline MFV_ALWAYS_INLINE real model_gltf(real3 l, real3 v, const real* p) {
  real alpha = p[0], metallic = p[1], base = p[2], f0 = p[3], f0_max = p[4], weight = p[5], alpha_b = p[6];
  real NoL = l.z, NoV = v.z;
  // below the horizon: no reflection. This one return stays (the rest is
  // selected last, below): with it, gltf_sheen's albedo kernel is 8-wide on
  // AVX2 as well; without it, LLVM's SLP pass pairs the sheen's two table
  // lookups there and the kernel is scalar (measured with PoCL 3.1 / LLVM
  // 15, not derived; docs/performance.md)
  if (NoL <= R(0.0) || NoV <= R(0.0)) return R(0.0);
  real s2, VoH;
  real3 h = half_vector(l, v, &s2, &VoH);  // v·h = |l + v|/2: symmetric, no cancellation
  real x = R(1.0) - VoH;
  real fw = x * x * x * x * x;  // (1 - |v·h|)^5
  // specular_brdf(alpha) = D G / (4 (n·l)(n·v)) with the catalog's stable GGX D
  // and height-correlated Smith G (Heitz 2014 eq. 99), one cosine at a time.
  real spec;
  if (alpha_b > R(0.0)) {
    // KHR_materials_anisotropy: anisotropic GGX D (Burley 2012 app. B; Heitz
    // 2014) with alpha_t along t = +x, and the height-correlated Smith
    // G2 = 1 / (1 + Λ(l) + Λ(v)) (Heitz 2014 eq. 99) with the anisotropic Λ at
    // each direction's projected width; the extension's V_GGX_anisotropic is
    // this G2 / (4 (n·l)(n·v)).
    real G = R(1.0) / (R(1.0) + Lambda_ggx_aniso(NoL, l.x, l.y, alpha, alpha_b) +
                       Lambda_ggx_aniso(NoV, v.x, v.y, alpha, alpha_b));
    spec = over_4_cosines(D_ggx_aniso(h.z, h.x, h.y, alpha, alpha_b) * G, NoL, NoV);
  } else {
    spec = over_4_cosines(D_ggx(h.z, s2, alpha) * G_smith_ggx_correlated(NoL, NoV, h.z, VoH, alpha), NoL, NoV);
  }
  real fr = f0 + (R(1.0) - f0) * fw;
  real fr_max = f0_max + (R(1.0) - f0_max) * fw;
  real dielectric = (R(1.0) - weight * fr_max) * base * MFV_INV_PI + weight * fr * spec;
  real metal = (base + (R(1.0) - base) * fw) * spec;  // conductor_fresnel(f0 = baseColor)
  // 0 at l = -v (both at the horizon; in float32 also where l + v
  // underflows): no half vector, h = 0/0, and the Smith G's χ⁺(v·h) is 0
  // there (Heitz 2014 eq. 99), so f is 0, not NaN. Selected last, as the
  // catalog's models do (models.cl, above_horizons): the glTF models' other
  // early returns kept gltf_clearcoat's and gltf_transmission's kernels scalar.
  return no_half_vector(NoL, NoV, VoH) ? R(0.0) : (R(1.0) - metallic) * dielectric + metallic * metal;
}

// KHR_materials_clearcoat over the glTF model, one colour channel (issue 21;
// catalog "gltf_clearcoat"). Reference twin: host/reference/model_gltf.cpp.
// KHR_materials_clearcoat specification, "Layering" and "Implementation":
//   coated_material   = mix(material, clearcoat_brdf, clearcoat · clearcoat_fresnel)
//   clearcoat_fresnel = 0.04 + (1 − 0.04)(1 − |V·Nc|)^5   (fresnel_coat, ior 1.5)
//   clearcoat_brdf    = D(ca) G(ca) / (4 |V·Nc| |L·Nc|),   ca = clearcoatRoughness²
// with Nc = n (no clearcoat normal texture: checked in the surface's frame).
// The coat's Fresnel weight is at n·V, not v·h (the spec's "Discussion"), so
// the layered BRDF is not reciprocal by design, and energy is conserved where
// the spec's Discussion puts it: at a fixed view V the layering is a mix of two
// BRDFs, so ∫ f cos dL <= 1 where base and coat each hold. Light at grazing
// incidence is not (measured: 1.57 for a coated chrome, the coat reflecting F → 1
// while the base keeps 1 − F(n·V) toward the other views). The catalog's
// albedo integrates over its second argument at a fixed first one, so the
// catalog's f(l, v) is the spec's coated_material with V = l and L = v: its
// energy check is the spec's claim; reciprocity is blind to the exchange.
// Parameters p[0..6]: alpha, metallic, base, f0, f0_max of the base material
// (isotropic, specularFactor 1), clearcoat_alpha, clearcoat (last: 0 = no coat,
// the default a whole model's p[6] takes, kernels/agree.cl).
// mix(material, clearcoat_brdf(ca), clearcoat · fresnel_coat(V·Nc)), V = l (above)
static inline MFV_ALWAYS_INLINE real clearcoat_over(real material, real3 l, real3 v, real ca, real clearcoat) {
  real NoL = l.z, NoV = v.z;
  real s2, VoH;
  real3 h = half_vector(l, v, &s2, &VoH);
  real layer = over_4_cosines(D_ggx(h.z, s2, ca) * G_smith_ggx_correlated(NoL, NoV, h.z, VoH, ca), NoL, NoV);
  real x = R(1.0) - NoL;  // the spec's V·Nc (V = the catalog's first direction, see above)
  real weight = clearcoat * (R(0.04) + R(0.96) * x * x * x * x * x);
  // l = -v: no half vector, G's χ⁺(v·h) = 0 (as model_gltf)
  return no_half_vector(NoL, NoV, VoH) ? R(0.0) : (R(1.0) - weight) * material + weight * layer;
}

static inline MFV_ALWAYS_INLINE real model_gltf_clearcoat(real3 l, real3 v, const real* p) {
  real q[7] = {p[0], p[1], p[2], p[3], p[4], R(1.0), R(0.0)};
  return clearcoat_over(model_gltf(l, v, q), l, v, p[5], p[6]);
}

// KHR_materials_clearcoat over a KHR_materials_anisotropy base (issue 21;
// catalog "gltf_clearcoat_aniso"): the same layering over the anisotropic
// glTF model. Parameters p[0..6]: alpha (alpha_t along t = +x), metallic,
// base, f0 (also fresnel_mix's max: an upper bound on the base's energy, as
// gltf_sheen), clearcoat_alpha, clearcoat, alpha_b (last: the second width,
// which stretches the estimators' proposal to (alpha_t, alpha_b) as for gltf).
static inline MFV_ALWAYS_INLINE real model_gltf_clearcoat_aniso(real3 l, real3 v, const real* p) {
  real q[7] = {p[0], p[1], p[2], p[3], p[3], R(1.0), p[6]};
  return clearcoat_over(model_gltf(l, v, q), l, v, p[4], p[5]);
}

// KHR_materials_sheen over the glTF model, one colour channel (issue 21;
// catalog "gltf_sheen"). Reference twin: host/reference/model_gltf.cpp.
// KHR_materials_sheen, "Implementation Notes":
//   f = f_sheen + (f_diffuse + f_specular) · sheenAlbedoScaling
//   f_sheen = sheenColor · D_charlie · V_charlie        (F = 1)
//   sheenAlbedoScaling = min(1 − max3(sheenColor) E(n·v), 1 − max3(sheenColor) E(n·l))
// with E the sheen lobe's directional albedo (white sheenColor), the table
// sheen_E below, which `mfv energy` produces (table charlie/charlie_sheen).
// The min over both directions keeps f reciprocal.
// Parameters p[0..6]: alpha, metallic, base, f0 of the base material
// (isotropic, specularFactor 1, f0_max = f0: fresnel_mix's base weight
// 1 − F(f0_max) only shrinks as f0_max grows, so for channels below the
// largest f0 this is an upper bound on the energy), sheen_alpha
// (sheenRoughness), sheen (this channel's sheenColor), sheen_others (the
// largest of the other two channels; 0 = a grey or single-channel sheen's
// default). max3(sheenColor) = max(sheen, sheen_others).
#include "abi/sheen_table.h"  // E_sheen, shared with the double reference

static inline MFV_ALWAYS_INLINE real sheen_E(real mu, real alpha) {
  // bilinear in (mu, log10 alpha) on the table's grid: mu at cell midpoints
  // (m + 0.5)/N, alpha = 10^(-3 + 3 j/(N - 1)) (checks/energy.cpp's grids)
  real x = clamp(mu * (real)SHEEN_E_N - R(0.5), R(0.0), (real)(SHEEN_E_N - 1));
  // log10 alpha as mfv_log(alpha) / ln 10 (common.cl): the library's log10
  // is a call, which keeps PoCL's work-item loop scalar; its error (log's 2
  // ulps, the product's half) moves y by a few float ulps, the table's
  // bilinear weight with it, and E by as little
  real y = clamp((mfv_log(alpha) * R(0.43429448190325182765) + R(3.0)) / R(3.0) * (real)(SHEEN_E_N - 1), R(0.0),
                 (real)(SHEEN_E_N - 1));
  int i = min((int)x, SHEEN_E_N - 2), j = min((int)y, SHEEN_E_N - 2);
  real fx = x - (real)i, fy = y - (real)j;
  real e0 = mix((real)SHEEN_E[j * SHEEN_E_N + i], (real)SHEEN_E[j * SHEEN_E_N + i + 1], fx);
  real e1 = mix((real)SHEEN_E[(j + 1) * SHEEN_E_N + i], (real)SHEEN_E[(j + 1) * SHEEN_E_N + i + 1], fx);
  return mix(e0, e1, fy);
}

static inline MFV_ALWAYS_INLINE real model_gltf_sheen(real3 l, real3 v, const real* p) {
  real NoL = l.z, NoV = v.z;
  real q[7] = {p[0], p[1], p[2], p[3], p[3], R(1.0), R(0.0)};
  real material = model_gltf(l, v, q);
  real s2, VoH;
  real3 h = half_vector(l, v, &s2, &VoH);
  real sa = p[4], sheen = p[5];
  // no sheen in this channel: no lobe (and no 0 · Inf where the cosines underflow)
  real f_sheen = sheen > R(0.0)
                     ? sheen * over_4_cosines(D_charlie(h.z, s2, sa) * G_charlie_sheen(NoL, NoV, h.z, VoH, sa), NoL, NoV)
                     : R(0.0);
  real max3 = max(sheen, p[6]);
  // fabs(E) = E (E >= 0: a bilinear mix, weights in [0, 1], of albedos),
  // but the two lookups no longer have one form: in one form, LLVM's SLP
  // pass paired them into 2-lane vectors, which kept PoCL's work-item loop
  // scalar (docs/performance.md)
  real scaling = min(R(1.0) - max3 * sheen_E(NoV, sa), R(1.0) - max3 * fabs(sheen_E(NoL, sa)));
  // below the horizon, or l = -v (no half vector, G's χ⁺(v·h) = 0): 0, as model_gltf
  return no_half_vector(NoL, NoV, VoH) ? R(0.0) : f_sheen + material * scaling;
}

// KHR_materials_transmission, thin-walled (issue 29; catalog
// "gltf_transmission"). Reference twin: host/reference/model_gltf.cpp.
// KHR_materials_transmission specification ("Implementation Notes"; glTF 2.0
// Appendix B for the rest): dielectric_brdf = fresnel_mix(ior,
// base = mix(diffuse_brdf, baseColor · specular_btdf(α), transmission),
// layer = specular_brdf(α)); the thin-walled specular_btdf is the specular
// lobe with the light direction mirrored through the surface (L' = L − 2 (n·L) n),
// weighted, as the base of fresnel_mix, by 1 − F(V·H'), H' the half vector of V
// and L'. One colour channel; V = l (the catalog's first direction), L = the
// second, anywhere on the sphere. Parameters p[0..4]: alpha (roughness²),
// metallic, base, f0 (((ior − 1)/(ior + 1))², specularFactor 1), transmission.
//
// The catalog's model folds the sphere onto the hemisphere of the second
// direction: f(l, v) + f(l, v mirrored below), so that its albedo (an
// integral over v above) is R + T, the power reflected and transmitted. With
// a white base, full transmission and no metal, R + T is the F = 1 albedo of
// the same D and Vis at every ior (the F and 1 − F of one H' add to 1): the
// derived expectation mfv run --scene tests (closed_form).
// Both halves in one evaluation: with v above (where the model is not 0),
// v mirrored below mirrors back to v itself, so the transmitted half's H',
// D, Vis and F are the reflected half's, to the bit. The reference twin evaluates the two halves apart
// (thin_walled twice) and the sum is the same: R + T, or 0 + 0 where there
// is no half vector. One evaluation, not two isomorphic calls: LLVM's SLP
// pass paired the two calls' selects and their sum into 2-lane vectors,
// which kept the whole-model reciprocity kernel scalar on AVX2 (issue 31,
// docs/performance.md); selects, not early returns, as model_gltf.
static inline MFV_ALWAYS_INLINE real model_gltf_transmission(real3 l, real3 v, const real* p) {
  real alpha = p[0], metallic = p[1], base = p[2], f0 = p[3], transmission = p[4];
  real NoL = l.z, NoV = v.z;
  real s2, VoH;
  real3 h = half_vector(l, v, &s2, &VoH);
  real x = R(1.0) - VoH;
  real fw = x * x * x * x * x;
  real fr = f0 + (R(1.0) - f0) * fw;
  real spec = over_4_cosines(D_ggx(h.z, s2, alpha) * G_smith_ggx_correlated(NoL, NoV, h.z, VoH, alpha), NoL, NoV);
  real through = (R(1.0) - metallic) * (R(1.0) - fr) * transmission * base * spec;  // a metal transmits nothing
  real dielectric = (R(1.0) - fr) * (R(1.0) - transmission) * base * MFV_INV_PI + fr * spec;
  real metal = (base + (R(1.0) - base) * fw) * spec;
  real reflected = (R(1.0) - metallic) * dielectric + metallic * metal;
  // either direction below the horizon, or no half vector (G's χ⁺(v·h) = 0):
  // 0, as model_gltf (above_horizons' tests are no_half_vector's first two)
  return no_half_vector(NoL, NoV, VoH) ? R(0.0) : reflected + through;
}
