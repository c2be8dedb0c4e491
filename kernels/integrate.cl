// Batched Monte Carlo integrals for the conformance checks (docs/design.md §3-4).
// Each work-group owns one slice of one integral and reduces sum and sum of
// squares in local memory, in double where the device has it; the host adds
// the slices. Needs the generated eval_D/eval_G/eval_F and brdf.cl.
// Reference twin of the estimators: host/reference/estimators.cpp.
//
// Proposals use a model's width only, never its formula: the microfacet
// normal m comes from a defensive mixture of a cosine lobe (weight MIX_COS)
// and 2D Cauchy slopes of width w (Student-t with one degree of freedom,
// heavier-tailed than GGX and Beckmann, so D(m)(m·n)/pdf stays bounded).

#ifdef MFV_ACC_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double acc_t;
#else
typedef float acc_t;
#endif

#define CHECK_D_NORM 0
#define CHECK_MASKING 1
#define CHECK_ALBEDO 2
// mfv energy (host/checks/energy.cpp): the albedo with a visible-normal
// proposal (see energy_weight) on randomized quasi-Monte Carlo points; each
// integral is one randomization (its stream picks the random shift), so the
// spread over several integrals gives the standard error.
#define CHECK_ALBEDO_RQMC 3  // E(o) at cos_o, as CHECK_ALBEDO
#define CHECK_EAVG_RQMC 4    // E_avg = ∫ E(μ) 2μ dμ: μ with density 2μ, stratified
#define CHECK_ALBEDO_RQMC_B 5  // sample_values only: the B of CHECK_ALBEDO_RQMC, for the reference
#define CHECK_ALBEDO_MIS 6     // mfv run's albedo: three proposals by multi-sample MIS on RQMC replicates (albedo_mis)

#define MIX_COS R(0.25)   // share of the cosine lobe in the microfacet proposal (a power of 2: see d_norm)
#define MIX_I_COS R(0.2)  // share of cosine-weighted light directions (albedo)

// 20 four-byte fields; host twin: IntegralSpec in host/checks/integrate.hpp.
typedef struct {
  int check, d, g, f;
  float pd, pg, f0, f1;
  float kd, width, cos_o, p5;
  uint stream, strata, model, channel;  // strata: samples of a stratified integral, 0 = iid
                                        // channel: the RGB channel of a user BRDF (mfv check)
  float pd2, phi_o;                     // anisotropic D: second width (alpha_y); view azimuth
                                        // pd2 > 0: an anisotropic integral (see spec_aniso)
  uint estimator, spare;                // mfv convergence: which estimator (0 = the check's own)
} IntegralSpec;

#ifdef MFV_USER_BRDF
// mfv check --brdf: the user's functions, through adapters defined in
// kernels/user_brdf.cl, which is built after the user's file (host/user/).
static inline real user_brdf_adapter(__global const IntegralSpec* s, real3 i, real3 o);
static inline real user_D_adapter(__global const IntegralSpec* s, real3 m);
static inline real user_G1_adapter(__global const IntegralSpec* s, real3 v, real3 m);
#endif

// Anisotropic integrals (pd2 > 0; 0 is every isotropic spec, untouched):
// D and an anisotropic G take the widths (pd, pd2) and (pg, pd2) along t = +x
// and b = +y (IntegralSpec carries one second width, shared by D and G), the
// view lies at azimuth phi_o, and the proposals are stretched to (width, pd2).
static inline bool spec_aniso(__global const IntegralSpec* s) { return s->pd2 > 0.0f; }

// The BRDF integral `s` checks: model 0 is the microfacet D×G×F BRDF of
// brdf.cl (with kd/π); whole models and user code plug in here, reading their
// parameters p[0..6] from pd, pg, f0, f1, kd, p5, pd2 (pd2 > 0 also stretches
// the proposals to (width, pd2), as for an anisotropic D).
#define MFV_MODEL_CATALOG_END 1000u  // models 1..999: the catalog's whole models (kernels/models.cl)
static inline real spec_brdf(__global const IntegralSpec* s, real3 i, real3 o) {
#ifdef MFV_USER_BRDF
  return user_brdf_adapter(s, i, o);
#endif
  if (s->model > 0u && s->model < MFV_MODEL_CATALOG_END) {
    // Whole models need not be reciprocal, so the albedo is taken per light:
    // the estimator's fixed direction o is the light, the sampled i the
    // view, and the integral is E(l) = ∫ f(l, v) (n·v) dv, the energy a beam
    // from l reflects (twin: spec_brdf in host/reference/estimators.cpp).
    real p[7] = {s->pd, s->pg, s->f0, s->f1, s->kd, s->p5, s->pd2};  // p[6]: a second width (0: isotropic)
    return eval_model((int)s->model, o, i, p);
  }
  if (spec_aniso(s)) return brdf_eval_aniso(s->d, s->g, s->f, i, o, s->pd, s->pd2, s->pg, s->pd2, s->f0, s->f1, s->kd);
  return brdf_eval(s->d, s->g, s->f, i, o, s->pd, s->pg, s->f0, s->f1, s->kd);
}

// The D of d_norm and masking at microfacet normal m (cos θ = c, sin²θ = s2).
static inline real spec_D(__global const IntegralSpec* s, real3 m, real c, real s2) {
#ifdef MFV_USER_BRDF
  return user_D_adapter(s, m);
#endif
  if (spec_aniso(s)) return eval_D_aniso(s->d, c, s2, m.x, m.y, s->pd, s->pd2);
  return eval_D(s->d, c, s2, s->pd);
}

// The Smith G1(o, m) of masking: the G2 with the light at the normal.
static inline real spec_G1(__global const IntegralSpec* s, real3 o, real3 m, real co, real c, real om) {
#ifdef MFV_USER_BRDF
  return user_G1_adapter(s, o, m);
#endif
  // anisotropic: the Smith G1 of the view's own azimuth, G1(o) (Heitz 2014)
  if (spec_aniso(s)) return eval_G1_aniso(s->g, co, o.x, o.y, s->pg, s->pd2);
  return eval_G(s->g, R(1.0), co, c, om, s->pg);
}

// Cauchy slopes in solid angle: p_slope(s) / cos³θ with
// p_slope = 1/(2πw²) (1 + tan²θ/w²)^(-3/2), which simplifies to
// 1 / (2π w² (cos² + sin²/w²)^(3/2)): no singularity at the normal or horizon.
static inline real pdf_slope(real c, real s2, real w) {
  real w2 = w * w;
  real k = c * c + s2 / w2;
  return R(1.0) / (R(2.0) * MFV_PI * w2 * k * sqrt(k));
}

