// The albedo estimators: mfv energy's randomized-QMC visible-normal
// estimator (with the split sum's B), the isotropic microfacet albedo by
// components (the vectorized fast path), mfv run's multi-sample MIS on RQMC
// replicates, and the general albedo sample. Needs estimators.cl.
// Reference twins: host/reference/estimators.cpp.
#include "abi/integral.h"  // IntegralSpec, MFV_CHECK_*, MFV_EST_*, MFV_SLOT_* (shared with the host)

// f(i,o) (n·i) / pdf(i) for i = reflect(o, m), m a visible normal of D_w;
// *schlick0 = (1 - o·h)^5, Schlick's F at F0 = 0 (the split sum's B weight).
static inline real energy_weight(__global const IntegralSpec* s, real3 m, real3 o, real so2, real w,
                                 real* schlick0) {
  *schlick0 = R(0.0);
  real om2 = R(2.0) * (o.x * m.x + o.y * m.y + o.z * m.z);
  real3 i = (real3)(om2 * m.x - o.x, om2 * m.y - o.y, om2 * m.z - o.z);
  if (i.z <= R(0.0)) return R(0.0);
  real hx, hy, hz;  // h = m up to rounding; formed as brdf_eval forms it
  real len = normalize_sum(i.x + o.x, i.y + o.y, i.z + o.z, &hx, &hy, &hz);
  real c = R(1.0) - min(R(0.5) * len, R(1.0));  // 1 - o·h as brdf_eval's VoH
  *schlick0 = c * c * c * c * c;
  return spec_brdf(s, i, o) * i.z / vis_pdf_i(hz, hx * hx + hy * hy, o.z, so2, w);
}

static inline uint4 rqmc_shift(__global const IntegralSpec* s, ulong seed) { return mfv_philox(seed, s->stream, spec_draw(s, 2u), 0); }

// The isotropic microfacet integrals that the component-wise fast paths take
// (see albedo_value_microfacet below).
static inline bool spec_is_microfacet(__global const IntegralSpec* s) {
#ifdef MFV_USER_BRDF
  return false;
#else
  return s->model == 0u && !spec_aniso(s) && !spec_stretched(s) && s->phi_o == 0.0f && s->width > 0.0f;
#endif
}

// The view cosine of point k of MFV_CHECK_EAVG_RQMC: density 2μ, μ²
// stratified over the integral's `strata` points with one random shift (a
// rank-1 lattice with the 2D sequence), N^-1 like the rest. μ² = p(v) by
// the periodizing transform of rqmc_radial (below), *jac = p'(v): E(μ) is not
// periodic in μ² (E(0) != E(1)) and grows as a power of μ at grazing views;
// measured in double at alpha = 0.04, 2^20 points: replicate SE of E_avg from
// 4.4e-7 to 2.7e-7.
static inline real eavg_cos(uint4 shift, uint k, uint strata, real* jac) {
  real u = u01_open(shift.z) + (real)k / (real)strata;
  u = u - floor(u);
  *jac = R(6.0) * u * (R(1.0) - u);
  return sqrt(u * u * (R(3.0) - R(2.0) * u));
}

// The periodizing transform of the radial RQMC coordinate (Korobov's
// polynomial transform, degree 3: Sloan & Joe 1994, "Lattice Methods for
// Multiple Integration", §2.12): the visible normal is drawn at
// u_r = t²(3 - 2t) from the lattice coordinate t, and the weight carries
// du_r/dt = 6t(1 - t). The integrand in t vanishes at both ends (the
// Kronecker set is a lattice on the torus: a non-periodic integrand costs it
// its N^-1), and 1 - u_r ≈ 3(1 - t)² spreads the narrow lobes' tails,
// 1 - u_r ~ α²/tan²θ_h, over a band of t of width ~α/tanθ_h instead of
// α²/tan²θ_h, where the light crosses the horizon. Measured in double at
// 2^20 points (GGX, height-correlated Smith): the replicate SE at
// alpha = 0.04, mu = 0.5 from 4.1e-6 to 9.2e-8; alpha = 1, mu = 0.1 from
// 3.0e-7 to 7.1e-8 (docs/performance.md). Twin: rqmc_radial in estimators.cpp.
static inline real rqmc_radial(real t, real* jac) {
  *jac = R(6.0) * t * (R(1.0) - t);
  return t * t * (R(3.0) - R(2.0) * t);
}

