// Pointwise agreement: evaluates one term or one assembled BRDF on
// Philox-generated inputs and writes the inputs it used beside the value, so
// the reference evaluates the identical (float-rounded) inputs.
//
// Records (float, kernels/abi/pointwise.h): the geometry in PW_WI_X..PW_WO_Z
// (modes D, G, F, G1: the cosines PW_NOL, PW_NOV, PW_NOH, PW_VOH; D_ANISO adds
// h.x, h.y and G1_ANISO wo.x, wo.y in PW_AUX_X, PW_AUX_Y), the parameters in
// PW_P0..PW_P6 (PW_ALPHA_Y: the anisotropic modes' second width), the value
// in PW_VALUE (float part) and PW_VALUE_LO (the remainder, double builds).
#include "abi/pointwise.h"

// ranges: PW_PARAMS slots (D param, G param, F p0, F p1, kd, p5, a whole model's p[6]) x (lo, hi, log flag)
static inline real draw_param(__global const float* ranges, int slot, real u) {
  real lo = ranges[3 * slot], hi = ranges[3 * slot + 1];
  if (ranges[3 * slot + 2] != 0.0f) return exp(log(lo) + u * (log(hi) - log(lo)));
  return lo + u * (hi - lo);
}

// w / |w| with the double sqrt and division, which OpenCL C requires
// correctly rounded (0 ulp, unlike normalize(), whose accuracy is
// implementation-defined), in a fixed order without contraction: the host
// reference forms the bit-identical unit vector (agree.cpp unit_exact).
static inline real3 unit_exact(real3 w) {
#pragma OPENCL FP_CONTRACT OFF
  real n2 = w.x * w.x + w.y * w.y + w.z * w.z;
  return w / sqrt(n2);
}

// Evaluates one float record: the value depends only on what the record holds.
static inline real eval_record(int mode, int d, int g, int f, __global const float* rec) {
  real r[PW_RECORD];
  pw_load_float(rec, r);
  // A record names directions. In double builds the float-rounded record is
  // unit only to ~1e-8, far above double rounding, so it is made unit first
  // (the reference does the same in double); float builds take it as it is.
#ifdef MFV_DOUBLE
  if (mode == PW_MODEL || mode == PW_BRDF_ANISO || mode == PW_BRDF || mode == PW_BTDF) {
    real3 wi = unit_exact((real3)(r[PW_WI_X], r[PW_WI_Y], r[PW_WI_Z]));
    real3 wo = unit_exact((real3)(r[PW_WO_X], r[PW_WO_Y], r[PW_WO_Z]));
    r[PW_WI_X] = wi.x, r[PW_WI_Y] = wi.y, r[PW_WI_Z] = wi.z;
    r[PW_WO_X] = wo.x, r[PW_WO_Y] = wo.y, r[PW_WO_Z] = wo.z;
  }
#endif
  // D from the cosine alone: sin² formed in the working precision
  if (mode == PW_D) r[PW_SIN2H] = sin2_from_cos(r[PW_NOH]);
  return pw_eval(mode, d, g, f, -1, r);
}

// The value as float plus the float remainder (a double survives to ~48 bits).
static inline void store_value(__global float* r, real value) {
  float hi = (float)value;
  r[PW_VALUE] = hi;
  r[PW_VALUE_LO] = isfinite(value) ? (float)(value - (real)hi) : 0.0f;
}

// A direction with cosθ = u² (dense at grazing) and a facet with θ = (π/2) u³
// (dense at the normal, where D peaks), turned by π about the normal onto the
// direction's side if it faced away (then w·m >= 2 (n·w)(n·m)).
static inline void draw_dir_facet(uint4 rg, real3* w, real3* m) {
  real co = sqr(u01_open(rg.x));
  real so = safe_sqrt(R(1.0) - co * co);
  real po = R(2.0) * MFV_PI * u01_open(rg.y);
  real th = R(0.5) * MFV_PI * pow(u01_open(rg.z), R(3.0));
  real ph = R(2.0) * MFV_PI * u01_open(rg.w);
  *w = (real3)(so * cos(po), so * sin(po), co);
  *m = (real3)(sin(th) * cos(ph), sin(th) * sin(ph), cos(th));
  if (dot(*w, *m) < R(0.0)) *m = (real3)(-(*m).x, -(*m).y, (*m).z);
}