// Width w <= 0 (mfv check on code that declares no roughness): a defensive
// mixture of Cauchy slopes of widths 4^-k, k = 0..MIX_WIDTHS-1 (1 down to
// 1/256), in equal shares, so any width from ~1e-3 to a few has a component
// within a factor of 4 of it. Twin: kMixWidths in estimators.cpp.
#define MIX_WIDTHS 5
static inline real mix_width(int k) { return ldexp(R(1.0), -2 * k); }

static inline real pdf_cauchy(real c, real s2, real w) {
  if (w > R(0.0)) return pdf_slope(c, s2, w);
  real p = R(0.0);
  for (int k = 0; k < MIX_WIDTHS; ++k) p += pdf_slope(c, s2, mix_width(k));
  return p / (real)MIX_WIDTHS;
}

// The mixture's pdf from its Cauchy part pc
static inline real pdf_mix(real c, real pc) { return MIX_COS * c * MFV_INV_PI + (R(1.0) - MIX_COS) * pc; }

static inline real pdf_m(real c, real s2, real w) { return pdf_mix(c, pdf_cauchy(c, s2, w)); }

// m from the cosine lobe or from Cauchy slopes of one width w > 0, by
// components (m = (*mx, *my, *c)), with cos θ and sin²θ formed without
// cancellation (sin² from the sampled radius, not from 1 - cos²).
// Both candidates are formed and one selected (no branch whose two sides
// PoCL's SLP pass would pair into 2-lane vectors; see albedo_values).
static inline void sample_m_c(bool cosine, real u_phi, real u_r, real w, real* mx, real* my, real* c, real* s2) {
  // Cauchy slopes: inverse CDF of |slope| gives tanθ
  real t = w * sqrt(u_r * (R(2.0) - u_r)) / (R(1.0) - u_r);
  real t2 = t * t;
  real ct = R(1.0) / sqrt(R(1.0) + t2);
  real s2t = t2 / (R(1.0) + t2), stt = t * ct;
  // cosine lobe (Malley): disk radius² = sin²θ
  real cc = sqrt(R(1.0) - u_r), stc = sqrt(u_r);
  *c = cosine ? cc : ct;
  *s2 = cosine ? u_r : s2t;
  real st = cosine ? stc : stt;
  real2 sc = sincos_2pi(u_phi);
  *mx = st * sc.y;
  *my = st * sc.x;
}

// Draws m from the mixture (sample_m_c; u_pick picks the component).
static inline real3 sample_m(real u_pick, real u_phi, real u_r, real w, real* c, real* s2) {
  // mixture of widths: u_pick, rescaled to [0, 1), picks the component
  if (u_pick >= MIX_COS && w <= R(0.0))
    w = mix_width(min((int)((u_pick - MIX_COS) / (R(1.0) - MIX_COS) * MIX_WIDTHS), MIX_WIDTHS - 1));
  real mx, my;
  sample_m_c(u_pick < MIX_COS, u_phi, u_r, w, &mx, &my, c, s2);
  return (real3)(mx, my, *c);
}

// Anisotropic proposal (spec_aniso): the Cauchy slopes stretched by (wx, wy)
// along (t, b), slope density 1/(2π wx wy) (1 + sx²/wx² + sy²/wy²)^(-3/2), in
// solid angle 1 / (2π wx wy (c² + (m.x/wx)² + (m.y/wy)²)^(3/2)) for unit m.
// In the stretched slopes an anisotropic GGX or Beckmann of widths (wx, wy)
// is radially symmetric, as the isotropic terms are in the plain ones; the
// D's formula is never sampled.
static inline real pdf_slope_aniso(real3 m, real wx, real wy) {
  real tx = m.x / wx, ty = m.y / wy;
  real k = m.z * m.z + tx * tx + ty * ty;
  return R(1.0) / (R(2.0) * MFV_PI * wx * wy * k * sqrt(k));
}

static inline real pdf_m_aniso(real3 m, real wx, real wy) {
  return MIX_COS * m.z * MFV_INV_PI + (R(1.0) - MIX_COS) * pdf_slope_aniso(m, wx, wy);
}

static inline real3 sample_m_aniso(real u_pick, real u_phi, real u_r, real wx, real wy, real* c, real* s2) {
  if (u_pick < MIX_COS) return sample_m(u_pick, u_phi, u_r, wx, c, s2);  // the cosine lobe, as isotropic
  real phi = R(2.0) * MFV_PI * u_phi;
  real t = sqrt(u_r * (R(2.0) - u_r)) / (R(1.0) - u_r);  // |slope| of unit width, as sample_m
  real sx = wx * t * cos(phi), sy = wy * t * sin(phi);
  real t2 = sx * sx + sy * sy;
  *c = R(1.0) / sqrt(R(1.0) + t2);
  *s2 = t2 / (R(1.0) + t2);
  return (real3)(sx * *c, sy * *c, *c);
}

// Stratum k of n equal cells of the unit square (anisotropic d_norm, whose
// integrand depends on the azimuth too): n_phi columns, n_phi the largest
// power of 2 with n_phi² <= n that divides n; neighbouring k share a row.
static inline void stratum_2d(ulong k, ulong n, real* u_r, real* u_phi) {
  ulong n_phi = 1;
  while (4u * n_phi * n_phi <= n && n % (2u * n_phi) == 0) n_phi *= 2u;
  *u_r = min(((real)(k / n_phi) + *u_r) / (real)(n / n_phi), R(0x1.fffffep-1));
  *u_phi = ((real)(k % n_phi) + *u_phi) / (real)n_phi;
}

// The view of masking and albedo: cos θ = cos_o at azimuth phi_o (in the
// xz-plane, phi_o = 0, for every isotropic spec).
static inline real3 spec_view(__global const IntegralSpec* s) {
  real co = s->cos_o, so = sqrt(sin2_from_cos(co));
  if (s->phi_o == 0.0f) return (real3)(so, R(0.0), co);
  return (real3)(so * cos((real)s->phi_o), so * sin((real)s->phi_o), co);
}

// The albedo proposal's pdf of light direction i (n·i = iz, o·h = oh) where
// the mixture's pdf of its half vector is pm: the union of a cosine lobe and
// o reflected about an m from the mixture (reflection Jacobian 1 / (4 o·h)).
static inline real albedo_pdf(real iz, real oh, real pm) {
  return MIX_I_COS * iz * MFV_INV_PI + (R(1.0) - MIX_I_COS) * pm / (R(4.0) * oh);
}

// Light direction i of the cosine lobe from its two uniforms, by components.
static inline void cosine_direction(real u_phi, real u_r, real* ix, real* iy, real* iz) {
  real st = sqrt(u_r);
  real2 sc = sincos_2pi(u_phi);
  *ix = st * sc.y;
  *iy = st * sc.x;
  *iz = sqrt(R(1.0) - u_r);
}

