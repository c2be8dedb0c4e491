// The glTF 2.0 metallic-roughness BRDF as one whole model (issue 7), one
// colour channel at a time. Selected in spec_brdf (integrate.cl) by
// IntegralSpec::model == MFV_MODEL_GLTF; compiled only into programs whose
// generated dispatch defines MFV_WITH_GLTF (TermSelection::gltf).
// Reference twin: host/reference/model_gltf.cpp.
//
// Sources: glTF 2.0 specification, Appendix B (B.3.2 specular_brdf = D·Vis
// with the GGX D and the height-correlated Smith G; B.3.3 diffuse_brdf;
// B.3.4 conductor_fresnel and fresnel_mix; B.3.5 material = mix(dielectric,
// metal, metallic)), with KHR_materials_specular's fresnel_mix(f0_color, ior,
// weight, base, layer) = (1 - weight·max(fr)) base + weight·fr·layer and
// KHR_materials_ior's f0 = ((ior - 1)/(ior + 1))².
//
// Parameters (IntegralSpec p[0..5] = pd, pg, f0, f1, kd, p5):
//   alpha    = roughness²
//   metallic
//   base     = baseColor of this channel
//   f0       = min(f0_ior · specularColor, 1) of this channel (dielectric F0)
//   f0_max   = the largest f0 over the three channels: Schlick's fr grows with
//              f0, so max over channels of fr is fr at f0_max
//   weight   = specularFactor
#define MFV_MODEL_GLTF 1000u

#ifdef MFV_WITH_GLTF
static inline real model_gltf_pbr(real3 wi, real3 wo, real alpha, real metallic, real base, real f0, real f0_max,
                                  real weight) {
  real NoL = wi.z, NoV = wo.z;
  if (NoL <= R(0.0) || NoV <= R(0.0)) return R(0.0);  // below the horizon: no reflection
  // Half vector and v·h = |l + v|/2 as in brdf_eval (symmetric, no cancellation).
  real3 sum = wi + wo;
  real len = length(sum);
  real3 h = sum / len;
  real VoH = min(R(0.5) * len, R(1.0));
  real sin2H = h.x * h.x + h.y * h.y;
  real x = R(1.0) - VoH;
  real fw = x * x * x * x * x;  // (1 - |v·h|)^5
  // specular_brdf(alpha) = D G / (4 (n·l)(n·v)) with the catalog's stable GGX D
  // and height-correlated Smith G (Heitz 2014 eq. 99), divided one cosine at a time.
  real spec = D_ggx(h.z, sin2H, alpha) * G_smith_ggx_correlated(NoL, NoV, h.z, VoH, alpha) / (R(4.0) * NoL) / NoV;
  real fr = f0 + (R(1.0) - f0) * fw;
  real fr_max = f0_max + (R(1.0) - f0_max) * fw;
  real dielectric = (R(1.0) - weight * fr_max) * base * MFV_INV_PI + weight * fr * spec;
  real metal = (base + (R(1.0) - base) * fw) * spec;  // conductor_fresnel(f0 = baseColor)
  return (R(1.0) - metallic) * dielectric + metallic * metal;
}
#endif