// The directions of one record: view cosθ = u² (dense at grazing); half
// vector θ = (π/2) u³ (dense at the normal, where D peaks); light = view
// mirrored about the half vector (it may fall below the horizon: terms must
// return 0 there). Writes the geometry slots of the mode.
static inline void draw_geometry(int mode, uint4 rg, uint4 rk, __global float* r) {
  // the half vector on the view's side (v·h >= 0): the terms' domain
  real3 wo, h;
  draw_dir_facet(rg, &wo, &h);
  // One D record in eight takes its half vector below the horizon (n.h < 0),
  // where every D is 0 (the χ+(m·n) of Walter et al. 2007 eq. 33): a D that
  // drops its horizon test disagrees with the reference there.
  if ((mode == PW_D || mode == PW_D_ANISO) && (rk.w & 14u) == 0u) h.z = -h.z;
  real3 wi = R(2.0) * dot(wo, h) * h - wo;
  if (mode == PW_BRDF || mode == PW_MODEL || mode == PW_BRDF_ANISO) {
    r[PW_WI_X] = wi.x; r[PW_WI_Y] = wi.y; r[PW_WI_Z] = wi.z;
    r[PW_WO_X] = wo.x; r[PW_WO_Y] = wo.y; r[PW_WO_Z] = wo.z;
    return;
  }
  r[PW_NOL] = wi.z; r[PW_NOV] = wo.z; r[PW_NOH] = h.z; r[PW_VOH] = dot(wo, h);
  r[PW_AUX_X] = 0.0f; r[PW_AUX_Y] = 0.0f;
  if (mode == PW_D_ANISO) { r[PW_AUX_X] = h.x; r[PW_AUX_Y] = h.y; }
  if (mode == PW_G1_ANISO) { r[PW_AUX_X] = wo.x; r[PW_AUX_Y] = wo.y; }
}

// The directions of a BTDF record: the incident i with cosθ = u² (dense at
// grazing), a facet m with θ = (π/2) u³ on i's side, o = i refracted through m
// at the record's eta (Walter et al. 2007 eq. 40; near the critical angle k ->
// 0), straight through under total internal reflection (h_t degenerate where
// eta ~ 1). One record in eight takes o uniform on the other side (any pair),
// one in sixteen on i's side (the BTDF is 0 there). Half the records mirror
// both through the surface: light from below, relative index 1/eta.
static inline void draw_btdf(uint4 rg, uint4 re, real eta, __global float* r) {
  real3 wi, m;
  draw_dir_facet(rg, &wi, &m);
  bool below = (re.w & 1u) != 0u;
  real q = below ? eta : R(1.0) / eta;  // η_i / η_o
  real c = dot(wi, m);
  real k = R(1.0) + q * q * (c * c - R(1.0));
  real3 wo = k >= R(0.0) ? (q * c - sqrt(k)) * m - q * wi : -wi;
  uint cls = (re.w >> 1) & 15u;
  if (cls <= 2u) {  // 3 in 16: o uniform in cosine, on the other side (2 in 16) or on i's (1 in 16)
    real co = u01_open(re.x), so = safe_sqrt(R(1.0) - co * co), po = R(2.0) * MFV_PI * u01_open(re.y);
    wo = (real3)(so * cos(po), so * sin(po), cls == 2u ? co : -co);
  }
  if (below) wi = -wi, wo = -wo;
  r[PW_WI_X] = wi.x; r[PW_WI_Y] = wi.y; r[PW_WI_Z] = wi.z;
  r[PW_WO_X] = wo.x; r[PW_WO_Y] = wo.y; r[PW_WO_Z] = wo.z;
}

__kernel MFV_NO_IMPLICIT_VECTORIZE void agree_eval(ulong seed, uint stream, ulong first, int mode, int d, int g, int f,
                                                    __global const float* ranges, __global float* rec) {
  size_t i = get_global_id(0);
  ulong idx = first + i;
  uint4 rg = mfv_philox(seed, stream, 0, idx);
  uint4 rp = mfv_philox(seed, stream, 1, idx);
  uint4 rk = mfv_philox(seed, stream, 2, idx);

  // Inputs are written to the float record first and evaluated from there,
  // so the value belongs to exactly the recorded numbers.
  __global float* r = rec + i * PW_RECORD;
  r[PW_P0 + 0] = draw_param(ranges, 0, u01_open(rp.x));
  r[PW_P0 + 1] = draw_param(ranges, 1, u01_open(rp.y));
  r[PW_P0 + 2] = draw_param(ranges, 2, u01_open(rp.z));
  r[PW_P0 + 3] = draw_param(ranges, 3, u01_open(rp.w));
  r[PW_P0 + 4] = draw_param(ranges, 4, u01_open(rk.x));
  r[PW_P0 + 5] = draw_param(ranges, 5, u01_open(rk.y));
  // the anisotropic modes' alpha_y, drawn from the range of alpha_x (the D's, or the G's)
  // a whole model's p[6] from its own range, and 0 for every other record
  // (models read p[6] = 0 as their isotropic default: both paths are drawn)
  r[PW_P6] = mode == PW_G1_ANISO ? draw_param(ranges, 1, u01_open(rk.z))
             : mode == PW_D_ANISO || mode == PW_BRDF_ANISO ? draw_param(ranges, 0, u01_open(rk.z))
             : mode == PW_MODEL && (rk.w & 1u) ? draw_param(ranges, 6, u01_open(rk.z))
                                               : 0.0f;
  // the geometry after the parameters: a BTDF refracts at the record's eta
  if (mode == PW_BTDF)
    draw_btdf(rg, mfv_philox(seed, stream, 3, idx), r[PW_F0], r);
  else
    draw_geometry(mode, rg, rk, r);
  store_value(r, eval_record(mode, d, g, f, r));
}

// Evaluates records the host wrote (mfv eval): the same path as agree_eval.
__kernel MFV_NO_IMPLICIT_VECTORIZE void eval_records(int mode, int d, int g, int f, __global float* rec) {
  __global float* r = rec + get_global_id(0) * PW_RECORD;
  store_value(r, eval_record(mode, d, g, f, r));
}