// f(i,o) (n·i) / pdf(i) for the albedo proposal (albedo_pdf).
static inline real albedo_weight(__global const IntegralSpec* s, real3 i, real3 o, real w) {
  if (i.z <= R(0.0)) return R(0.0);
  real hx, hy, hz;
  real oh = R(0.5) * normalize_sum(i.x + o.x, i.y + o.y, i.z + o.z, &hx, &hy, &hz);  // o·h, as in brdf_eval
  real hs2 = hx * hx + hy * hy;
  real pm = spec_aniso(s) ? pdf_m_aniso((real3)(hx, hy, hz), w, s->pd2) : pdf_m(hz, hs2, w);
  return spec_brdf(s, i, o) * i.z / albedo_pdf(i.z, oh, pm);
}

// Kronecker (additive recurrence) sequence of Roberts 2018 in 2D: point k is
// frac(shift + k·g), g_j = 1/φ^j with φ the plastic number (x³ = x + 1), in
// 32-bit fixed point so that k·g mod 1 is exact. (The 3D generators' first
// two coordinates are a much worse 2D set: measured N^-1/2 instead of N^-1
// at grazing view.) Cranley-Patterson shift from Philox draw 2 of the
// integral's stream. Host twin: kRqmcG in estimators.cpp.
#define RQMC_G1 3242174889u
#define RQMC_G2 2447445414u

// mfv energy's proposal (CHECK_ALBEDO_RQMC / CHECK_EAVG_RQMC): o reflected
// about a visible normal of the GGX *shape* of width w. The proposal is its
// own code (not the catalog's D_ggx, whose value only appears in the
// numerator), so a wrong D under test still shows. It covers every light
// direction (every h with o·h > 0 has D_w(h) > 0) and takes the 1/cos_o
// growth of the integrand at grazing view; the weight D G / (D_w G1_w(o)) is
// bounded for every D of the catalog (Beckmann, Phong and ρ tails are no
// heavier than GGX's once masked). Measured against the conformance
// proposal's cosine + Cauchy mixture: the same error per point with one
// BRDF evaluation instead of three. Twin: albedo_rqmc in estimators.cpp.

// pdf over light directions of i = reflect(o, h) when h is a visible normal of
// D_w(h) = w² / (π (h_c² w² + h_s²)²) (Walter et al. 2007 eq. 33, with
// h_s² = |n×h|² so it has no cancellation): G1(o) (o·h) D_w(h) / cos_o
// (Heitz 2018 eq. 3) times the reflection Jacobian 1 / (4 o·h), with Smith
// G1(o) = 2 cos_o / (cos_o + sqrt(cos_o² + w² sin_o²)) (Heitz 2014 eq. 72):
// D_w(h) / (2 (cos_o + sqrt(cos_o² + w² sin_o²))), finite at cos_o = 0.
static inline real vis_pdf_i(real hc, real hs2, real co, real so2, real w) {
  real w2 = w * w;
  real k = hc * hc * w2 + hs2;
  return w2 / (MFV_PI * k * k) / (R(2.0) * (co + sqrt(co * co + w2 * so2)));
}

// A visible normal of D_w at o by spherical caps (Dupuy & Benyoub 2023,
// Listing 3, isotropic). Returns 0 where the sample degenerates (h = 0).
static inline void sample_vis_c(real vx, real vy, real vz, real u_phi, real u_r, real w, real* mx, real* my,
                                real* mz) {
  // component arithmetic and sincos_2pi, as albedo_value
  real ox = w * vx, oy = w * vy, oz = vz;  // o in the stretched (w = 1) configuration
  real inv = rsqrt(ox * ox + oy * oy + oz * oz);
  ox *= inv;
  oy *= inv;
  oz *= inv;
  real z = (R(1.0) - u_r) * (R(1.0) + oz) - oz;
  real st = sqrt(clamp(R(1.0) - z * z, R(0.0), R(1.0)));
  real2 sc = sincos_2pi(u_phi);
  real hx = w * (st * sc.y + ox), hy = w * (st * sc.x + oy), hz = z + oz;
  real len2 = hx * hx + hy * hy + hz * hz;
  real r = len2 > R(0.0) ? rsqrt(len2) : R(0.0);
  *mx = hx * r;
  *my = hy * r;
  *mz = hz * r;
}

static inline real3 sample_vis(real3 o, real u_phi, real u_r, real w) {
  real mx, my, mz;
  sample_vis_c(o.x, o.y, o.z, u_phi, u_r, w, &mx, &my, &mz);
  return (real3)(mx, my, mz);
}

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

static inline uint4 rqmc_shift(__global const IntegralSpec* s, ulong seed) { return mfv_philox(seed, s->stream, 2, 0); }

// One point of CHECK_ALBEDO_RQMC / CHECK_EAVG_RQMC: the albedo integrand and,
// on the same direction, that of the split sum's B (the same BRDF with F
// multiplied by (1 - o·h)^5: B is defined with F = none, kd = 0).
// `shift` is the integral's Cranley-Patterson shift, rqmc_shift(s, seed):
// one Philox draw per integral, taken by the caller outside its sample loop.
static inline real2 albedo_rqmc_value(__global const IntegralSpec* s, uint4 shift, ulong index) {
  uint k = (uint)index;
  real u_phi = u01_open(shift.x + k * RQMC_G1), u_r = u01_open(shift.y + k * RQMC_G2);
  real co = s->cos_o;
  if (s->check == CHECK_EAVG_RQMC) {
    // density 2μ: μ² stratified over the integral's `strata` points with one
    // random shift (a rank-1 lattice with the 2D sequence), N^-1 like the rest
    real u = u01_open(shift.z) + (real)k / (real)s->strata;
    co = sqrt(u - floor(u));
  }
  real so2 = sin2_from_cos(co);
  real3 o = (real3)(sqrt(so2), R(0.0), co);
  real3 m = sample_vis(o, u_phi, u_r, s->width);
  if (!(m.z > R(0.0))) return (real2)(R(0.0), R(0.0));
  real b;
  real e = energy_weight(s, m, o, so2, s->width, &b);
  return (real2)(e, e * b);
}

// One sample of the directional albedo E(o) = ∫ f(i,o) (n·i) di
// (CHECK_ALBEDO) from its four uniforms: i from a cosine lobe or by
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
static inline bool spec_is_microfacet(__global const IntegralSpec* s) {
#ifdef MFV_USER_BRDF
  return false;
#else
  return s->model == 0u && !spec_aniso(s) && s->phi_o == 0.0f && s->width > 0.0f;
#endif
}

