// mfv check --brdf FILE.cl: adapters between the user's functions and the
// estimators. Built only with -DMFV_USER_BRDF, right after the user's file
// (injected by host/user/ with `#line 1 "FILE.cl"`, so build logs point into
// it), after integrate.cl, whose seams spec_brdf, spec_D and spec_G1 call
// these. The contract (docs/cli/check.md), in the local frame n = +z:
//   float3 brdf(float3 wi, float3 wo, const float* params);   RGB, required
//   float D(float3 m, const float* params);                    optional
//   float G1(float3 v, float3 m, const float* params);          optional
// params[k] is the k-th declared parameter; the host defines MFV_USER_HAS_D
// and MFV_USER_HAS_G1 when the file has them.

// MFV_USER_PARAMS (6) is defined in kernels/user_guard.cl. The arrays hold
// one more slot, the poison slot that out-of-range reads are sent to; slots
// past the declared MFV_USER_NPARAMS are NaN too, for reads through pointer
// arithmetic the rewrite does not see.
#define MFV_USER_SLOTS (MFV_USER_PARAMS + 1)

static inline void user_poison(float* p) {
  for (int k = MFV_USER_NPARAMS; k < MFV_USER_SLOTS; ++k) p[k] = NAN;
}

// The parameters of integral `s`: p[0..5] from pd, pg, f0, f1, kd, p5.
static inline void user_params(__global const IntegralSpec* s, float* p) {
  p[0] = s->pd;
  p[1] = s->pg;
  p[2] = s->f0;
  p[3] = s->f1;
  p[4] = s->kd;
  p[5] = s->p5;
  user_poison(p);
}

static inline real user_channel(float3 v, uint channel) { return channel == 0u ? v.x : channel == 1u ? v.y : v.z; }

static inline real user_brdf_adapter(__global const IntegralSpec* s, real3 i, real3 o) {
  float p[MFV_USER_SLOTS];
  user_params(s, p);
  return user_channel(brdf(convert_float3(i), convert_float3(o), p), s->channel);
}

static inline real user_D_adapter(__global const IntegralSpec* s, real3 m) {
#ifdef MFV_USER_HAS_D
  float p[MFV_USER_SLOTS];
  user_params(s, p);
  return D(convert_float3(m), p);
#else
  return NAN;  // the host runs no D check without D
#endif
}

static inline real user_G1_adapter(__global const IntegralSpec* s, real3 v, real3 m) {
#ifdef MFV_USER_HAS_G1
  float p[MFV_USER_SLOTS];
  user_params(s, p);
  return G1(convert_float3(v), convert_float3(m), p);
#else
  return NAN;
#endif
}

// Pointwise evaluation for the finiteness census and the agreement with a
// claimed model: a record holds wi, wo, a microfacet normal m and the
// parameters (USER_IN floats); the result holds brdf(wi, wo) (RGB), D(m),
// G1(wo, m) and G1(wi, m) (USER_OUT floats; NaN where the file lacks one).
#define USER_IN 16
#define USER_OUT 6
__kernel void user_eval(__global const float* in, __global float* out) {
  size_t i = get_global_id(0);
  __global const float* r = in + i * USER_IN;
  float3 wi = (float3)(r[0], r[1], r[2]), wo = (float3)(r[3], r[4], r[5]), m = (float3)(r[6], r[7], r[8]);
  float p[MFV_USER_SLOTS];
  for (int k = 0; k < MFV_USER_PARAMS; ++k) p[k] = r[9 + k];
  user_poison(p);
  __global float* o = out + i * USER_OUT;
  float3 f = brdf(wi, wo, p);
  o[0] = f.x;
  o[1] = f.y;
  o[2] = f.z;
#ifdef MFV_USER_HAS_D
  o[3] = D(m, p);
#else
  o[3] = NAN;
#endif
#ifdef MFV_USER_HAS_G1
  o[4] = G1(wo, m, p);
  o[5] = G1(wi, m, p);
#else
  o[4] = o[5] = NAN;
#endif
}
