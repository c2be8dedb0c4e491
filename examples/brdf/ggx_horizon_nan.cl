// mfv check example, BUGGY: correct GGX terms in their textbook forms, but
// no test for directions at or below the horizon and tan^2 = (1 - c^2)/c^2
// formed directly: at n.v = 0 the Smith Lambda is inf - inf, and a light
// below the surface gives a negative BRDF. The integrals never look there;
// the census over the stability sweep's extreme directions does.
//
//   mfv check --brdf examples/brdf/ggx_horizon_nan.cl
//
// mfv: param alpha 0.001 1 default 0.3 roughness
// mfv: param f0 0 1 default 0.04

float lambda(float c, float a) {
  float tan2 = (1.0f - c * c) / (c * c);
  return (-1.0f + sqrt(1.0f + a * a * tan2)) / 2.0f;  // Heitz 2014 eq. 72
}

float3 brdf(float3 wi, float3 wo, const float* params) {
  float a = params[0], f0 = params[1];
  float3 h = normalize(wi + wo);
  float a2 = a * a, NoH = h.z;
  float t = NoH * NoH * (a2 - 1.0f) + 1.0f;
  float d = a2 / (M_PI_F * t * t);
  float g = 1.0f / (1.0f + lambda(wi.z, a) + lambda(wo.z, a));
  float F = f0 + (1.0f - f0) * pow(1.0f - dot(wo, h), 5.0f);
  return (float3)(d * g * F / (4.0f * wi.z * wo.z));  // BUG: no n.l > 0, n.v > 0 test
}