// albedo_rqmc_value of an isotropic microfacet integral (spec_is_microfacet)
// by components, in straight-line code over plain arguments, so that
// albedo_rqmc_values vectorizes (see albedo_value_microfacet below): the same
// operations in the same order as energy_weight with brdf_eval, so both give
// the same value to the bit.
// Returns E and sets *b to B (scalars: a 2-lane real2 select would keep
// PoCL from vectorizing across work-items).
static inline MFV_ALWAYS_INLINE real albedo_rqmc_microfacet(int d, int g, int f, real pd, real pg, real f0, real f1, real kd, real w,
                                          real co, uint4 shift, uint k, real* b) {
  real jac, u_phi = u01_open(shift.x + k * RQMC_G1), u_r = rqmc_radial(u01_open(shift.y + k * RQMC_G2), &jac);
  real so2 = sin2_from_cos(co), ox = sqrt(so2);
  real mx, my, mz;
  sample_vis_c(ox, R(0.0), co, u_phi, u_r, w, &mx, &my, &mz);
  real om2 = R(2.0) * (ox * mx + R(0.0) * my + co * mz);
  real ix = om2 * mx - ox, iy = om2 * my - R(0.0), iz = om2 * mz - co;
  bool live = mz > R(0.0) && iz > R(0.0);
  real hx, hy, hz;
  real len = normalize_sum(ix + ox, iy + R(0.0), iz + co, &hx, &hy, &hz);
  real c = R(1.0) - min(R(0.5) * len, R(1.0));
  // brdf_eval_c in select form (haswell: a branch leaves the loads conditional)
  real fv = brdf_above_c(d, g, f, ix, iy, iz, ox, R(0.0), co, pd, pg, f0, f1, kd);
  real e = (fmin(iz, co) <= R(0.0) ? R(0.0) : fv) * iz /
           vis_pdf_i(hz, hx * hx + hy * hy, co, so2, w) * jac;
  *b = live ? e * (c * c * c * c * c) : R(0.0);
  return live ? e : R(0.0);
}

// One point of MFV_CHECK_ALBEDO_RQMC / MFV_CHECK_EAVG_RQMC: the albedo integrand and,
// on the same direction, that of the split sum's B (the same BRDF with F
// multiplied by (1 - o·h)^5: B is defined with F = none, kd = 0).
// `shift` is the integral's Cranley-Patterson shift, rqmc_shift(s, seed):
// one Philox draw per integral, taken by the caller outside its sample loop.
static inline real2 albedo_rqmc_value(__global const IntegralSpec* s, uint4 shift, ulong index) {
  uint k = (uint)index;
  real jv = R(1.0), co = s->cos_o;
  if (s->check == MFV_CHECK_EAVG_RQMC) co = eavg_cos(shift, k, s->strata, &jv);
  if (spec_is_microfacet(s)) {
    real b;
    real e = albedo_rqmc_microfacet(s->d, s->g, s->f, s->pd, s->pg, s->f0, s->f1, s->kd, s->width, co, shift, k, &b);
    return (real2)(e * jv, b * jv);
  }
  real jac, u_phi = u01_open(shift.x + k * RQMC_G1), u_r = rqmc_radial(u01_open(shift.y + k * RQMC_G2), &jac);
  real so2 = sin2_from_cos(co);
  real3 o = (real3)(sqrt(so2), R(0.0), co);
  real3 m = sample_vis(o, u_phi, u_r, s->width);
  if (!(m.z > R(0.0))) return (real2)(R(0.0), R(0.0));
  real b;
  real e = energy_weight(s, m, o, so2, s->width, &b) * jac * jv;
  return (real2)(e, e * b);
}

