// mfv check --brdf FILE.cl: adapters between the user's functions and the
// estimators. Built only with -DMFV_USER_BRDF, right after the user's file
// (injected by host/user/ with `#line 1 "FILE.cl"`, so build logs point into
// it), after integrate.cl, whose seams spec_brdf, spec_D and spec_G1 call
// these. The contract (docs/cli/check.md), in the local frame n = +z:
//   float3 brdf(float3 wi, float3 wo, const float* params);   RGB, required
//   float D(float3 m, const float* params);                    optional
//   float G1(float3 v, float3 m, const float* params);          optional
//   float3 btdf(float3 wi, float3 wo, const float* params);   wi, wo on opposite sides
//   float3 bsdf(float3 wi, float3 wo, const float* params);   both hemispheres, in place of brdf and btdf
// params[k] is the k-th declared parameter; the host defines MFV_USER_HAS_BRDF,
// MFV_USER_HAS_BTDF, MFV_USER_HAS_BSDF, MFV_USER_HAS_D and MFV_USER_HAS_G1
// when the file has them (at least one of the first three).

// The user's files end here: what kernels/user_prelude.cl pushed is popped.
#pragma pop_macro("R")
#pragma pop_macro("float4")
#pragma pop_macro("float3")
#pragma pop_macro("float2")
#pragma pop_macro("float")
#pragma clang diagnostic pop
#if MFV_USER_DIALECT != 0
#pragma clang attribute pop
#endif

// MFV_USER_PARAMS (6) is defined in kernels/user_guard.cl. The arrays hold
// one more slot, the poison slot that out-of-range reads are sent to; slots
// past the declared MFV_USER_NPARAMS are NaN too, for reads through pointer
// arithmetic the rewrite does not see.
#define MFV_USER_SLOTS (MFV_USER_PARAMS + 1)

static inline void user_poison(mfv_ufloat* p) {
  for (int k = MFV_USER_NPARAMS; k < MFV_USER_SLOTS; ++k) p[k] = NAN;
}

// The parameters of integral `s`: p[0..5] from IntegralSpec::p.
static inline void user_params(__global const IntegralSpec* s, mfv_ufloat* p) {
  for (int k = 0; k < 6; ++k) p[k] = s->p[k];
  user_poison(p);
}

static inline real user_channel(mfv_ufloat3 v, uint channel) { return channel == 0u ? v.x : channel == 1u ? v.y : v.z; }

// The reflection the BRDF checks read: brdf, or a bsdf asked with both
// directions above; NaN where the file has neither (the host runs no BRDF
// check then).
static inline mfv_ufloat3 user_reflect(mfv_ufloat3 i, mfv_ufloat3 o, mfv_ufloat* p) {
#if defined(MFV_USER_HAS_BSDF)
  return bsdf(i, o, p);
#elif defined(MFV_USER_HAS_BRDF)
  return brdf(i, o, p);
#else
  return (mfv_ufloat3)(NAN);
#endif
}

// The whole BSDF over the sphere (the transmission checks: o on i's side is
// reflection, on the other side transmission; docs/cli/check.md): bsdf, or
// brdf (asked on either side) and btdf; NaN for a part the file lacks.
static inline mfv_ufloat3 user_bsdf(mfv_ufloat3 i, mfv_ufloat3 o, mfv_ufloat* p) {
#if defined(MFV_USER_HAS_BSDF)
  return bsdf(i, o, p);
#else
  if ((i.z > 0) == (o.z > 0)) {
#if defined(MFV_USER_HAS_BRDF)
    return brdf(i, o, p);
#else
    return (mfv_ufloat3)(NAN);
#endif
  }
#if defined(MFV_USER_HAS_BTDF)
  return btdf(i, o, p);
#else
  return (mfv_ufloat3)(NAN);
#endif
#endif
}

static inline real user_brdf_adapter(__global const IntegralSpec* s, real3 i, real3 o) {
  mfv_ufloat p[MFV_USER_SLOTS];
  user_params(s, p);
  return user_channel(user_reflect(convert_mfv_ufloat3(i), convert_mfv_ufloat3(o), p), s->channel);
}

// kernels/transmission.cl's seam (spec_bsdf_value): i is the fixed direction.
static inline real user_bsdf_adapter(__global const IntegralSpec* s, real3 i, real3 o) {
  mfv_ufloat p[MFV_USER_SLOTS];
  user_params(s, p);
  return user_channel(user_bsdf(convert_mfv_ufloat3(i), convert_mfv_ufloat3(o), p), s->channel);
}

