// mfv stability: evaluates one term, one assembled BRDF or one alternative
// formulation (stability_variants.cl) on inputs the host lays out as a
// deterministic sweep, in the working precision (real). The host rounds its
// grid to that precision first, so the reference sees the identical numbers.
//
// Record layout (STAB_IN reals): [0..5] geometry, [6..10] parameters
// (D param, G param, F p0, F p1, kd), [11..12] unused (MODEL: [6..12] = p[0..6]). Geometry by mode:
//   D:  [2] NoH, [4] sin2H = |n×h|² (formed by the host beside NoH)
//   G:  [0..3] NoL, NoV, NoH, VoH      G1: [1] NoV      F: [3] VoH
//   BRDF, MODEL: [0..2] wi (light), [3..5] wo (view), taken as they are (not renormalised)
//   VARIANT: see stability_variants.cl

#define STAB_D 0
#define STAB_G 1
#define STAB_F 2
#define STAB_G1 3
#define STAB_BRDF 4
#define STAB_VARIANT 5
#define STAB_MODEL 6  // a whole model: `d` carries its number, [6..12] its p[0..6]
#define STAB_IN 13

__kernel void stability_eval(int mode, int d, int g, int f, int variant, __global const real* in,
                             __global real* out) {
  size_t i = get_global_id(0);
  __global const real* r = in + i * STAB_IN;
  real v = NAN;
  switch (mode) {
    case STAB_D: v = eval_D(d, r[2], r[4], r[6]); break;
    case STAB_G: v = eval_G(g, r[0], r[1], r[2], r[3], r[7]); break;
    case STAB_G1: v = eval_G1(g, r[1], r[7]); break;
    case STAB_F: v = eval_F(f, r[3], r[8], r[9]); break;
    case STAB_BRDF:
      v = brdf_eval(d, g, f, (real3)(r[0], r[1], r[2]), (real3)(r[3], r[4], r[5]), r[6], r[7], r[8], r[9], r[10]);
      break;
    case STAB_VARIANT: v = stability_variant(variant, r); break;
    case STAB_MODEL: {
      real p[7] = {r[6], r[7], r[8], r[9], r[10], r[11], r[12]};
      v = eval_model(d, (real3)(r[0], r[1], r[2]), (real3)(r[3], r[4], r[5]), p);
      break;
    }
  }
  out[i] = v;
}
