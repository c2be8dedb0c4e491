// mfv check example: a Lambertian BRDF (Lambert 1760), kd / pi, whose
// directional albedo is kd at every view: the smallest BRDF a furnace test
// must pass at kd = 1 and must fail with any gain above it.
//
//   mfv check --brdf examples/brdf/lambert.cl
//
// No roughness is declared, so the estimators use their mixture of widths
// (README "mfv check"); the contract is that of examples/brdf/ggx.cl.
//
// mfv: param kd 0 1 default 1

float3 brdf(float3 wi, float3 wo, const float* params) {
  if (wi.z <= 0.0f || wo.z <= 0.0f) return (float3)(0.0f);  // below the horizon: no reflection
  return (float3)(params[0] * M_1_PI_F);  // Lambert: kd / pi
}
