// mfv check example: a correct GGX microfacet BRDF, written the way a
// renderer would ship it (float32, local shading frame n = +z).
//
//   mfv check --brdf examples/brdf/ggx.cl --as ggx/smith_ggx_correlated/schlick
//
// The contract (README "mfv check"): directions point away from the surface,
// wi = light, wo = view; params[k] is the k-th `// mfv: param` line below.
//   float3 brdf(float3 wi, float3 wo, const float* params)   required, RGB
//   float  D(float3 m, const float* params)                   optional: d_norm
//   float  G1(float3 v, float3 m, const float* params)        optional: masking (with D)
//
// mfv: param alpha 0.001 1 default 0.3 roughness
// mfv: param f0 0 1 default 0.04
//
// Terms: GGX D (Walter et al. 2007 eq. 33), height-correlated Smith G2
// (Heitz 2014 eq. 99) with GGX's Lambda (Heitz 2014 eq. 72), Schlick's F at
// the microfacet (v.h). Verdicts it gets: see README "mfv check".

// GGX D from cos² and sin² of m given apart: 1 / (pi a² (c² + s²/a²)²), equal
// to a² / (pi ((n.m)²(a²-1)+1)²) for unit m, without the cancellation of
// 1 - (n.m)² near the normal.
float D(float3 m, const float* params) {
  float alpha = params[0];
  if (m.z <= 0.0f) return 0.0f;
  float a2 = alpha * alpha;
  float k = m.z * m.z + (m.x * m.x + m.y * m.y) / a2;
  return 1.0f / (M_PI_F * a2 * k * k);
}

// Smith Lambda for GGX: (-1 + sqrt(1 + a² tan²)) / 2 = x / (2 (1 + sqrt(1 + x))),
// x = a² tan²: no cancellation for small x; a tan / 2 where x overflows.
float lambda_ggx(float c, float alpha) {
  if (c >= 1.0f) return 0.0f;       // a cosine that rounded above 1: tan = 0
  if (c <= 0.0f) return INFINITY;  // grazing: G1 -> 0
  float s2 = max((1.0f - c) * (1.0f + c), 0.0f);
  float x = alpha * alpha * s2 / (c * c);
  if (isinf(x)) return 0.5f * alpha * sqrt(s2) / c;
  return x / (2.0f * (1.0f + sqrt(1.0f + x)));
}

float G1(float3 v, float3 m, const float* params) {
  if (v.z <= 0.0f || dot(v, m) <= 0.0f) return 0.0f;  // back-facing microfacet
  return 1.0f / (1.0f + lambda_ggx(v.z, params[0]));
}

float3 brdf(float3 wi, float3 wo, const float* params) {
  float alpha = params[0], f0 = params[1];
  if (wi.z <= 0.0f || wo.z <= 0.0f) return (float3)(0.0f);
  float3 sum = wi + wo;
  float len = length(sum);
  float3 h = sum / len;
  float voh = min(0.5f * len, 1.0f);  // v.h = |l + v| / 2: symmetric in l and v
  float m5 = pow(1.0f - voh, 5.0f);
  float F = f0 + (1.0f - f0) * m5;
  float G2 = 1.0f / (1.0f + lambda_ggx(wi.z, alpha) + lambda_ggx(wo.z, alpha));
  // divided one cosine at a time: (n.l)(n.v) underflows near the horizon
  return (float3)(D(h, params) * G2 * F / (4.0f * wi.z) / wo.z);
}
