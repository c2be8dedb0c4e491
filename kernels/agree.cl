// Pointwise agreement: evaluates one term or one assembled BRDF on
// Philox-generated inputs and writes the inputs it used beside the value, so
// the reference evaluates the identical (float-rounded) inputs.
//
// Record layout (16 floats): [0..5] geometry, [6..11] parameters (a whole model's p[0..5], its p[6] in [14]),
// [12] value (float part), [13] value - float part (double builds), [14] the second
// width of the anisotropic modes (alpha_y of D and G; a whole model's p[6]), [15] unused.
// Geometry: modes D, G, F, G1 store NoL, NoV, NoH, VoH; modes BRDF and MODEL store wi.xyz, wo.xyz;
// D_ANISO adds h.x, h.y in [4], [5] and G1_ANISO wo.x, wo.y (tangent frame t = +x, b = +y).

#define AGREE_D 0
#define AGREE_G 1
#define AGREE_F 2
#define AGREE_G1 3
#define AGREE_BRDF 4
#define AGREE_MODEL 5  // `d` carries the model's number
#define AGREE_D_ANISO 6   // anisotropic terms (Term::aniso) with both widths
#define AGREE_G1_ANISO 7
#define AGREE_BRDF_ANISO 8
#define AGREE_RECORD 16

// ranges: 7 slots (D param, G param, F p0, F p1, kd, p5, a whole model's p[6]) x (lo, hi, log flag)
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

// Evaluates one record: the value depends only on what the record holds.
static inline real eval_record(int mode, int d, int g, int f, __global const float* r) {
  // A record names directions. In double builds the float-rounded record is
  // unit only to ~1e-8, far above double rounding, so it is made unit first
  // (the reference does the same in double); float builds take it as it is.
  // r[0..5]: the light and view of BRDF and model records (unused by the others)
  real3 wi = (real3)(r[0], r[1], r[2]), wo = (real3)(r[3], r[4], r[5]);
#ifdef MFV_DOUBLE
  wi = unit_exact(wi);
  wo = unit_exact(wo);
#endif
  if (mode == AGREE_MODEL) {
    real p[7] = {r[6], r[7], r[8], r[9], r[10], r[11], r[14]};
    return eval_model(d, wi, wo, p);
  }
  if (mode == AGREE_D_ANISO || mode == AGREE_G1_ANISO) {
    // the half vector or view (x, y, z = NoH or NoV) as recorded, not made
    // unit: the reference evaluates the kernels' forms at exactly these
    // numbers (agree.cpp: G1 is homogeneous of degree 0 in w, D of degree -4)
    real3 w = (real3)(r[4], r[5], mode == AGREE_D_ANISO ? r[2] : r[1]);
    if (mode == AGREE_D_ANISO) return eval_D_aniso(d, w.z, sin2_from_cos(w.z), w.x, w.y, r[6], r[14]);
    return eval_G1_aniso(g, w.z, w.x, w.y, r[7], r[14]);
  }
  if (mode == AGREE_BRDF_ANISO) return brdf_eval_aniso(d, g, f, wi, wo, r[6], r[14], r[7], r[14], r[8], r[9], r[10]);
  if (mode == AGREE_BRDF) return brdf_eval(d, g, f, wi, wo, r[6], r[7], r[8], r[9], r[10]);
  if (mode == AGREE_D) return eval_D(d, r[2], sin2_from_cos(r[2]), r[6]);
  if (mode == AGREE_G) return eval_G(g, r[0], r[1], r[2], r[3], r[7]);
  if (mode == AGREE_G1) return eval_G1(g, r[1], r[7]);
  return eval_F(f, r[3], r[8], r[9]);
}

// The value as float plus the float remainder (a double survives to ~48 bits).
static inline void store_value(__global float* r, real value) {
  float hi = (float)value;
  r[12] = hi;
  r[13] = isfinite(value) ? (float)(value - (real)hi) : 0.0f;
}