static inline real albedo_value_microfacet(int d, int g, int f, real pd, real pg, real f0, real f1, real kd, real w,
                                           real co, real u_branch, real u_pick, real u_phi, real u_r) {
  real ox = sqrt(sin2_from_cos(co)), oz = co;  // spec_view at phi_o = 0
  // both candidates, one selected (as in sample_m_c)
  real cx, cy, cz;
  cosine_direction(u_phi, u_r, &cx, &cy, &cz);
  real mx, my, c, s2;
  sample_m_c(u_pick < MIX_COS, u_phi, u_r, w, &mx, &my, &c, &s2);
  real om2 = R(2.0) * (ox * mx + oz * c);  // o reflected about m
  bool lobe = u_branch < MIX_I_COS;
  real rx = om2 * mx - ox, ry = om2 * my, rz = om2 * c - oz;
  real ix = lobe ? cx : rx, iy = lobe ? cy : ry, iz = lobe ? cz : rz;
  if (iz <= R(0.0)) return R(0.0);
  real hx, hy, hz;
  // o·h; the arguments are brdf_eval_c's own (iy + 0: the view's y), so the
  // compiler forms the half vector once for both
  real oh = R(0.5) * normalize_sum(ix + ox, iy + R(0.0), iz + oz, &hx, &hy, &hz);
  real pm = pdf_mix(hz, pdf_slope(hz, hx * hx + hy * hy, w));
  return brdf_eval_c(d, g, f, ix, iy, iz, ox, R(0.0), oz, pd, pg, f0, f1, kd) * iz / albedo_pdf(iz, oh, pm);
}

// ---- mfv run's albedo (CHECK_ALBEDO_MIS; host: IntegralKind::AlbedoMis) --
// Three proposals of the light direction i, none of which calls a term under
// test (DESIGN.md §3): (a) o reflected about a visible normal of the GGX
// *shape* of width w (sample_vis_c, vis_pdf_i: Heitz 2018, written here, never
// D_*/G1_*), the low-variance one; (b) o reflected about Cauchy slopes of
// width w and (c) the cosine lobe, the defensive pair whose tails cover every
// catalog D (see the top of this file). Combined by the multi-sample model of
// MIS with the balance heuristic (Veach 1997 §9.2.2, eq. 9.13): with shares
// c = (1/2, 1/4, 1/4) of the points, every point contributes
// f(i,o) (n·i) / (Σ_t c_t p_t(i)), whichever proposal drew it, and the mean
// is unbiased. A wrong D or G under test only enters the numerator, so it
// cannot cancel (tests/test_suite.cpp plants three).
// Points: index = r n + k with n = strata points per replicate; replicate r
// has its own Cranley-Patterson shift (Philox draw 3, counter r); k < n/2
// takes proposal (a), k < 3n/4 (b), the rest (c), each on its own run
// j = 0, 1, ... of the 2D Kronecker sequence (RQMC_G1, RQMC_G2). Replicates
// are independent, so their spread gives an honest standard error (host:
// Integrator::run, Student t with R - 1 degrees of freedom).
// Reference twin: albedo_mis in host/reference/estimators.cpp.
#define MIS_C_VIS R(0.5)
#define MIS_C_SLOPE R(0.25)
#define MIS_C_COS R(0.25)
#define MIS_DRAW 3u  // the Philox draw of the replicates' shifts

static inline uint4 mis_shift(uint stream, ulong seed, uint replicate) { return mfv_philox(seed, stream, MIS_DRAW, replicate); }

// Point k of n of a replicate with shift `shift`, by components and with
// selects (no branch, no float3: albedo_mis_values vectorizes, see
// albedo_values); the three candidates share one (u_phi, u_r).
static inline real albedo_mis_microfacet(int d, int g, int f, real pd, real pg, real f0, real f1, real kd, real w,
                                         real co, uint4 shift, uint k, uint n) {
  uint n_vis = n / 2u, n_slope = n / 4u;
  bool vis = k < n_vis, cosine = k >= n_vis + n_slope;
  uint j = vis ? k : cosine ? k - n_vis - n_slope : k - n_vis;
  real u_phi = u01_open(shift.x + j * RQMC_G1), u_r = u01_open(shift.y + j * RQMC_G2);
  real so2 = sin2_from_cos(co), ox = sqrt(so2), oz = co;  // the view in the xz-plane
  real vx, vy, vz, sx, sy, sz, s2;
  sample_vis_c(ox, R(0.0), oz, u_phi, u_r, w, &vx, &vy, &vz);
  sample_m_c(false, u_phi, u_r, w, &sx, &sy, &sz, &s2);
  real mx = vis ? vx : sx, my = vis ? vy : sy, mz = vis ? vz : sz;
  real om2 = R(2.0) * (ox * mx + oz * mz);  // o reflected about m (m = 0, a degenerate visible normal: i = -o)
  real cx, cy, cz;
  cosine_direction(u_phi, u_r, &cx, &cy, &cz);
  real ix = cosine ? cx : om2 * mx - ox, iy = cosine ? cy : om2 * my, iz = cosine ? cz : om2 * mz - oz;
  if (iz <= R(0.0)) return R(0.0);
  real hx, hy, hz;
  real oh = R(0.5) * normalize_sum(ix + ox, iy + R(0.0), iz + oz, &hx, &hy, &hz);  // as brdf_eval_c forms it
  real hs2 = hx * hx + hy * hy;
  // the pdfs of i under each proposal: (a) vis_pdf_i; (b) the slope density
  // of h with the reflection Jacobian 1 / (4 o·h); (c) cos/π
  real q = MIS_C_VIS * vis_pdf_i(hz, hs2, oz, so2, w) + MIS_C_SLOPE * pdf_slope(hz, hs2, w) / (R(4.0) * oh) +
           MIS_C_COS * iz * MFV_INV_PI;
  return brdf_eval_c(d, g, f, ix, iy, iz, ox, R(0.0), oz, pd, pg, f0, f1, kd) * iz / q;
}

static inline real albedo_mis_value(__global const IntegralSpec* s, ulong seed, ulong index) {
#ifdef MFV_USER_BRDF
  return NAN;  // the host sends no AlbedoMis integral to user code (mfv check)
#else
  uint n = s->strata;
  return albedo_mis_microfacet(s->d, s->g, s->f, s->pd, s->pg, s->f0, s->f1, s->kd, s->width, s->cos_o,
                               mis_shift(s->stream, seed, (uint)(index / n)), (uint)(index % n), n);
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
    real3 m = spec_aniso(s) ? sample_m_aniso(u_pick, u_phi, u_r, w, s->pd2, &c, &s2)
                            : sample_m(u_pick, u_phi, u_r, w, &c, &s2);
    real om2 = R(2.0) * (o.x * m.x + o.y * m.y + o.z * m.z);
    i = (real3)(om2 * m.x - o.x, om2 * m.y - o.y, om2 * m.z - o.z);
  }
  return albedo_weight(s, i, o, w);
}

