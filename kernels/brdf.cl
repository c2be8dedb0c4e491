// The assembled microfacet BRDF (needs the generated eval_D/eval_G/eval_F).
// Reference twin: host/reference/brdf.cpp.

// seed 000: f = kd/π + D(h) F(l,h) G(l,v,h) / (4 (n·l)(n·v)), local frame n = +z,
// wi = light, wo = view, both pointing away from the surface.
static inline real brdf_eval(int d, int g, int f, real3 wi, real3 wo, real pd, real pg, real f0, real f1,
                             real kd) {
  real NoL = wi.z;
  real NoV = wo.z;
  if (NoL <= R(0.0) || NoV <= R(0.0)) return R(0.0);  // below the horizon: no reflection
  // Both above the horizon, so wi + wo != 0 and the half vector is defined.
  real3 h = normalize(wi + wo);
  real NoH = h.z;
  real VoH = saturate(dot(wo, h));
  real sin2H = h.x * h.x + h.y * h.y;  // |n×h|², exact where 1 - NoH is not
  real spec = eval_D(d, NoH, sin2H, pd) * eval_F(f, VoH, f0, f1) * eval_G(g, NoL, NoV, NoH, VoH, pg);
  return kd * MFV_INV_PI + spec / (R(4.0) * NoL * NoV);
}
