// The anisotropic microfacet integrals of mfv run (host/checks/suite_aniso.cpp:
// anisotropic GGX and Beckmann, widths (pd, pd2) and (pg, pg2), the view at
// any azimuth phi_o) by components, and their one-sample-per-work-item
// kernels. d_norm (stratified in the stretched radius and the azimuth),
// masking (Heitz 2014 eq. 19 with the view's own Smith G1) and the white
// furnace (MFV_CHECK_ALBEDO, the defensive mixture) take the proposals of
// estimators.cl (sample_m_aniso_c, pdf_m_aniso_c: the Cauchy slopes
// stretched to (width, width_y), never the D under test). `integrate`'s
// sample_value takes these same functions for these integrals, so the
// kernels below give its samples to the bit. Built after estimators.cl,
// albedo.cl and convergence.cl and before integrate.cl
// (runtime/integrator.cpp integration_files).
// Straight-line code over plain arguments: no float3 value, no loop, no
// library call, selects rather than branches, so that PoCL's work-group
// vectorizer runs eight work-items per AVX2 instruction (docs/performance.md,
// "Vectorization per path"). Reference twins: host/reference/estimators.cpp.
#include "abi/integral.h"  // IntegralSpec, MFV_CHECK_* (shared with the host)

// The anisotropic integrals these functions take: the catalog's microfacet
// BRDF (model 0, no user code) with pd2 > 0, a proposal width > 0 stretched by width_y, and
// d_norm only stratified (the integrator stratifies every such d_norm).
static inline bool spec_is_aniso_microfacet(__global const IntegralSpec* s) {
#ifdef MFV_USER_BRDF
  return false;
#else
  return s->model == 0u && spec_aniso(s) && spec_stretched(s) && s->width > 0.0f && (s->check != MFV_CHECK_D_NORM || s->strata > 0u);
#endif
}

// d_norm, ∫ D(m) (m·n) dm = 1: sample `index` of `strata`. As the isotropic
// d_norm_value_c, the first strata/4 drive the cosine lobe and the rest the
// stretched slopes, each over its own strata, here 2D ones (stratum_2d: the
// integrand depends on the azimuth too).
static inline real d_norm_aniso_value_c(int d, real pd, real pd2, real w, real wy, uint strata, uint index, real u_phi,
                                        real u_r) {
  uint n_cos = strata / 4u;
  bool cosine = index < n_cos;
  uint k = cosine ? index : index - n_cos, n = cosine ? n_cos : strata - n_cos;
  stratum_2d(k, n, &u_r, &u_phi);
  real mx, my, c, s2;
  sample_m_aniso_c(cosine, u_phi, u_r, w, wy, &mx, &my, &c, &s2);
  return eval_D_aniso(d, c, s2, mx, my, pd, pd2) * c / pdf_m_aniso_c(mx, my, c, w, wy);
}

// masking, the weak white furnace ∫ G1(o) D(m) max(0, o·m) dm / (o·n) = 1
// (Heitz 2014 eq. 19; an anisotropic Smith G1 depends on o only, Λ at the
// view's projected width α(φ_o)).
static inline real masking_aniso_value_c(int d, int g, real pd, real pd2, real pg, real pg2, real w, real wy, real co,
                                         real phi_o, real u_pick, real u_phi, real u_r) {
  real ox, oy;
  spec_view_c(co, phi_o, &ox, &oy);
  real mx, my, c, s2;
  sample_m_aniso_c(u_pick < MIX_COS, u_phi, u_r, w, wy, &mx, &my, &c, &s2);
  real om = ox * mx + oy * my + co * c;
  real v = eval_G1_aniso(g, co, ox, oy, pg, pg2) * eval_D_aniso(d, c, s2, mx, my, pd, pd2) * om /
           (pdf_m_aniso_c(mx, my, c, w, wy) * co);
  return om > R(0.0) ? v : R(0.0);
}

