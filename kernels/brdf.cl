// The assembled microfacet BRDF (needs the generated eval_D/eval_G/eval_F).
// Reference twin: host/reference/brdf.cpp.

// seed 000: f = kd/π + D(h) F(l,h) G(l,v,h) / (4 (n·l)(n·v)), local frame n = +z,
// wi = light, wo = view, both pointing away from the surface.
// By components (l = (lx, ly, lz), v = (vx, vy, vz)): no float3 value, so
// PoCL can run work-items in SIMD lanes (albedo.cl albedo_values).
// brdf_above_c is the value where both directions are above the horizon
// (lz > 0, vz > 0; elsewhere its result is meaningless and must be selected
// away): kernels that select 0 below the horizon themselves
// (`fmin(lz, vz) <= 0 ? 0 : brdf_above_c(...)`, the same floats as
// brdf_eval_c) keep every load of the BRDF's parameters unconditional, which
// PoCL's haswell (AVX2) target needs to vectorize them (docs/performance.md).

// The BRDF from its microfacet numerator spec = D F G.
static inline MFV_ALWAYS_INLINE real brdf_of_spec(real spec, real NoL, real NoV, real kd) {
  // Divided one cosine at a time: (n·l)(n·v) underflows to 0 for directions
  // within ~1e-19 of the horizon (float), where spec / 0 would give 0/0 = NaN.
  return kd * MFV_INV_PI + spec / (R(4.0) * NoL) / NoV;
}

// brdf_above_c from the half vector h: NoH, sin2H = |n×h|² and half_len =
// |l + v| / 2 (v·h before its clamp), as brdf_above_c forms them
// (albedo_mis_microfacet, kernels/albedo.cl, takes them from its geometry).
static inline MFV_ALWAYS_INLINE real brdf_above_h(int d, int g, int f, real NoL, real NoV, real NoH, real sin2H,
                                                  real half_len, real pd, real pg, real f0, real f1, real kd) {
  real VoH = min(half_len, R(1.0));
  real spec = eval_D(d, NoH, sin2H, pd) * eval_F(f, VoH, f0, f1) * eval_G(g, NoL, NoV, NoH, VoH, pg);
  return brdf_of_spec(spec, NoL, NoV, kd);
}

static inline MFV_ALWAYS_INLINE real brdf_above_c(int d, int g, int f, real lx, real ly, real lz, real vx, real vy,
                                                  real vz, real pd, real pg, real f0, real f1, real kd) {
  real NoL = lz;
  real NoV = vz;
  // Both above the horizon, so wi + wo != 0 and the half vector is defined.
  // v·h = l·h = |l + v| / 2 for unit l, v: symmetric in l and v (so f is
  // reciprocal to the last bit) and free of the cancellation dot(v, h) has
  // when l and v are nearly opposite and v·h -> 0.
  real hx, hy, NoH;
  real len = normalize_sum(lx + vx, ly + vy, lz + vz, &hx, &hy, &NoH);
  real sin2H = hx * hx + hy * hy;  // |n×h|², exact where 1 - NoH is not
  return brdf_above_h(d, g, f, NoL, NoV, NoH, sin2H, R(0.5) * len, pd, pg, f0, f1, kd);
}

static inline MFV_ALWAYS_INLINE real brdf_eval_c(int d, int g, int f, real lx, real ly, real lz, real vx, real vy,
                                                 real vz, real pd, real pg, real f0, real f1, real kd) {
  if (lz <= R(0.0) || vz <= R(0.0)) return R(0.0);  // below the horizon: no reflection
  return brdf_above_c(d, g, f, lx, ly, lz, vx, vy, vz, pd, pg, f0, f1, kd);
}

static inline real brdf_eval(int d, int g, int f, real3 wi, real3 wo, real pd, real pg, real f0, real f1,
                             real kd) {
  return brdf_eval_c(d, g, f, wi.x, wi.y, wi.z, wo.x, wo.y, wo.z, pd, pg, f0, f1, kd);
}

// The same BRDF with anisotropic terms (Term::aniso): D of widths (pd, pd2)
// and G of widths (pg, pg2) in the tangent frame t = +x, b = +y; isotropic
// terms in the mix see exactly what brdf_eval gives them. By components and
// with the half vector formed as brdf_eval_c forms it (normalize_sum), so
// that kernels/aniso_values.cl vectorizes.
// Reference twin: brdf_aniso in host/reference/brdf.cpp.
static inline real brdf_eval_aniso_c(int d, int g, int f, real lx, real ly, real lz, real vx, real vy, real vz,
                                     real pd, real pd2, real pg, real pg2, real f0, real f1, real kd) {
  real NoL = lz;
  real NoV = vz;
  if (NoL <= R(0.0) || NoV <= R(0.0)) return R(0.0);  // below the horizon: no reflection
  real hx, hy, NoH;
  real len = normalize_sum(lx + vx, ly + vy, lz + vz, &hx, &hy, &NoH);
  real VoH = min(R(0.5) * len, R(1.0));
  real sin2H = hx * hx + hy * hy;
  real spec = eval_D_aniso(d, NoH, sin2H, hx, hy, pd, pd2) * eval_F(f, VoH, f0, f1) *
              eval_G_aniso(g, lx, ly, lz, vx, vy, vz, NoH, VoH, pg, pg2);
  return kd * MFV_INV_PI + spec / (R(4.0) * NoL) / NoV;
}

static inline real brdf_eval_aniso(int d, int g, int f, real3 wi, real3 wo, real pd, real pd2, real pg, real pg2,
                                   real f0, real f1, real kd) {
  return brdf_eval_aniso_c(d, g, f, wi.x, wi.y, wi.z, wo.x, wo.y, wo.z, pd, pd2, pg, pg2, f0, f1, kd);
}