__kernel void agree_eval(ulong seed, uint stream, ulong first, int mode, int d, int g, int f,
                         __global const float* ranges, __global float* rec) {
  size_t i = get_global_id(0);
  ulong idx = first + i;
  uint4 rg = mfv_philox(seed, stream, 0, idx);
  uint4 rp = mfv_philox(seed, stream, 1, idx);
  uint4 rk = mfv_philox(seed, stream, 2, idx);

  // View: cosθ = u² (dense at grazing); half vector: θ = (π/2) u³ (dense at
  // the normal, where D peaks); light = view mirrored about the half vector
  // (it may fall below the horizon: terms must return 0 there).
  real co = sqr(u01_open(rg.x));
  real so = safe_sqrt(R(1.0) - co * co);
  real po = R(2.0) * MFV_PI * u01_open(rg.y);
  real th = R(0.5) * MFV_PI * pow(u01_open(rg.z), R(3.0));
  real ph = R(2.0) * MFV_PI * u01_open(rg.w);
  real3 wo = (real3)(so * cos(po), so * sin(po), co);
  real3 h = (real3)(sin(th) * cos(ph), sin(th) * sin(ph), cos(th));
  // Keep the half vector on the view's side (v·h >= 0), the terms' domain:
  // turning it by π about the normal makes v·h >= 2 (n·v)(n·h).
  if (dot(wo, h) < R(0.0)) h = (real3)(-h.x, -h.y, h.z);
  // One D record in eight takes its half vector below the horizon (n.h < 0),
  // where every D is 0 (the χ+(m·n) of Walter et al. 2007 eq. 33): a D that
  // drops its horizon test disagrees with the reference there.
  if ((mode == AGREE_D || mode == AGREE_D_ANISO) && (rk.w & 14u) == 0u) h.z = -h.z;
  real3 wi = R(2.0) * dot(wo, h) * h - wo;

  // Inputs are written to the float record first and evaluated from there,
  // so the value belongs to exactly the recorded numbers.
  real p[6];
  p[0] = draw_param(ranges, 0, u01_open(rp.x));
  p[1] = draw_param(ranges, 1, u01_open(rp.y));
  p[2] = draw_param(ranges, 2, u01_open(rp.z));
  p[3] = draw_param(ranges, 3, u01_open(rp.w));
  p[4] = draw_param(ranges, 4, u01_open(rk.x));
  p[5] = draw_param(ranges, 5, u01_open(rk.y));

  __global float* r = rec + i * AGREE_RECORD;
  if (mode == AGREE_BRDF || mode == AGREE_MODEL || mode == AGREE_BRDF_ANISO) {
    r[0] = wi.x; r[1] = wi.y; r[2] = wi.z;
    r[3] = wo.x; r[4] = wo.y; r[5] = wo.z;
  } else {
    r[0] = wi.z; r[1] = wo.z; r[2] = h.z; r[3] = dot(wo, h); r[4] = 0.0f; r[5] = 0.0f;
    if (mode == AGREE_D_ANISO) { r[4] = h.x; r[5] = h.y; }
    if (mode == AGREE_G1_ANISO) { r[4] = wo.x; r[5] = wo.y; }
  }
  for (int k = 0; k < 6; ++k) r[6 + k] = p[k];
  // the anisotropic modes' alpha_y, drawn from the range of alpha_x (the D's, or the G's)
  // a whole model's p[6] from its own range, and 0 for every other record
  // (models read p[6] = 0 as their isotropic default: both paths are drawn)
  r[14] = mode == AGREE_G1_ANISO ? draw_param(ranges, 1, u01_open(rk.z))
          : mode == AGREE_D_ANISO || mode == AGREE_BRDF_ANISO ? draw_param(ranges, 0, u01_open(rk.z))
          : mode == AGREE_MODEL && (rk.w & 1u) ? draw_param(ranges, 6, u01_open(rk.z))
                                               : 0.0f;
  r[15] = 0.0f;
  store_value(r, eval_record(mode, d, g, f, r));
}

// Evaluates records the host wrote (mfv eval): the same path as agree_eval.
__kernel void eval_records(int mode, int d, int g, int f, __global float* rec) {
  __global float* r = rec + get_global_id(0) * AGREE_RECORD;
  store_value(r, eval_record(mode, d, g, f, r));
}