// One sample of the directional albedo E(o) = ∫ f(i,o) (n·i) di
// (MFV_CHECK_ALBEDO) from its four uniforms: i from a cosine lobe or by
// reflecting o about an m from the mixture; the pdf is that of the union.
// Component arithmetic and sincos_2pi: no float3 operations, no out-of-line
// calls (measured 1.6x faster on PoCL than float3, length() and sin/cos).
// The isotropic microfacet BRDF's albedo (spec_is_microfacet: model 0,
// pd2 = 0, phi_o = 0, one proposal width > 0, no user code) is the case of
// the conformance suite and of mfv bench. Its sample is computed here by
// components, in straight-line code over plain arguments (no float3, no
// loop, no library call: see sincos_2pi), so that PoCL's work-group
// vectorizer runs eight work-items per AVX2 instruction in albedo_values.
// The general path below takes the other albedo integrals.

// Its two stages, apart so that albedo_values can interleave two samples
// (below): the light direction i (o = (ox, 0, oz), the view
// at phi_o = 0; `lobe`: the cosine lobe's branch, u_branch < MIX_I_COS)...
static inline void albedo_light_microfacet(bool lobe, real w, real ox, real oz, real u_pick, real u_phi, real u_r,
                                           real* ix, real* iy, real* iz) {
  // both candidates, one selected (as in sample_m_c)
  real cx, cy, cz;
  cosine_direction(u_phi, u_r, &cx, &cy, &cz);
  real mx, my, c, s2;
  sample_m_c(u_pick < MIX_COS, u_phi, u_r, w, &mx, &my, &c, &s2);
  real om2 = R(2.0) * (ox * mx + oz * c);  // o reflected about m
  real rx = om2 * mx - ox, ry = om2 * my, rz = om2 * c - oz;
  *ix = lobe ? cx : rx;
  *iy = lobe ? cy : ry;
  *iz = lobe ? cz : rz;
}

// ...and the sample's value at i, f(i,o) (n·i) / pdf(i).
static inline real albedo_weight_microfacet(int d, int g, int f, real pd, real pg, real f0, real f1, real kd, real w,
                                            real ox, real oz, real ix, real iy, real iz) {
  real hx, hy, hz;
  // |i + o| = 2 o·h, and the half vector, formed once for the pdf and the
  // BRDF (brdf_eval_c's own: iy + 0 is the view's y)
  real len = normalize_sum(ix + ox, iy + R(0.0), iz + oz, &hx, &hy, &hz);
  real hs2 = hx * hx + hy * hy, oh = R(0.5) * len;
  real pm = pdf_mix(hz, pdf_slope(hz, hs2, w));
  // brdf_eval_c, whose horizon test and half vector these are
  real fr = (iz <= R(0.0) || oz <= R(0.0)) ? R(0.0) : brdf_above_h(d, g, f, iz, oz, hz, hs2, oh, pd, pg, f0, f1, kd);
  return iz <= R(0.0) ? R(0.0) : fr * iz / albedo_pdf(iz, oh, pm);
}

static inline real albedo_value_microfacet(int d, int g, int f, real pd, real pg, real f0, real f1, real kd, real w,
                                           real co, real u_branch, real u_pick, real u_phi, real u_r) {
  real ox = sqrt(sin2_from_cos(co)), oz = co;  // spec_view at phi_o = 0
  real ix, iy, iz;
  albedo_light_microfacet(u_branch < MIX_I_COS, w, ox, oz, u_pick, u_phi, u_r, &ix, &iy, &iz);
  return albedo_weight_microfacet(d, g, f, pd, pg, f0, f1, kd, w, ox, oz, ix, iy, iz);
}

