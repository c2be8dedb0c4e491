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
static inline real model_gltf_clearcoat(real3 l, real3 v, const real* p) {
  real NoL = l.z, NoV = v.z;
  if (NoL <= R(0.0) || NoV <= R(0.0)) return R(0.0);  // below the horizon: no reflection
  real q[7] = {p[0], p[1], p[2], p[3], p[4], R(1.0), R(0.0)};
  real material = model_gltf(l, v, q);
  real s2, VoH;
  real3 h = half_vector(l, v, &s2, &VoH);
  if (!(VoH > R(0.0))) return R(0.0);  // l = -v: no half vector, G's χ⁺(v·h) = 0 (as model_gltf)
  real ca = p[5];
  real layer = over_4_cosines(D_ggx(h.z, s2, ca) * G_smith_ggx_correlated(NoL, NoV, h.z, VoH, ca), NoL, NoV);
  real x = R(1.0) - NoL;  // the spec's V·Nc (V = the catalog's first direction, see above)
  real weight = p[6] * (R(0.04) + R(0.96) * x * x * x * x * x);
  return (R(1.0) - weight) * material + weight * layer;
}