// ---- mfv convergence (host/checks/convergence.cpp): estimators chosen by
// IntegralSpec::estimator for d_norm and albedo; 0 is the check's own
// estimator (the conformance MIS proposal above, unchanged). Reference
// twins: convergence_value in host/reference/estimators.cpp, same uniforms.
#define EST_UNIFORM 1u         // uniform hemisphere, pdf 1/(2π)
#define EST_COSINE 2u          // cosine-weighted hemisphere (Malley), pdf cos/π
#define EST_DSAMPLE_GGX 3u     // albedo only: h ~ D_w(h)(h·n) of the GGX shape
#define EST_DSAMPLE_BECKMANN 4u  // albedo only: the same with the Beckmann shape
#define EST_VNDF 5u            // albedo only: visible normals of the GGX shape (Heitz 2018)
#define EST_RQMC 6u            // 2D Kronecker points with a Philox Cranley-Patterson shift

// The D of the proposal's own shape (not the catalog's term: a wrong D under
// test must still show). GGX: Walter et al. 2007 eq. 33 as α²/(π(c²α² + s²)²);
// Beckmann: eq. 28, exp(-tan²/α²)/(π α² cos⁴).
static inline real conv_shape_D(uint est, real c, real s2, real w) {
  real w2 = w * w;
  if (est == EST_DSAMPLE_BECKMANN) {
    real c2 = c * c;
    real e = exp(-s2 / (c2 * w2));
    return e == R(0.0) ? R(0.0) : e / (MFV_PI * w2 * c2 * c2);
  }
  real k = c * c + s2 / w2;
  return R(1.0) / (MFV_PI * w2 * k * k);
}

// h with density D_w(h)(h·n): tan²θ = w² u / (1 - u) (GGX, Walter et al. 2007
// eq. 35) or -w² log(1 - u) (Beckmann, eq. 28); cos and sin² from tan², so
// nothing cancels near the normal.
// The unit direction at cos θ = c, sin²θ = s2 and azimuth 2π u_phi.
static inline real3 conv_direction(real c, real s2, real u_phi) {
  real st = sqrt(s2), phi = R(2.0) * MFV_PI * u_phi;
  return (real3)(st * cos(phi), st * sin(phi), c);
}

static inline real3 conv_sample_shape(uint est, real u_phi, real u_r, real w, real* c, real* s2) {
  real t2 = est == EST_DSAMPLE_BECKMANN ? -w * w * log1p(-u_r) : w * w * u_r / (R(1.0) - u_r);
  *c = rsqrt(R(1.0) + t2);
  *s2 = t2 / (R(1.0) + t2);
  return conv_direction(*c, *s2, u_phi);
}

// One sample of integral `s` under estimator s->estimator (!= 0).
static inline real convergence_value(__global const IntegralSpec* s, ulong seed, ulong index) {
  uint est = s->estimator;
  real w = s->width;
  real u_phi, u_r;
  if (est == EST_RQMC) {
    // albedo: mfv energy's visible-normal proposal on the same points
    if (s->check != CHECK_D_NORM) return albedo_rqmc_value(s, rqmc_shift(s, seed), index).x;
    uint4 shift = rqmc_shift(s, seed);
    uint k = (uint)index;
    u_phi = u01_open(shift.x + k * RQMC_G1);
    u_r = u01_open(shift.y + k * RQMC_G2);
  } else {
    uint4 r = mfv_philox(seed, s->stream, 0, index);
    u_phi = u01_open(r.z);
    u_r = u01_open(r.w);
  }
  if (s->check == CHECK_D_NORM) {
    real c, s2;
    if (est == EST_UNIFORM) {
      c = u_r;  // cos θ uniform on (0, 1) is uniform over the hemisphere
      s2 = sin2_from_cos(c);
      return spec_D(s, conv_direction(c, s2, u_phi), c, s2) * c * (R(2.0) * MFV_PI);
    }
    if (est == EST_COSINE) {
      s2 = u_r;
      c = sqrt(R(1.0) - u_r);
      return spec_D(s, conv_direction(c, s2, u_phi), c, s2) * MFV_PI;  // D c / (c/π)
    }
    if (est == EST_RQMC) {
      // the Cauchy slopes of the conformance mixture alone: D c / pdf is
      // bounded for GGX (2 / sqrt(1 + tan²/w²)) and Beckmann
      real3 m = sample_m(R(1.0), u_phi, u_r, w, &c, &s2);
      return spec_D(s, m, c, s2) * c / pdf_slope(c, s2, w);
    }
    // Sampling by D (or visible normals) is never used for D normalization:
    // with the proposal equal to the D under test every weight is D c /
    // (D c) = 1, so d_norm would be 1 by construction (docs/design.md §3). The
    // host refuses these; NaN makes a misuse visible.
    return NAN;
  }
  real co = s->cos_o;
  real so2 = sin2_from_cos(co);
  real3 o = (real3)(sqrt(so2), R(0.0), co);
  if (est == EST_UNIFORM || est == EST_COSINE) {
    real c = est == EST_UNIFORM ? u_r : sqrt(R(1.0) - u_r);
    real3 i = conv_direction(c, est == EST_UNIFORM ? sin2_from_cos(c) : u_r, u_phi);
    real inv_pdf = est == EST_UNIFORM ? R(2.0) * MFV_PI : MFV_PI / c;
    return spec_brdf(s, i, o) * c * inv_pdf;
  }
  if (est == EST_DSAMPLE_GGX || est == EST_DSAMPLE_BECKMANN) {
    // i = reflect(o, h): pdf_i = D_w(h)(h·n) / (4 o·h) (Walter et al. 2007 eq. 14, 38)
    real c, s2;
    real3 h = conv_sample_shape(est, u_phi, u_r, w, &c, &s2);
    real oh = dot(o, h);
    if (oh <= R(0.0)) return R(0.0);
    real3 i = R(2.0) * oh * h - o;
    if (i.z <= R(0.0)) return R(0.0);
    return spec_brdf(s, i, o) * i.z * (R(4.0) * oh) / (conv_shape_D(est, c, s2, w) * c);
  }
  if (est == EST_VNDF) {
    real3 m = sample_vis(o, u_phi, u_r, w);
    if (!(m.z > R(0.0))) return R(0.0);
    real b;
    return energy_weight(s, m, o, so2, w, &b);
  }
  return NAN;
}

