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
static inline real model_gltf(real3 l, real3 v, const real* p) {
  real alpha = p[0], metallic = p[1], base = p[2], f0 = p[3], f0_max = p[4], weight = p[5], alpha_b = p[6];
  real NoL = l.z, NoV = v.z;
  if (NoL <= R(0.0) || NoV <= R(0.0)) return R(0.0);  // below the horizon: no reflection
  real s2, VoH;
  real3 h = half_vector(l, v, &s2, &VoH);  // v·h = |l + v|/2: symmetric, no cancellation
  // l = -v (both at the horizon; in float32 also where l + v underflows):
  // no half vector, h = 0/0. The Smith G's χ⁺(v·h) is 0 there (Heitz 2014
  // eq. 99, G_smith_ggx_correlated), so f is 0, not NaN.
  if (!(VoH > R(0.0))) return R(0.0);
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
  return (R(1.0) - metallic) * dielectric + metallic * metal;
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
static inline real clearcoat_over(real material, real3 l, real3 v, real ca, real clearcoat) {
  real NoL = l.z, NoV = v.z;
  real s2, VoH;
  real3 h = half_vector(l, v, &s2, &VoH);
  if (!(VoH > R(0.0))) return R(0.0);  // l = -v: no half vector, G's χ⁺(v·h) = 0 (as model_gltf)
  real layer = over_4_cosines(D_ggx(h.z, s2, ca) * G_smith_ggx_correlated(NoL, NoV, h.z, VoH, ca), NoL, NoV);
  real x = R(1.0) - NoL;  // the spec's V·Nc (V = the catalog's first direction, see above)
  real weight = clearcoat * (R(0.04) + R(0.96) * x * x * x * x * x);
  return (R(1.0) - weight) * material + weight * layer;
}

static inline real model_gltf_clearcoat(real3 l, real3 v, const real* p) {
  if (l.z <= R(0.0) || v.z <= R(0.0)) return R(0.0);  // below the horizon: no reflection
  real q[7] = {p[0], p[1], p[2], p[3], p[4], R(1.0), R(0.0)};
  return clearcoat_over(model_gltf(l, v, q), l, v, p[5], p[6]);
}

// KHR_materials_clearcoat over a KHR_materials_anisotropy base (issue 21;
// catalog "gltf_clearcoat_aniso"): the same layering over the anisotropic
// glTF model. Parameters p[0..6]: alpha (alpha_t along t = +x), metallic,
// base, f0 (also fresnel_mix's max: an upper bound on the base's energy, as
// gltf_sheen), clearcoat_alpha, clearcoat, alpha_b (last: the second width,
// which stretches the estimators' proposal to (alpha_t, alpha_b) as for gltf).
static inline real model_gltf_clearcoat_aniso(real3 l, real3 v, const real* p) {
  if (l.z <= R(0.0) || v.z <= R(0.0)) return R(0.0);  // below the horizon: no reflection
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
// E_sheen(mu, alpha) = ∫ D_charlie V_charlie (n·l) dl (white sheen), rows
// alpha = 10^(-3 + 3 j/15), columns mu = (m + 0.5)/16: the E table of
// `mfv energy --models charlie/charlie_sheen --grid 16x16` (its sheen_e.cl; seed 1, max standard error 5.0e-04).
#define SHEEN_E_N 16
__constant float SHEEN_E[SHEEN_E_N * SHEEN_E_N] = {
    1.639740f, 0.106591f, 0.004073f, 0.000067f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f,
    1.713197f, 0.204673f, 0.018534f, 0.001118f, 0.000042f, 0.000001f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f,
    1.700698f, 0.318744f, 0.052859f, 0.006859f, 0.000636f, 0.000046f, 0.000002f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f,
    1.623187f, 0.426502f, 0.108616f, 0.024361f, 0.004341f, 0.000693f, 0.000075f, 0.000006f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f,
    1.503021f, 0.511732f, 0.177530f, 0.057636f, 0.017039f, 0.004123f, 0.000945f, 0.000167f, 0.000023f, 0.000002f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f, 0.000000f,
    1.361599f, 0.567083f, 0.246767f, 0.104384f, 0.041867f, 0.015417f, 0.005142f, 0.001560f, 0.000392f, 0.000082f, 0.000014f, 0.000002f, 0.000000f, 0.000000f, 0.000000f, 0.000000f,
    1.214889f, 0.593561f, 0.306581f, 0.157151f, 0.078633f, 0.037507f, 0.016912f, 0.007123f, 0.002749f, 0.000898f, 0.000260f, 0.000062f, 0.000013f, 0.000002f, 0.000000f, 0.000000f,
    1.075651f, 0.596454f, 0.350793f, 0.208009f, 0.121800f, 0.069971f, 0.038284f, 0.020183f, 0.010098f, 0.004635f, 0.001985f, 0.000736f, 0.000243f, 0.000055f, 0.000009f, 0.000000f,
    0.951756f, 0.585712f, 0.381249f, 0.251808f, 0.166362f, 0.108124f, 0.068404f, 0.042642f, 0.025486f, 0.014590f, 0.007831f, 0.003966f, 0.001746f, 0.000690f, 0.000187f, 0.000027f,
    0.850688f, 0.568344f, 0.401373f, 0.288438f, 0.208236f, 0.149033f, 0.105529f, 0.073146f, 0.050049f, 0.033187f, 0.021083f, 0.012718f, 0.007279f, 0.003695f, 0.001565f, 0.000429f,
    0.778007f, 0.556001f, 0.418453f, 0.321003f, 0.247684f, 0.191130f, 0.145865f, 0.110870f, 0.082684f, 0.060812f, 0.043803f, 0.030232f, 0.020316f, 0.012536f, 0.006811f, 0.002950f,
    0.737381f, 0.556609f, 0.440618f, 0.355533f, 0.289626f, 0.235189f, 0.191227f, 0.154212f, 0.123463f, 0.097529f, 0.076791f, 0.058860f, 0.043671f, 0.031281f, 0.020619f, 0.012000f,
    0.735524f, 0.579010f, 0.476233f, 0.399787f, 0.337833f, 0.287031f, 0.242740f, 0.205261f, 0.172528f, 0.144730f, 0.120527f, 0.099309f, 0.080061f, 0.062931f, 0.047667f, 0.033651f,
    0.778896f, 0.630530f, 0.533127f, 0.459547f, 0.399890f, 0.349315f, 0.305821f, 0.266590f, 0.232133f, 0.202036f, 0.175636f, 0.151856f, 0.129719f, 0.109241f, 0.089959f, 0.072090f,
    0.854761f, 0.703559f, 0.604477f, 0.530350f, 0.469984f, 0.418229f, 0.373085f, 0.332464f, 0.296178f, 0.264461f, 0.236705f, 0.210966f, 0.187375f, 0.165069f, 0.144036f, 0.123904f,
    0.880505f, 0.731716f, 0.635902f, 0.564139f, 0.506194f, 0.457092f, 0.413381f, 0.374476f, 0.339278f, 0.308752f, 0.281689f, 0.257145f, 0.234231f, 0.212718f, 0.192250f, 0.172996f,
};

static inline real sheen_E(real mu, real alpha) {
  // bilinear in (mu, log10 alpha) on the table's grid: mu at cell midpoints
  // (m + 0.5)/N, alpha = 10^(-3 + 3 j/(N - 1)) (checks/energy.cpp's grids)
  real x = clamp(mu * (real)SHEEN_E_N - R(0.5), R(0.0), (real)(SHEEN_E_N - 1));
  real y = clamp((log10(alpha) + R(3.0)) / R(3.0) * (real)(SHEEN_E_N - 1), R(0.0), (real)(SHEEN_E_N - 1));
  int i = min((int)x, SHEEN_E_N - 2), j = min((int)y, SHEEN_E_N - 2);
  real fx = x - (real)i, fy = y - (real)j;
  real e0 = mix((real)SHEEN_E[j * SHEEN_E_N + i], (real)SHEEN_E[j * SHEEN_E_N + i + 1], fx);
  real e1 = mix((real)SHEEN_E[(j + 1) * SHEEN_E_N + i], (real)SHEEN_E[(j + 1) * SHEEN_E_N + i + 1], fx);
  return mix(e0, e1, fy);
}

static inline real model_gltf_sheen(real3 l, real3 v, const real* p) {
  real NoL = l.z, NoV = v.z;
  if (NoL <= R(0.0) || NoV <= R(0.0)) return R(0.0);  // below the horizon: no reflection
  real q[7] = {p[0], p[1], p[2], p[3], p[3], R(1.0), R(0.0)};
  real material = model_gltf(l, v, q);
  real s2, VoH;
  real3 h = half_vector(l, v, &s2, &VoH);
  if (!(VoH > R(0.0))) return R(0.0);  // l = -v: no half vector, G's χ⁺(v·h) = 0 (as model_gltf)
  real sa = p[4], sheen = p[5];
  // no sheen in this channel: no lobe (and no 0 · Inf where the cosines underflow)
  real f_sheen = sheen > R(0.0)
                     ? sheen * over_4_cosines(D_charlie(h.z, s2, sa) * G_charlie_sheen(NoL, NoV, h.z, VoH, sa), NoL, NoV)
                     : R(0.0);
  real max3 = max(sheen, p[6]);
  real scaling = min(R(1.0) - max3 * sheen_E(NoV, sa), R(1.0) - max3 * sheen_E(NoL, sa));
  return f_sheen + material * scaling;
}
