// mfv check example, BUGGY: GGX D without its 1/pi (a common slip when the
// renderer's light units already absorb a pi), in Filament's style with
// perceptual roughness r (alpha = r^2). D integrates to pi, not 1.
//
//   mfv check --brdf examples/brdf/ggx_missing_pi.cl --as ggx/smith_ggx_correlated/schlick --map alpha=roughness^2
//
// mfv: param roughness 0.045 1 default 0.5 perceptual
// mfv: param f0 0 1 default 0.04

float D_GGX(float NoH, float a) {
  float a2 = a * a;
  float f = (NoH * a2 - NoH) * NoH + 1.0f;
  return a2 / (f * f);  // BUG: a2 / (pi f^2)
}

// Filament's height-correlated Smith visibility V = G2 / (4 (n.l)(n.v))
float V_SmithGGXCorrelated(float NoV, float NoL, float a) {
  float a2 = a * a;
  float GGXL = NoV * sqrt((-NoL * a2 + NoL) * NoL + a2);
  float GGXV = NoL * sqrt((-NoV * a2 + NoV) * NoV + a2);
  return 0.5f / (GGXV + GGXL);
}

float D(float3 m, const float* params) {
  return m.z > 0.0f ? D_GGX(m.z, params[0] * params[0]) : 0.0f;
}

float3 brdf(float3 wi, float3 wo, const float* params) {
  float a = params[0] * params[0], f0 = params[1];
  if (wi.z <= 0.0f || wo.z <= 0.0f) return (float3)(0.0f);
  float3 h = normalize(wi + wo);
  float LoH = clamp(dot(wi, h), 0.0f, 1.0f);
  float F = f0 + (1.0f - f0) * pow(1.0f - LoH, 5.0f);
  return (float3)(D_GGX(h.z, a) * V_SmithGGXCorrelated(wo.z, wi.z, a) * F);
}
