// mfv check example, BUGGY: the Schlick-GGX G1 of Karis 2013 (UE4),
// G1 = (n.v) / ((n.v)(1 - k) + k) with k = alpha / 2, fed the perceptual
// roughness r instead of alpha = r^2: k = r / 2 masks far too much.
//
//   mfv check --brdf examples/brdf/ggx_schlick_k.cl --as ggx/smith_ggx/schlick --map alpha=roughness^2
//
// mfv: param roughness 0.05 1 default 0.5 perceptual
// mfv: param f0 0 1 default 0.04

float D(float3 m, const float* params) {
  float a = params[0] * params[0];
  if (m.z <= 0.0f) return 0.0f;
  float a2 = a * a;
  float t = m.z * m.z * (a2 - 1.0f) + 1.0f;
  return a2 / (M_PI_F * t * t);
}

float G1(float3 v, float3 m, const float* params) {
  float k = params[0] / 2.0f;  // BUG: k = alpha / 2 = roughness^2 / 2
  float NoV = v.z;
  if (NoV <= 0.0f || dot(v, m) <= 0.0f) return 0.0f;
  return NoV / (NoV * (1.0f - k) + k);
}

float3 brdf(float3 wi, float3 wo, const float* params) {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return (float3)(0.0f);
  float3 h = normalize(wi + wo);
  float VoH = clamp(dot(wo, h), 0.0f, 1.0f);
  float F = params[1] + (1.0f - params[1]) * pow(1.0f - VoH, 5.0f);
  float G = G1(wi, h, params) * G1(wo, h, params);
  return (float3)(D(h, params) * G * F / (4.0f * wi.z * wo.z));
}