// d_norm and masking samples of an isotropic microfacet integral
// (spec_is_microfacet), by components and with selects as
// albedo_value_microfacet, so that d_norm_values and masking_values
// vectorize; sample_value takes the same functions, so the general kernel and
// the fast path give the same samples to the bit.

// d_norm, stratified: sample `index` of `strata` (see sample_value).
static inline real d_norm_value_c(int d, real pd, real w, uint strata, uint index, real u_phi, real u_r) {
  uint n_cos = strata / 4u;
  bool cosine = index < n_cos;
  uint k = cosine ? index : index - n_cos, n = cosine ? n_cos : strata - n_cos;
  u_r = min(((real)k + u_r) / (real)n, R(0x1.fffffep-1));
  real mx, my, c, s2;
  sample_m_c(cosine, u_phi, u_r, w, &mx, &my, &c, &s2);
  return eval_D(d, c, s2, pd) * c / pdf_mix(c, pdf_slope(c, s2, w));  // pdf_m at w > 0, without its loop
}

static inline real masking_value_c(int d, int g, real pd, real pg, real w, real co, real u_pick, real u_phi,
                                   real u_r) {
  real ox = sqrt(sin2_from_cos(co));  // spec_view at phi_o = 0
  real mx, my, c, s2;
  sample_m_c(u_pick < MIX_COS, u_phi, u_r, w, &mx, &my, &c, &s2);
  real om = ox * mx + co * c;
  if (om <= R(0.0)) return R(0.0);
  return eval_G(g, R(1.0), co, c, om, pg) * eval_D(d, c, s2, pd) * om / (pdf_mix(c, pdf_slope(c, s2, w)) * co);
}

// One sample of the estimator of integral `s`.
static inline real sample_value(__global const IntegralSpec* s, ulong seed, ulong index) {
  if (s->estimator != 0u) return convergence_value(s, seed, index);
  if (s->check == CHECK_ALBEDO_MIS) return albedo_mis_value(s, seed, index);
  if (s->check >= CHECK_ALBEDO_RQMC) {
    real2 v = albedo_rqmc_value(s, rqmc_shift(s, seed), index);
    return s->check == CHECK_ALBEDO_RQMC_B ? v.y : v.x;
  }
  uint4 r = mfv_philox(seed, s->stream, 0, index);
  real u_branch = u01_open(r.x), u_pick = u01_open(r.y), u_phi = u01_open(r.z), u_r = u01_open(r.w);
  real w = s->width;
  if (s->check == CHECK_D_NORM) {
    // ∫ D(m) (m·n) dm = 1. The integrand depends on θ only (isotropic D), so
    // the radial uniform is stratified (multi-sample MIS, Veach 1997 §9.2):
    // the first strata/4 samples drive the cosine lobe, the rest the Cauchy
    // slopes, each over its own strata, so no stratum holds the jump between
    // the two and the balance-heuristic weights are exactly MIX_COS. The
    // error falls much faster than 1/sqrt(N); the host estimates it from
    // pairs of neighbouring strata.
    real c, s2;
    const bool aniso = spec_aniso(s);
    if (s->strata > 0u && spec_is_microfacet(s))
      return d_norm_value_c(s->d, s->pd, w, s->strata, (uint)index, u_phi, u_r);
    if (s->strata > 0u) {
      ulong n_cos = (ulong)s->strata / 4u;
      bool cosine = index < n_cos;
      ulong k = cosine ? index : index - n_cos;
      ulong n = cosine ? n_cos : (ulong)s->strata - n_cos;
      u_pick = cosine ? R(0.0) : R(1.0);
      // anisotropic: the integrand depends on the azimuth as well (in the
      // stretched slopes only through the cosine lobe's share)
      if (aniso) stratum_2d(k, n, &u_r, &u_phi);
      else u_r = min(((real)k + u_r) / (real)n, R(0x1.fffffep-1));
    }
    if (aniso) {
      real3 m = sample_m_aniso(u_pick, u_phi, u_r, w, s->pd2, &c, &s2);
      return spec_D(s, m, c, s2) * c / pdf_m_aniso(m, w, s->pd2);
    }
    real3 m = sample_m(u_pick, u_phi, u_r, w, &c, &s2);
    return spec_D(s, m, c, s2) * c / pdf_m(c, s2, w);
  }
  real co = s->cos_o;
  real3 o = spec_view(s);
  if (s->check == CHECK_MASKING) {
    // weak white furnace (Heitz 2014 eq. 19): ∫ G1(o,m) D(m) max(0, o·m) dm / (o·n) = 1,
    // with G1(o,m) = G2(light at the normal, o, m), the Smith G1 for Smith G2s
    if (spec_is_microfacet(s)) return masking_value_c(s->d, s->g, s->pd, s->pg, w, co, u_pick, u_phi, u_r);
    real c, s2;
    if (spec_aniso(s)) {
      real3 m = sample_m_aniso(u_pick, u_phi, u_r, w, s->pd2, &c, &s2);
      real om = dot(o, m);
      if (om <= R(0.0)) return R(0.0);
      return spec_G1(s, o, m, co, c, om) * spec_D(s, m, c, s2) * om / (pdf_m_aniso(m, w, s->pd2) * co);
    }
    real3 m = sample_m(u_pick, u_phi, u_r, w, &c, &s2);
    real om = dot(o, m);
    if (om <= R(0.0)) return R(0.0);
    return spec_G1(s, o, m, co, c, om) * spec_D(s, m, c, s2) * om / (pdf_m(c, s2, w) * co);
  }
  return albedo_value(s, u_branch, u_pick, u_phi, u_r);
}