// ---- mfv run's albedo (MFV_CHECK_ALBEDO_MIS; host: IntegralKind::AlbedoMis) --
// Three proposals of the light direction i, none of which calls a term under
// test (DESIGN.md §3): (a) o reflected about a visible normal of the GGX
// *shape* of width w (sample_vis_c, vis_pdf_i: Heitz 2018, written here, never
// D_*/G1_*), the low-variance one; (b) o reflected about Cauchy slopes of
// width w and (c) the cosine lobe, the defensive pair whose tails cover every
// catalog D (see the top of estimators.cl). Combined by multi-sample MIS
// with the balance heuristic over a fixed mixture c = (61/64, 1/64, 1/32)
// (Veach 1997 §9.2.2, eq. 9.13 with weights c_t p_t / Σ c_s p_s): every point
// of proposal t contributes c_t (n / n_t) f(i,o) (n·i) / (Σ_s c_s p_s(i)),
// so the mean over the n points is Σ_t c_t (mean over t's points), which is
// unbiased for any point counts n_t. A wrong D or G under test only enters
// the numerator, so it cannot cancel (tests/test_albedo_mis.cpp plants
// three), and f/q <= 64 f / p_slope and 32 f / p_cosine stay bounded.
// Points: index = r n + k with n = `points` = 5·2^(m-2) per replicate
// (Integrator::mis_points): k < 2^m = 4n/5 takes (a), the next n/10 (b),
// the last n/10 (c), each share a power of two on Owen-scrambled Sobol
// points (owen_sobol_2d: (a) seeded by Philox words x, y of draw 3 at counter
// r, (b) by z, w, (c) by w, z), so each share is a whole (0, m, 2)-net. The
// shares and the net sizes are measured (docs/statistics.md): against a
// 1/2, 1/4, 1/4 split on Kronecker points the variance per point fell
// 30-140x at (alpha, mu) = (0.5, 0.5), (0.1, 0.1), (0.01, 0.9); a share
// that is not a power of two (3·2^10) gave no more than its 2^11 net alone.
// Replicates are independent, so their spread gives an honest standard
// error (host: Integrator::run, Student t with R - 1 degrees of freedom).
// Rim-dense (a): (a) draws its visible normal at 1 - u_r = (1 - t)^1.5
// from the net's radial coordinate t and weights the point by du_r/dt =
// 1.5 (1 - t)^0.5 (a change of variables in (a)'s own unit square, so its
// share's mean stays unbiased, and q, the other shares and their points are
// untouched). Near the cap's rim (u_r -> 1, h grazing the view) (a)'s
// integrand falls from ~1 to 0 within 1 - u_r ~ 1e-3..3e-2 at alpha 0.01,
// mu 0.9, where the Cauchy share's density overtakes the GGX shape's tail
// in q (and, below that, i crosses the horizon): a step the net cannot
// resolve at 2^8 points; in t it is 1e-2..1e-1 wide (the idea of
// rqmc_radial's polynomial transform, Sloan & Joe 1994 §2.12, at one end).
// The exponent is the D's to pay for: (a) is the GGX shape whatever D is
// under test, and a lighter-tailed D (Beckmann, Phong) is ~0 near the rim,
// where the change puts more points. Measured in double (numpy twin of
// this share, 80 points, 100 replicates, alpha 0.01..1 x mu 0.02..0.99),
// the summed variance per point against exponent 1 (no change), 1.25, 1.5,
// 2: GGX D 0.063, 0.036, 0.028, 0.030; Beckmann D 0.159, 0.176, 0.180,
// 0.266. At 2 mfv run's furnace pooled SEs rose 1.2-1.45x for every
// non-GGX D (fell 0.6-0.8x for GGX): 1.5 keeps GGX's gain at about a tenth
// of that cost. Variance per point of the three shares together (twin,
// 150-200 replicates), before -> after: alpha 0.01, mu 0.9 at 320 points
// 2.5e-4 -> 5.3e-5, at 2560 6.5e-6 -> 3.1e-6; alpha 0.1, mu 0.1 at 2560
// 2.6e-4 -> 4.1e-5; alpha 0.5, mu 0.5 at 2560 2.6e-5 -> 2.3e-5
// (docs/statistics.md). The same change on the Cauchy share raised its
// variance.
// Reference twin: albedo_mis in host/reference/estimators.cpp.
#define MIS_C_VIS R(0.9375)
#define MIS_C_SLOPE R(0.03125)
#define MIS_C_COS R(0.03125)
// The albedo's own mixture, c = (61/64, 1/64, 1/32) on the same points: the
// Cauchy share's weight halved from the glass flux's 1/32 (above, kept by
// bsdf_flux_mis) lowers the variance per point 1.3-1.5x at (alpha, mu) =
// (0.5, 0.5), leaves (0.1, 0.1) and mfv run's diffuse-lobe albedos
// (energy_diffuse: the cosine share's 1/32 kept) as they were, and raises
// it 1.1-1.3x at (0.01, 0.9) (docs/performance.md, issue 32); the weight stays
// bounded, f/q <= 64 f / p_slope and 32 f / p_cosine.
#define ALB_C_VIS R(0.953125)
#define ALB_C_SLOPE R(0.015625)
#define ALB_C_COS R(0.03125)
// c_t n / n_t: (61/64)(5/4) = 305/256 for (a), (1/64) 10 = 5/32 for (b), (1/32) 10 = 5/16 for (c)
#define ALB_SHARE_VIS R(1.19140625)
#define ALB_SHARE_SLOPE R(0.15625)
#define ALB_SHARE_COS R(0.3125)
#define MIS_DRAW 3u  // the Philox draw of the replicates' scramble seeds

