// The pointwise evaluation shared by mfv agree, mfv eval and mfv stability:
// one record (kernels/abi/pointwise.h), copied into the working precision,
// evaluated by mode. The value depends only on what the record holds, so the
// host reference evaluates the identical inputs.
#include "abi/pointwise.h"

// A record held in global memory, in float (agree, eval) or in the working
// precision (stability), copied into a private one in `real`.
static inline void pw_load_float(__global const float* g, real* r) {
  for (int k = 0; k < PW_RECORD; ++k) r[k] = g[k];
}
static inline void pw_load_real(__global const real* g, real* r) {
  for (int k = 0; k < PW_RECORD; ++k) r[k] = g[k];
}

// Evaluates one record. `d` carries a whole model's number in mode PW_MODEL,
// `f` a BTDF's code in mode PW_BTDF;
// `variant` names the formulation in mode PW_VARIANT (stability_variants.cl,
// compiled into mfv stability's program only).
static inline real pw_eval(int mode, int d, int g, int f, int variant, const real* r) {
  real3 wi = (real3)(r[PW_WI_X], r[PW_WI_Y], r[PW_WI_Z]), wo = (real3)(r[PW_WO_X], r[PW_WO_Y], r[PW_WO_Z]);
  switch (mode) {
    case PW_D: return eval_D(d, r[PW_NOH], r[PW_SIN2H], r[PW_PD]);
    case PW_G: return eval_G(g, r[PW_NOL], r[PW_NOV], r[PW_NOH], r[PW_VOH], r[PW_PG]);
    case PW_G1: return eval_G1(g, r[PW_NOV], r[PW_PG]);
    case PW_F: return eval_F(f, r[PW_VOH], r[PW_F0], r[PW_F1]);
    case PW_BRDF: return brdf_eval(d, g, f, wi, wo, r[PW_PD], r[PW_PG], r[PW_F0], r[PW_F1], r[PW_KD]);
    case PW_MODEL: {
      real p[PW_PARAMS];
      for (int k = 0; k < PW_PARAMS; ++k) p[k] = r[PW_P0 + k];
      return eval_model(d, wi, wo, p);
    }
    // the half vector or view (x, y, z = NoH or NoV) as recorded, not made
    // unit: the reference evaluates the kernels' forms at exactly these
    // numbers (agree.cpp: G1 is homogeneous of degree 0 in w, D of degree -4)
    case PW_D_ANISO:
      return eval_D_aniso(d, r[PW_NOH], sin2_from_cos(r[PW_NOH]), r[PW_AUX_X], r[PW_AUX_Y], r[PW_PD], r[PW_ALPHA_Y]);
    case PW_G1_ANISO: return eval_G1_aniso(g, r[PW_NOV], r[PW_AUX_X], r[PW_AUX_Y], r[PW_PG], r[PW_ALPHA_Y]);
    case PW_BRDF_ANISO:
      return brdf_eval_aniso(d, g, f, wi, wo, r[PW_PD], r[PW_ALPHA_Y], r[PW_PG], r[PW_ALPHA_Y], r[PW_F0], r[PW_F1],
                             r[PW_KD]);
    case PW_BTDF: return btdf_eval(d, g, f, wi, wo, r[PW_PD], r[PW_PG], r[PW_F0]);
#ifdef MFV_STABILITY_VARIANTS
    case PW_VARIANT: return stability_variant(variant, r);
#endif
  }
  return NAN;
}
