// mfv check example, BUGGY: Schlick's Fresnel evaluated with n.v (the
// macro-surface cosine) instead of v.h (the microfacet's), so f(wi, wo)
// depends on the view alone through F: not reciprocal, and not the model.
//
//   mfv check --brdf examples/brdf/ggx_fresnel_nov.cl --as ggx/smith_ggx/schlick
//
// mfv: param alpha 0.001 1 default 0.3 roughness
// mfv: param f0 0 1 default 0.04

float3 brdf(float3 wi, float3 wo, const float* params) {
  float alpha = params[0], f0 = params[1];
  float NoL = wi.z, NoV = wo.z;
  if (NoL <= 0.0f || NoV <= 0.0f) return (float3)(0.0f);
  float3 h = normalize(wi + wo);
  float a2 = alpha * alpha;
  float s2 = h.x * h.x + h.y * h.y;            // |n x h|^2
  float k = h.z * h.z + s2 / a2;
  float d = 1.0f / (M_PI_F * a2 * k * k);      // GGX D
  // separable Smith GGX: G1 = 2 / (1 + sqrt(1 + a^2 tan^2))
  float tl = max(1.0f - NoL * NoL, 0.0f) / (NoL * NoL), tv = max(1.0f - NoV * NoV, 0.0f) / (NoV * NoV);
  float g = 4.0f / ((1.0f + sqrt(1.0f + a2 * tl)) * (1.0f + sqrt(1.0f + a2 * tv)));
  float F = f0 + (1.0f - f0) * pow(1.0f - NoV, 5.0f);  // BUG: 1 - dot(wo, h)
  return (float3)(d * g * F / (4.0f * NoL) / NoV);
}