static inline uint4 mis_shift(__global const IntegralSpec* s, ulong seed, uint replicate) {
  return mfv_philox(seed, s->stream, spec_draw(s, MIS_DRAW), replicate);
}

// Point k of n of a replicate with seeds `shift`, by components and with
// selects (no branch, no float3: albedo_mis_values vectorizes, see
// albedo_values); the three candidates share one (u_phi, u_r).
// In three parts, so that albedo_mis_values is three kernels
// (kernels/integrate.cl), and the cold run compiles one kernel per D and one
// per G where it compiled one per (D, G) pair (docs/performance.md, "Cold
// start"): albedo_mis_geometry_c, which evaluates no D and no G (one kernel),
// gives i·n = iz (<= 0: below the horizon, value 0), the half vector's
// NoH = hz and |n×h|² = hs2, o·h = oh, the mixture density q of i and F;
// D F is then one D's part (albedo_mis_df_c), and albedo_mis_weight_g the
// point's value from D F and one G. Each part rounds as brdf_above_c's
// D F G in one expression does ((D F) G), so the floats are those of the
// one-piece estimator.
static inline MFV_ALWAYS_INLINE void albedo_mis_geometry_c(int f, real f0, real f1, real w, real co, uint4 shift, uint k,
                                                           uint n, real* iz_out, real* hz_out, real* hs2_out,
                                                           real* oh_out, real* q_out, real* f_out) {
  uint n_def = n / 10u, n_vis = 8u * n_def;
  bool vis = k < n_vis, cosine = k >= n_vis + n_def;
  uint j = vis ? k : cosine ? k - n_vis - n_def : k - n_vis;
  real u_phi, u_r;
  owen_sobol_2d(j, vis ? shift.x : cosine ? shift.w : shift.z, vis ? shift.y : cosine ? shift.z : shift.w, &u_phi, &u_r);
  real so2 = sin2_from_cos(co), ox = sqrt(so2), oz = co;  // the view in the xz-plane
  real vx, vy, vz, sx, sy, sz, s2;
  // (a) at its rim-dense radial coordinate (above ALB_C_VIS): 1 - u_r = (1 - t)^1.5, t the
  // net's coordinate (1 - t exact: u01_open's values are odd multiples of 2^-24)
  real v = R(1.0) - u_r, sv = sqrt(v);
  sample_vis_aniso_v(ox, R(0.0), oz, u_phi, v * sv, w, w, &vx, &vy, &vz);
  sample_m_c(false, u_phi, u_r, w, &sx, &sy, &sz, &s2);
  real mx = vis ? vx : sx, my = vis ? vy : sy, mz = vis ? vz : sz;
  real om2 = R(2.0) * (ox * mx + oz * mz);  // o reflected about m (m = 0, a degenerate visible normal: i = -o)
  real cx, cy, cz;
  cosine_direction(u_phi, u_r, &cx, &cy, &cz);
  real ix = cosine ? cx : om2 * mx - ox, iy = cosine ? cy : om2 * my, iz = cosine ? cz : om2 * mz - oz;
  real hx, hy, hz;
  real oh = R(0.5) * normalize_sum(ix + ox, iy + R(0.0), iz + oz, &hx, &hy, &hz);  // as brdf_eval_c forms it
  real hs2 = hx * hx + hy * hy;
  // the pdfs of i under each proposal: (a) vis_pdf_i; (b) the slope density
  // of h with the reflection Jacobian 1 / (4 o·h); (c) cos/π
  real q = ALB_C_VIS * vis_pdf_i(hz, hs2, oz, so2, w) + ALB_C_SLOPE * pdf_slope(hz, hs2, w) / (R(4.0) * oh) +
           ALB_C_COS * iz * MFV_INV_PI;
  *q_out = vis ? q / (R(1.5) * sv) : q;  // (a)'s weight du_r/dt = 1.5 (1 - t)^0.5 as a divisor of q
  *iz_out = iz;
  *hz_out = hz;
  *hs2_out = hs2;
  *oh_out = oh;
  *f_out = eval_F(f, min(oh, R(1.0)), f0, f1);  // brdf_above_h's VoH
}

