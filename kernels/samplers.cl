// Draws from the suite's sampling routines for mfv samplers (host/checks/
// samplers.cpp), which bins them and compares the histogram with the
// reference twin's pdf (host/reference/estimators.cpp) by a chi-square test.
// Built after integrate.cl: the routines tested are exactly those the
// integrals use (sample_m, sample_vis), not copies.

#define SAMPLER_MIXTURE 0  // m from sample_m's mixture; pdf_m
#define SAMPLER_SLOPES 1   // m from the Cauchy-slope branch alone; pdf_slope
#define SAMPLER_COSINE 2   // m from the cosine-lobe branch alone; cos θ / π
#define SAMPLER_VIS 3      // light direction reflect(o, sample_vis(o)) at cos_o; vis_pdf_i (i may lie below the horizon)
#define SAMPLER_FLUX 4     // bsdf_furnace's proposal over the sphere (transmission.cl): o from i at cos_o, relative index eta

// One direction per work-item, written as three floats; Philox draw 3 of
// stream `which` (a stream no integral uses with draw 3).
__kernel void draw_samples(int which, float w_in, float cos_o, float eta, ulong seed, __global float* out) {
  size_t k = get_global_id(0);
  uint4 r = mfv_philox(seed, (uint)which, 3, (ulong)k);
  real u_pick = u01_open(r.x), u_phi = u01_open(r.y), u_r = u01_open(r.z);
  real w = (real)w_in;
  real3 d;
  if (which == SAMPLER_FLUX) {
    // one draw of the mixture of shares c = (15/16, 1/32, 1/32) picked by u_pick, the
    // whole sphere (MFV_LOBE_ALL); its density is flux_mis_pdf; (0,0,0) where it gives none
    real co = (real)cos_o, ox, oy, oz;
    bool vis = u_pick < MIS_C_VIS, cosine = !(u_pick < MIS_C_VIS + MIS_C_SLOPE);
    if (!flux_mis_direction(vis, cosine, u_phi, u_r, u01_open(r.w), sqrt(sin2_from_cos(co)), co, w, (real)eta,
                            MFV_LOBE_ALL, &ox, &oy, &oz))
      ox = oy = oz = R(0.0);
    d = (real3)(ox, oy, oz);
  } else if (which == SAMPLER_VIS) {
    real co = (real)cos_o;
    real3 o = (real3)(sqrt(sin2_from_cos(co)), R(0.0), co);
    real3 m = sample_vis(o, u_phi, u_r, w);
    d = R(2.0) * dot(o, m) * m - o;  // (0,0,0) - o where sample_vis degenerates: counted as lost by the host
    if (!(m.z > R(0.0))) d = (real3)(R(0.0), R(0.0), R(0.0));
  } else {
    if (which == SAMPLER_SLOPES) u_pick = R(1.0);
    if (which == SAMPLER_COSINE) u_pick = R(0.0);
    real c, s2;
    d = sample_m(u_pick, u_phi, u_r, w, &c, &s2);
  }
  out[3 * k] = (float)d.x;
  out[3 * k + 1] = (float)d.y;
  out[3 * k + 2] = (float)d.z;
}
