// mfv stability: evaluates one term, one assembled BRDF, one whole model or
// one alternative formulation (stability_variants.cl) on records the host
// lays out as a deterministic sweep, in the working precision (real). The
// host rounds its grid to that precision first, so the reference sees the
// identical numbers.
//
// Records (`real`, kernels/abi/pointwise.h): mode D takes NoH and
// sin2H = |n×h|² (formed by the host beside NoH); G the four cosines; G1 NoV;
// F VoH; BRDF and MODEL the directions wi, wo as they are (not
// renormalised) and the parameters p[0..6]. The value goes to PW_VALUE.
#include "abi/pointwise.h"

__kernel void stability_eval(int mode, int d, int g, int f, int variant, __global real* rec) {
  __global real* g_rec = rec + get_global_id(0) * PW_RECORD;
  real r[PW_RECORD];
  pw_load_real(g_rec, r);
  g_rec[PW_VALUE] = pw_eval(mode, d, g, f, variant, r);
}