static inline MFV_ALWAYS_INLINE real albedo_mis_df_c(int d, real pd, real hz, real hs2, real fv) {
  return eval_D(d, hz, hs2, pd) * fv;
}

static inline MFV_ALWAYS_INLINE real albedo_mis_weight_g(int g, real pg, real kd, real co, uint k, uint n, real iz,
                                                         real hz, real oh, real q, real df) {
  uint n_def = n / 10u, n_vis = 8u * n_def;
  bool vis = k < n_vis, cosine = k >= n_vis + n_def;
  real share = vis ? ALB_SHARE_VIS : cosine ? ALB_SHARE_COS : ALB_SHARE_SLOPE;
  // brdf_eval_c at (i, o), as brdf_above_h forms it from the half vector
  real spec = df * eval_G(g, iz, co, hz, min(oh, R(1.0)), pg);
  real fv = co <= R(0.0) ? R(0.0) : brdf_of_spec(spec, iz, co, kd);
  real v = share * fv * iz / q;
  // below the horizon: 0, as a select (a branch leaves the loads of the
  // planes conditional, and haswell's (AVX2) cost model then keeps this
  // kernel scalar: the AVX2 column of scripts/pocl-vectorization.sh)
  return iz <= R(0.0) ? R(0.0) : v;
}

static inline MFV_ALWAYS_INLINE real albedo_mis_microfacet(int d, int g, int f, real pd, real pg, real f0, real f1, real kd, real w,
                                         real co, uint4 shift, uint k, uint n) {
  real iz, hz, hs2, oh, q, fv;
  albedo_mis_geometry_c(f, f0, f1, w, co, shift, k, n, &iz, &hz, &hs2, &oh, &q, &fv);
  return albedo_mis_weight_g(g, pg, kd, co, k, n, iz, hz, oh, q, albedo_mis_df_c(d, pd, hz, hs2, fv));
}