static inline real user_D_adapter(__global const IntegralSpec* s, real3 m) {
#ifdef MFV_USER_HAS_D
  mfv_ufloat p[MFV_USER_SLOTS];
  user_params(s, p);
  return D(convert_mfv_ufloat3(m), p);
#else
  return NAN;  // the host runs no D check without D
#endif
}

static inline real user_G1_adapter(__global const IntegralSpec* s, real3 v, real3 m) {
#ifdef MFV_USER_HAS_G1
  mfv_ufloat p[MFV_USER_SLOTS];
  user_params(s, p);
  return G1(convert_mfv_ufloat3(v), convert_mfv_ufloat3(m), p);
#else
  return NAN;
#endif
}

// Pointwise evaluation for the finiteness census and the agreement with a
// claimed model, on the records of kernels/abi/pointwise.h (float): a record
// holds wi, wo, a microfacet normal m (PW_M_X..Z) and the parameters
// (PW_P0..); user_eval writes brdf(wi, wo) (RGB: PW_BRDF_R..B), D(m)
// (PW_USER_D), G1(wo, m) and G1(wi, m) (PW_USER_G1_WO, _WI; NaN where the
// file lacks one).
#include "abi/pointwise.h"
__kernel void user_eval(__global float* rec) {
  __global float* r = rec + get_global_id(0) * PW_RECORD;
  mfv_ufloat3 wi = (mfv_ufloat3)(r[PW_WI_X], r[PW_WI_Y], r[PW_WI_Z]);
  mfv_ufloat3 wo = (mfv_ufloat3)(r[PW_WO_X], r[PW_WO_Y], r[PW_WO_Z]);
  mfv_ufloat3 m = (mfv_ufloat3)(r[PW_M_X], r[PW_M_Y], r[PW_M_Z]);
  mfv_ufloat p[MFV_USER_SLOTS];
  for (int k = 0; k < MFV_USER_PARAMS; ++k) p[k] = r[PW_P0 + k];
  user_poison(p);
  mfv_ufloat3 f = user_reflect(wi, wo, p);  // the twin's values rounded to float: 6e-8 relative
  r[PW_BRDF_R] = (float)f.x;
  r[PW_BRDF_G] = (float)f.y;
  r[PW_BRDF_B] = (float)f.z;
#ifdef MFV_USER_HAS_D
  r[PW_USER_D] = (float)D(m, p);
#else
  r[PW_USER_D] = NAN;
#endif
#ifdef MFV_USER_HAS_G1
  r[PW_USER_G1_WO] = (float)G1(wo, m, p);
  r[PW_USER_G1_WI] = (float)G1(wi, m, p);
#else
  r[PW_USER_G1_WO] = r[PW_USER_G1_WI] = NAN;
#endif
}

// bsdf_reciprocity of mfv check (host/user/user_transmission.cpp): each record
// holds wi, wo and the parameters (MFV_PAIR_*); user_bsdf_pairs writes the
// BSDF both ways, f(wi, wo) and f(wo, wi), RGB (pre-filled with NaN).
#define MFV_PAIR_WI 0
#define MFV_PAIR_WO 3
#define MFV_PAIR_P0 6
#define MFV_PAIR_FWD 12
#define MFV_PAIR_REV 15
#define MFV_PAIR_RECORD 18
__kernel void user_bsdf_pairs(__global float* rec) {
  __global float* r = rec + get_global_id(0) * MFV_PAIR_RECORD;
  mfv_ufloat3 wi = (mfv_ufloat3)(r[MFV_PAIR_WI], r[MFV_PAIR_WI + 1], r[MFV_PAIR_WI + 2]);
  mfv_ufloat3 wo = (mfv_ufloat3)(r[MFV_PAIR_WO], r[MFV_PAIR_WO + 1], r[MFV_PAIR_WO + 2]);
  mfv_ufloat p[MFV_USER_SLOTS];
  for (int k = 0; k < MFV_USER_PARAMS; ++k) p[k] = r[MFV_PAIR_P0 + k];
  user_poison(p);
  mfv_ufloat3 a = user_bsdf(wi, wo, p), b = user_bsdf(wo, wi, p);
  r[MFV_PAIR_FWD] = (float)a.x, r[MFV_PAIR_FWD + 1] = (float)a.y, r[MFV_PAIR_FWD + 2] = (float)a.z;
  r[MFV_PAIR_REV] = (float)b.x, r[MFV_PAIR_REV + 1] = (float)b.y, r[MFV_PAIR_REV + 2] = (float)b.z;
}