// The directional albedo E(o) = ∫ f(i,o) (n·i) di (furnace, F = none): i from
// the cosine lobe (u_branch < MIX_I_COS) or o reflected about an m of the
// anisotropic mixture; f(i,o) (n·i) / pdf(i) with the union's pdf
// (albedo_pdf), as albedo_value_microfacet does for isotropic terms.
static inline real albedo_aniso_value_c(int d, int g, int f, real pd, real pd2, real pg, real pg2, real f0, real f1,
                                        real kd, real w, real wy, real co, real phi_o, real u_branch, real u_pick, real u_phi,
                                        real u_r) {
  real ox, oy, oz = co;
  spec_view_c(co, phi_o, &ox, &oy);
  real cx, cy, cz;  // both candidates, one selected (as in sample_m_aniso_c)
  cosine_direction(u_phi, u_r, &cx, &cy, &cz);
  real mx, my, mz, s2;
  sample_m_aniso_c(u_pick < MIX_COS, u_phi, u_r, w, wy, &mx, &my, &mz, &s2);
  real om2 = R(2.0) * (ox * mx + oy * my + oz * mz);  // o reflected about m
  bool lobe = u_branch < MIX_I_COS;
  real ix = lobe ? cx : om2 * mx - ox, iy = lobe ? cy : om2 * my - oy, iz = lobe ? cz : om2 * mz - oz;
  if (iz <= R(0.0)) return R(0.0);
  real hx, hy, hz;  // the half vector as brdf_eval_aniso_c forms it (the compiler forms it once)
  real oh = R(0.5) * normalize_sum(ix + ox, iy + oy, iz + oz, &hx, &hy, &hz);
  real pm = pdf_m_aniso_c(hx, hy, hz, w, wy);
  return brdf_eval_aniso_c(d, g, f, ix, iy, iz, ox, oy, oz, pd, pd2, pg, pg2, f0, f1, kd) * iz /
         albedo_pdf(iz, oh, pm);
}

// One sample of integral `s` (spec_is_aniso_microfacet: d_norm, masking or
// albedo) at `index` from its four uniforms: `integrate`'s sample_value.
static inline real aniso_sample_value(__global const IntegralSpec* s, uint index, real u_branch, real u_pick,
                                      real u_phi, real u_r) {
  if (s->check == MFV_CHECK_D_NORM)
    return d_norm_aniso_value_c(s->d, s->pd, s->pd2, s->width, s->width_y, s->strata, index, u_phi, u_r);
  if (s->check == MFV_CHECK_MASKING)
    return masking_aniso_value_c(s->d, s->g, s->pd, s->pd2, s->pg, s->pg2, s->width, s->width_y, s->cos_o, s->phi_o, u_pick,
                                 u_phi, u_r);
  return albedo_aniso_value_c(s->d, s->g, s->f, s->pd, s->pd2, s->pg, s->pg2, s->f0, s->f1, s->kd, s->width, s->width_y,
                              s->cos_o, s->phi_o, u_branch, u_pick, u_phi, u_r);
}

#ifndef MFV_USER_BRDF
// The fast paths (host: Integrator::run, values_kernel), as d_norm_values;
// sum_pairs (d_norm: neighbouring strata) or sum_values reduce.
MFV_SAMPLE_VALUES(d_norm_aniso_values, d_norm_aniso_value_c(s->d, s->pd, s->pd2, s->width, s->width_y, s->strata, (uint)(first + k),
                                                                  u01_open(r.z), u01_open(r.w)))
MFV_SAMPLE_VALUES(masking_aniso_values,
                        masking_aniso_value_c(s->d, s->g, s->pd, s->pd2, s->pg, s->pg2, s->width, s->width_y, s->cos_o, s->phi_o,
                                              u01_open(r.y), u01_open(r.z), u01_open(r.w)))
MFV_SAMPLE_VALUES(albedo_aniso_values,
                        albedo_aniso_value_c(s->d, s->g, s->f, s->pd, s->pd2, s->pg, s->pg2, s->f0, s->f1, s->kd,
                                             s->width, s->width_y, s->cos_o, s->phi_o, u01_open(r.x), u01_open(r.y), u01_open(r.z),
                                             u01_open(r.w)))
#endif