// The same estimator for every other albedo integral of mfv run (anisotropic
// terms, whole models, a scene's glTF lobes, a user's BRDF): the view o at
// its azimuth (spec_view), the BRDF through spec_brdf, and proposals (a) and
// (b) stretched to the widths (width, width_y) where the spec has two
// (vis_pdf_i_aniso, sample_vis_aniso_v at the rim-dense coordinate, pdf_slope_aniso; sample_m_aniso_c
// for the slopes), the same points, shares and weights as
// albedo_mis_microfacet, which it equals up to rounding at one width and
// phi_o = 0. Needs a width > 0 (a user file that declares no roughness keeps
// the defensive mixture of widths: host/user/user_check.cpp). Twin:
// albedo_mis in host/reference/estimators.cpp.
static inline real albedo_mis_general(__global const IntegralSpec* s, uint4 shift, uint k, uint n) {
  uint n_def = n / 10u, n_vis = 8u * n_def;
  bool vis = k < n_vis, cosine = k >= n_vis + n_def;
  uint j = vis ? k : cosine ? k - n_vis - n_def : k - n_vis;
  real u_phi, u_r;
  owen_sobol_2d(j, vis ? shift.x : cosine ? shift.w : shift.z, vis ? shift.y : cosine ? shift.z : shift.w, &u_phi, &u_r);
  real wx = s->width, wy = spec_stretched(s) ? s->width_y : s->width;
  real3 o = spec_view(s);
  real v = R(1.0) - u_r, sv = sqrt(v);  // (a) rim-dense, as albedo_mis_geometry_c
  real ix, iy, iz;
  if (cosine) {
    cosine_direction(u_phi, u_r, &ix, &iy, &iz);
  } else {
    real mx, my, mz, s2;
    if (vis) sample_vis_aniso_v(o.x, o.y, o.z, u_phi, v * sv, wx, wy, &mx, &my, &mz);
    else sample_m_aniso_c(false, u_phi, u_r, wx, wy, &mx, &my, &mz, &s2);
    real om2 = R(2.0) * (o.x * mx + o.y * my + o.z * mz);
    ix = om2 * mx - o.x;
    iy = om2 * my - o.y;
    iz = om2 * mz - o.z;
  }
  if (iz <= R(0.0)) return R(0.0);
  real hx, hy, hz;
  real oh = R(0.5) * normalize_sum(ix + o.x, iy + o.y, iz + o.z, &hx, &hy, &hz);
  real q = ALB_C_VIS * vis_pdf_i_aniso(hx, hy, hz, o.x, o.y, o.z, wx, wy) +
           ALB_C_SLOPE * pdf_slope_aniso(hx, hy, hz, wx, wy) / (R(4.0) * oh) + ALB_C_COS * iz * MFV_INV_PI;
  real share = vis ? ALB_SHARE_VIS : cosine ? ALB_SHARE_COS : ALB_SHARE_SLOPE;
  q = vis ? q / (R(1.5) * sv) : q;  // (a)'s du_r/dt, as albedo_mis_geometry_c
  return share * spec_brdf(s, (real3)(ix, iy, iz), o) * iz / q;
}

static inline real albedo_mis_value(__global const IntegralSpec* s, ulong seed, ulong index) {
  uint n = s->points;
  uint4 shift = mis_shift(s, seed, (uint)(index / n));
  if (!spec_is_microfacet(s)) return albedo_mis_general(s, shift, (uint)(index % n), n);
#ifdef MFV_USER_BRDF
  return NAN;  // unreachable: spec_is_microfacet is false in user programs
#else
  return albedo_mis_microfacet(s->d, s->g, s->f, s->pd, s->pg, s->f0, s->f1, s->kd, s->width, s->cos_o, shift,
                               (uint)(index % n), n);
#endif
}

static inline real albedo_value(__global const IntegralSpec* s, real u_branch, real u_pick, real u_phi, real u_r) {
  if (spec_is_microfacet(s))
    return albedo_value_microfacet(s->d, s->g, s->f, s->pd, s->pg, s->f0, s->f1, s->kd, s->width, s->cos_o, u_branch,
                                   u_pick, u_phi, u_r);
  real w = s->width;
  real3 o = spec_view(s);
  real3 i;
  if (u_branch < MIX_I_COS) {
    real ix, iy, iz;
    cosine_direction(u_phi, u_r, &ix, &iy, &iz);
    i = (real3)(ix, iy, iz);
  } else {
    real c, s2;
    real3 m = spec_stretched(s) ? sample_m_aniso(u_pick, u_phi, u_r, w, s->width_y, &c, &s2)
                            : sample_m(u_pick, u_phi, u_r, w, &c, &s2);
    real om2 = R(2.0) * (o.x * m.x + o.y * m.y + o.z * m.z);
    i = (real3)(om2 * m.x - o.x, om2 * m.y - o.y, om2 * m.z - o.z);
  }
  return albedo_weight(s, i, o, w);
}