// Work-group g integrates slice (g % slices) of integral (g / slices): each
// work-item takes per_item consecutive sample indices, counted from `first`
// (a later pass extends an iid or Kronecker point set; 0 for stratified ones).
__kernel MFV_NO_IMPLICIT_VECTORIZE void integrate(__global const IntegralSpec* specs, uint slices, uint per_item, ulong seed,
                        __global acc_t* sums, __local acc_t* scratch, ulong first) {
  size_t group = get_group_id(0), lid = get_local_id(0), lsize = get_local_size(0);
  __global const IntegralSpec* s = specs + group / slices;
  ulong base = first + ((ulong)(group % slices) * lsize + lid) * per_item;
  acc_t sum = 0, sumsq = 0;
  if (s->strata > 0u) {
    // stratified: sumsq collects squared differences of neighbouring strata
    // (per_item is even, so pairs never straddle work-items)
    for (uint k = 0; k < per_item; k += 2) {
      acc_t v0 = (acc_t)sample_value(s, seed, base + k), v1 = (acc_t)sample_value(s, seed, base + k + 1);
      sum += v0 + v1;
      sumsq += (v0 - v1) * (v0 - v1);
    }
  } else if (s->check == CHECK_ALBEDO_RQMC) {
    // RQMC errors come from the spread of replicates, not from a sum of
    // squares: the second accumulator takes the split sum's B on the same points
    uint4 shift = rqmc_shift(s, seed);
    for (uint k = 0; k < per_item; ++k) {
      real2 v = albedo_rqmc_value(s, shift, base + k);
      sum += (acc_t)v.x;
      sumsq += (acc_t)v.y;
    }
  } else {
    for (uint k = 0; k < per_item; ++k) {
      acc_t v = (acc_t)sample_value(s, seed, base + k);
      sum += v;
      sumsq += v * v;
    }
  }
  __local acc_t* ssum = scratch;
  __local acc_t* ssq = scratch + lsize;
  ssum[lid] = sum;
  ssq[lid] = sumsq;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (size_t step = lsize / 2; step > 0; step >>= 1) {
    if (lid < step) {
      ssum[lid] += ssum[lid + step];
      ssq[lid] += ssq[lid + step];
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0) {
    sums[2 * group] = ssum[0];
    sums[2 * group + 1] = ssq[0];
  }
}

#ifndef MFV_USER_BRDF
// The fast path of `integrate` for isotropic microfacet albedo integrals
// (spec_is_microfacet; host: Integrator::run). One sample per work-item
// and no barrier: PoCL turns a work-group into a loop over its work-items
// and vectorizes that loop only where the body has no inner loop and keeps
// no 64-bit value per work-item across a barrier (a local-memory reduction
// keeps pointers and size_t counters), so the samples are stored and
// sum_values reduces them. Work-item (k, j) takes sample first + k of
// integral j; the sample is the one `integrate` takes at that index, to the
// bit (the same albedo_value_microfacet).
__kernel void albedo_values(__global const IntegralSpec* restrict specs, ulong seed, ulong first,
                            __global float* restrict values) {
  size_t k = get_global_id(0), j = get_global_id(1);
  __global const IntegralSpec* s = specs + j;
  uint4 r = mfv_philox(seed, s->stream, 0, first + k);
  values[j * get_global_size(0) + k] =
      (float)albedo_value_microfacet(s->d, s->g, s->f, s->pd, s->pg, s->f0, s->f1, s->kd, s->width, s->cos_o,
                                     u01_open(r.x), u01_open(r.y), u01_open(r.z), u01_open(r.w));
}
#endif

#ifndef MFV_USER_BRDF
// mfv run's albedo (CHECK_ALBEDO_MIS) with one point per work-item, as
// albedo_values: row `row0 + get_global_id(1)` is replicate (row % replicates)
// of integral (row / replicates); work-item k takes point k of it. The
// replicate's shift depends on the row only, so it is computed once per
// work-group loop, not per point. sum_values then reduces each row.
__kernel void albedo_mis_values(__global const IntegralSpec* restrict specs, ulong seed, uint replicates, uint row0,
                                __global float* restrict values) {
  size_t k = get_global_id(0), row = row0 + get_global_id(1);
  __global const IntegralSpec* s = specs + row / replicates;
  uint4 shift = mis_shift(s->stream, seed, (uint)(row % replicates));
  values[get_global_id(1) * get_global_size(0) + k] =
      (float)albedo_mis_microfacet(s->d, s->g, s->f, s->pd, s->pg, s->f0, s->f1, s->kd, s->width, s->cos_o, shift,
                                   (uint)k, s->strata);
}
#endif

#ifndef MFV_USER_BRDF
// d_norm (stratified) and masking of isotropic microfacet integrals
// (spec_is_microfacet) with one sample per work-item, as albedo_values:
// work-item (k, j) takes sample first + k of integral j, the sample
// `integrate` takes there. sum_pairs / sum_values reduce.
__kernel void d_norm_values(__global const IntegralSpec* restrict specs, ulong seed, ulong first,
                            __global float* restrict values) {
  size_t k = get_global_id(0), j = get_global_id(1);
  __global const IntegralSpec* s = specs + j;
  uint4 r = mfv_philox(seed, s->stream, 0, first + k);
  values[j * get_global_size(0) + k] =
      (float)d_norm_value_c(s->d, s->pd, s->width, s->strata, (uint)(first + k), u01_open(r.z), u01_open(r.w));
}

__kernel void masking_values(__global const IntegralSpec* restrict specs, ulong seed, ulong first,
                             __global float* restrict values) {
  size_t k = get_global_id(0), j = get_global_id(1);
  __global const IntegralSpec* s = specs + j;
  uint4 r = mfv_philox(seed, s->stream, 0, first + k);
  values[j * get_global_size(0) + k] = (float)masking_value_c(s->d, s->g, s->pd, s->pg, s->width, s->cos_o,
                                                              u01_open(r.y), u01_open(r.z), u01_open(r.w));
}
#endif

// Sum and the sum of squared differences of neighbouring samples (pairs
// 2i, 2i + 1: neighbouring strata) of each run of `per_group` values (a
// multiple of 4), as `integrate` leaves a stratified integral's work-groups.
__kernel void sum_pairs(__global const float* restrict values, uint per_group, __global acc_t* restrict sums) {
  size_t g = get_global_id(0);
  __global const float* v = values + g * per_group;
  acc_t s[2] = {0, 0}, q[2] = {0, 0};
  for (uint k = 0; k < per_group; k += 4) {
#pragma unroll
    for (uint j = 0; j < 2; ++j) {
      acc_t a = (acc_t)v[k + 2 * j], b = (acc_t)v[k + 2 * j + 1];
      s[j] += a + b;
      q[j] += (a - b) * (a - b);
    }
  }
  sums[2 * g] = s[0] + s[1];
  sums[2 * g + 1] = q[0] + q[1];
}

// Sum and sum of squares of each run of `per_group` consecutive values (a
// multiple of 4) into sums[2g], sums[2g + 1], as `integrate` leaves its
// work-groups' sums; four partial sums each keep the adds from waiting on
// one another.
__kernel void sum_values(__global const float* restrict values, uint per_group, __global acc_t* restrict sums) {
  size_t g = get_global_id(0);
  __global const float* v = values + g * per_group;
  acc_t s[4] = {0, 0, 0, 0}, q[4] = {0, 0, 0, 0};
  for (uint k = 0; k < per_group; k += 4) {
#pragma unroll
    for (uint j = 0; j < 4; ++j) {
      acc_t a = (acc_t)v[k + j];
      s[j] += a;
      q[j] += a * a;
    }
  }
  sums[2 * g] = (s[0] + s[1]) + (s[2] + s[3]);
  sums[2 * g + 1] = (q[0] + q[1]) + (q[2] + q[3]);
}

// The per-sample values of n samples of each integral, for the reference's
// same-sample comparison: the first n, or for a stratified integral n spread
// over all its strata (so both mixture components are compared). In a
// MFV_DOUBLE program (the double twin, host/checks/reference_compare.cpp)
// the values are doubles.
__kernel MFV_NO_IMPLICIT_VECTORIZE void sample_values(__global const IntegralSpec* specs, uint n, ulong seed, __global real* out) {
  size_t i = get_global_id(0);
  __global const IntegralSpec* s = specs + i / n;
  ulong stride = s->strata >= n ? (ulong)(s->strata / n) : 1ul;
  out[i] = sample_value(s, seed, (ulong)(i % n) * stride);
}

// Reciprocity: |f(i,o) - f(o,i)| / max(|f(i,o)|, |f(o,i)|, 1e-4) over pairs
// drawn by kind (index % 4): uniform hemisphere, grazing, near-retro,
// near-mirror. Pair `index` (Philox draw 1; reference twin: reciprocity_pair
// in host/reference/estimators.cpp), by components: directions from sincos_2pi, the
// near-retro/mirror offsets normalised with rsqrt, both sides selected.
static inline void reciprocity_pair_c(__global const IntegralSpec* s, ulong seed, uint index, real* ax, real* ay,
                                      real* az, real* bx, real* by, real* bz) {
  uint4 r = mfv_philox(seed, s->stream, 1, index);
  uint kind = index % 4u;
  real scale = kind == 1u ? R(1e-3) : R(1.0);  // both grazing
  real ca = u01_open(r.x) * scale, cb = u01_open(r.z) * scale, u_w = u01_open(r.w);
  real sa = sqrt(sin2_from_cos(ca)), sb = sqrt(sin2_from_cos(cb));
  real2 pa = sincos_2pi(u01_open(r.y)), pb = sincos_2pi(u_w);
  *ax = sa * pa.y;
  *ay = sa * pa.x;
  *az = ca;
  // a small offset from the retro (b = a) or mirror (b = reflect a) direction
  real sign = kind == 3u ? R(-1.0) : R(1.0);
  real nx = sign * *ax + R(1e-3) * (cb - R(0.5)), ny = sign * *ay + R(1e-3) * (u_w - R(0.5)), nz = ca;
  real inv = rsqrt(nx * nx + ny * ny + nz * nz);
  bool near = kind >= 2u;
  *bx = near ? nx * inv : sb * pb.y;
  *by = near ? ny * inv : sb * pb.x;
  *bz = near ? nz * inv : cb;  // nz = ca > 0: above the horizon
}

// |f1 - f2| / max(|f1|, |f2|, 1e-4), 0 where both vanish: relative, except
// below f = 1e-4 /sr (a thousandth of a white Lambertian surface's 1/π),
// where float code loses its relative precision without consequence: F =
// (1 - v·h)^5 at F0 = 0 cancels when v·h -> 1, and intermediates go subnormal.
// (max and min in place of fabs: two fabs feeding a max become a 2-lane SLP
// vector that stops PoCL vectorizing, see normalize_sum)
// A NaN or Inf value is no evidence of symmetry (max() would drop a NaN):
// it is the worst asymmetry.
static inline float reciprocity_asym(real f1, real f2) {
  real m = max(max(f1, f2), -min(f1, f2));  // max(|f1|, |f2|)
  real d = max(f1 - f2, f2 - f1);           // |f1 - f2|
  float a = m > R(0.0) ? (float)(d / max(m, R(1e-4))) : 0.0f;
  return isfinite(f1) && isfinite(f2) ? a : INFINITY;
}

// One pair per work-item: work-item (k, j) writes the asymmetry of pair k of
// integral j (reciprocity_pair_c); the host takes the worst. The
// generic kernel evaluates spec_brdf (whole models, user code); the
// microfacet one (model 0, isotropic) brdf_eval_c, which PoCL vectorizes.
__kernel MFV_NO_IMPLICIT_VECTORIZE void reciprocity_values(__global const IntegralSpec* restrict specs, ulong seed,
                                 __global float* restrict asym) {
  size_t k = get_global_id(0), j = get_global_id(1);
  __global const IntegralSpec* s = specs + j;
  real ax, ay, az, bx, by, bz;
  reciprocity_pair_c(s, seed, (uint)k, &ax, &ay, &az, &bx, &by, &bz);
  real3 a = (real3)(ax, ay, az), b = (real3)(bx, by, bz);
  asym[j * get_global_size(0) + k] = reciprocity_asym(spec_brdf(s, a, b), spec_brdf(s, b, a));
}

#if !defined(MFV_USER_BRDF) && !defined(MFV_DOUBLE)
// The microfacet kernel in two passes, so that each work-item makes one
// brdf_eval_c call: with two (f(a, b) and f(b, a)) LLVM keeps the BRDF, or
// a term such as G_smith_ggx_correlated (inline cost 245 > 225), out of line,
// and that call stops PoCL vectorizing the work-item loop. Work-item
// (k, j) evaluates f of pair k / 2 of integral j, with its directions
// swapped for odd k; reciprocity_asym_pairs turns neighbouring values into
// the asymmetry reciprocity_values gives (the same float values to the bit).
__kernel void reciprocity_values_microfacet(__global const IntegralSpec* restrict specs, ulong seed,
                                            __global float* restrict f) {
  size_t k = get_global_id(0), j = get_global_id(1);
  __global const IntegralSpec* s = specs + j;
  real ax, ay, az, bx, by, bz;
  reciprocity_pair_c(s, seed, (uint)(k / 2u), &ax, &ay, &az, &bx, &by, &bz);
  bool swap = (k & 1u) != 0u;  // selects, not a branch (see sample_m_c)
  real lx = swap ? bx : ax, ly = swap ? by : ay, lz = swap ? bz : az;
  real vx = swap ? ax : bx, vy = swap ? ay : by, vz = swap ? az : bz;
  f[j * get_global_size(0) + k] = brdf_eval_c(s->d, s->g, s->f, lx, ly, lz, vx, vy, vz, s->pd, s->pg, s->f0, s->f1, s->kd);
}

// asym[i] from f(a, b) = f[2i] and f(b, a) = f[2i + 1].
__kernel void reciprocity_asym_pairs(__global const float* restrict f, __global float* restrict asym) {
  size_t i = get_global_id(0);
  asym[i] = reciprocity_asym(f[2 * i], f[2 * i + 1]);
}
#endif