#ifndef MFV_USER_BRDF
// The fast path of `integrate` for isotropic microfacet albedo integrals
// (spec_is_microfacet; host: Integrator::run). Two samples per work-item
// and no barrier: PoCL turns a work-group into a loop over its work-items
// and vectorizes that loop only where the body has no inner loop and keeps
// no 64-bit value per work-item across a barrier (a local-memory reduction
// keeps pointers and size_t counters), so the samples are stored and
// sum_values reduces them. Work-item (k, j) of a launch n wide takes samples
// first + k and first + k + n of integral j, stored where
// MFV_SAMPLE_VALUES_2 stores them; each is the one `integrate` takes at
// that index, to the bit (albedo_value_microfacet's two stages, and
// mfv_philox_split: mfv_philox's bits).
// The two samples are interleaved by stage: both draws, both light
// directions, then both values. A sample is one chain of dependent
// operations (~300 cycles by llvm-mca: Philox's rounds, then a dozen
// divisions and square roots in series) whose vector loop body is longer
// than the core's out-of-order window, so a second sample written after the
// first overlapped it little; by stage, the window holds both chains
// (docs/performance.md, issue 31: +12 % on AVX2). Each of the second sample's
// stages sits in a block of its own (`n != 0` always holds), as in
// MFV_SAMPLE_VALUES_2, so that SLP does not pair the two samples' operations
// into 2-lane vectors; and `lobe` is an integer compare of r.x
// (u01_open_below_fifth), so that SLP does not pair it with u_pick's.
__kernel __attribute__((flatten)) void albedo_values(__global const IntegralSpec* restrict specs, ulong seed,
                                                     ulong first, __global float* restrict values) {
  size_t k0 = get_global_id(0), j = get_global_id(1), n = get_global_size(0);
  __global const IntegralSpec* s = specs + j;
  // the parameters loaded once, before the blocks (a load inside one is a gather)
  int d = s->d, g = s->g, f = s->f;
  real pd = s->pd, pg = s->pg, f0 = s->f0, f1 = s->f1, kd = s->kd, w = s->width, co = s->cos_o;
  real ox = sqrt(sin2_from_cos(co)), oz = co;  // spec_view at phi_o = 0, as albedo_value_microfacet
  uint4 ra = mfv_philox_split(seed, s->stream, spec_draw(s, 0u), first + k0);
  // the second draw's words as scalars: a uint4 out of the block would be a
  // vector-typed phi, which the work-item vectorizer refuses
  uint rbx = 0u, rby = 0u, rbz = 0u, rbw = 0u;
  if (n != 0) {
    uint4 rb = mfv_philox_split(seed, s->stream, spec_draw(s, 0u), first + k0 + n);
    rbx = rb.x;
    rby = rb.y;
    rbz = rb.z;
    rbw = rb.w;
  }
  real ixa, iya, iza, ixb = R(0.0), iyb = R(0.0), izb = R(0.0);
  albedo_light_microfacet(u01_open_below_fifth(ra.x), w, ox, oz, u01_open(ra.y), u01_open(ra.z), u01_open(ra.w),
                          &ixa, &iya, &iza);
  if (n != 0)
    albedo_light_microfacet(u01_open_below_fifth(rbx), w, ox, oz, u01_open(rby), u01_open(rbz), u01_open(rbw), &ixb,
                            &iyb, &izb);
  float va = (float)albedo_weight_microfacet(d, g, f, pd, pg, f0, f1, kd, w, ox, oz, ixa, iya, iza), vb = 0.0f;
  if (n != 0) vb = (float)albedo_weight_microfacet(d, g, f, pd, pg, f0, f1, kd, w, ox, oz, ixb, iyb, izb);
  values[j * 2 * n + k0] = va;
  values[j * 2 * n + k0 + n] = vb;
}
#endif
