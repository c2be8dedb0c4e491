// The integrals' proposals and integrands (docs/design.md §3): what each
// IntegralSpec integrates (spec_brdf, spec_D, spec_G1, the view) and the
// proposals, which use a model's width only, never its formula: the
// microfacet normal m comes from a defensive mixture of a cosine lobe (weight
// MIX_COS) and 2D Cauchy slopes of width w (Student-t with one degree of
// freedom, heavier-tailed than GGX and Beckmann, so D(m)(m·n)/pdf stays
// bounded), and mfv energy's visible normals of the GGX *shape*.
// Reference twins: host/reference/estimators.cpp. Built before albedo.cl,
// convergence.cl, integrate.cl and reciprocity.cl (runtime/integrator.cpp).

#include "abi/integral.h"  // IntegralSpec, MFV_CHECK_*, MFV_EST_*, MFV_SLOT_* (shared with the host)

// MFV_SAMPLE_VALUES(name, VALUE): the shape of the one-sample-per-work-item
// kernels (aniso_values.cl, model_values.cl): work-item (k, j)
// stores VALUE, an expression of s (integral j), r (its Philox draw at sample
// first + k) and first + k; sum_values or sum_pairs reduce.
#define MFV_SAMPLE_VALUES(NAME, VALUE) MFV_SAMPLE_VALUES_DRAWN(NAME, mfv_philox, VALUE)
// ...with another generator of mfv_philox's bits (model_values.cl: mfv_philox_split)
#define MFV_SAMPLE_VALUES_DRAWN(NAME, GENERATOR, VALUE)                                                           \
  __kernel void NAME(__global const IntegralSpec* restrict specs, ulong seed, ulong first,                       \
                     __global float* restrict values) {                                                          \
    size_t k = get_global_id(0), j = get_global_id(1);                                                           \
    __global const IntegralSpec* s = specs + j;                                                                  \
    uint4 r = GENERATOR(seed, s->stream, spec_draw(s, 0u), first + k);                                           \
    values[j * get_global_size(0) + k] = (float)(VALUE);                                                         \
  }

// MFV_SAMPLE_VALUES_2(name, VALUE): MFV_SAMPLE_VALUES with two samples per
// work-item, k and k + n of a launch n wide (the host launches half of the
// row's samples; runtime/integrator.cpp sums_values), stored where the
// one-sample kernel stores them, so sum_values and sum_pairs see the same
// floats. One sample is one chain of dependent operations (Philox's ten
// rounds, then the integrand) longer than the core's out-of-order window;
// two independent chains in one body overlap (docs/performance.md, "Two
// samples per work-item"). k + n rather than k + 1, so LLVM's SLP pass
// finds no adjacent stores from which to pair the two into 2-lane vectors,
// which would keep PoCL from vectorizing across work-items; and the second
// sample in a block of its own (`n != 0` always holds), as SLP pairs only
// within a block: in one block it paired the two samples' compares and
// everything under them into 2-lane vectors (d_norm_values, "instruction
// return type cannot be vectorized"). flatten: LLVM inlines one Philox call
// but not two (cost 555 against 337), and a call left in the body keeps the
// work-item loop scalar.
#define MFV_SAMPLE_VALUES_2(NAME, VALUE)                                                                          \
  __kernel __attribute__((flatten)) void NAME(__global const IntegralSpec* restrict specs, ulong seed,            \
                                              ulong first, __global float* restrict values) {                    \
    size_t k0 = get_global_id(0), j = get_global_id(1), n = get_global_size(0);                                  \
    __global const IntegralSpec* s = specs + j;                                                                  \
    float v0, v1 = 0.0f;                                                                                         \
    {                                                                                                            \
      size_t k = k0;                                                                                             \
      uint4 r = mfv_philox(seed, s->stream, spec_draw(s, 0u), first + k);                                        \
      v0 = (float)(VALUE);                                                                                       \
    }                                                                                                            \
    if (n != 0) {                                                                                                \
      size_t k = k0 + n;                                                                                         \
      uint4 r = mfv_philox(seed, s->stream, spec_draw(s, 0u), first + k);                                        \
      v1 = (float)(VALUE);                                                                                       \
    }                                                                                                            \
    values[j * 2 * n + k0] = v0;                                                                                 \
    values[j * 2 * n + k0 + n] = v1;                                                                             \
  }

// Counter word 3 of integral s's Philox draw `draw` (< 256): the draw with
// the stream's high bits above it (rng.cl). Host twin: ref::draw_word.
static inline uint spec_draw(__global const IntegralSpec* s, uint draw) { return draw | (s->stream_hi << 8); }

#define MIX_COS R(0.25)   // share of the cosine lobe in the microfacet proposal (a power of 2: see d_norm)
#define MIX_I_COS R(0.2)  // share of cosine-weighted light directions (albedo)


#ifdef MFV_USER_BRDF
// mfv check --brdf: the user's functions, through adapters defined in
// kernels/user_brdf.cl, which is built after the user's file (host/user/).
static inline real user_brdf_adapter(__global const IntegralSpec* s, real3 i, real3 o);
static inline real user_D_adapter(__global const IntegralSpec* s, real3 m);
static inline real user_G1_adapter(__global const IntegralSpec* s, real3 v, real3 m);
#endif

// Anisotropic terms (model 0, pd2 > 0; 0 is every isotropic spec, untouched):
// D and an anisotropic G take the widths (pd, pd2) and (pg, pg2) along t = +x
// and b = +y, and the view lies at azimuth phi_o.
static inline bool spec_aniso(__global const IntegralSpec* s) { return s->pd2 > 0.0f; }
// A stretched proposal (width_y > 0: the Cauchy slopes of widths (width,
// width_y); the host sets it for anisotropic terms and stretched whole models).
static inline bool spec_stretched(__global const IntegralSpec* s) { return s->width_y > 0.0f; }

// The BRDF integral `s` checks: model 0 is the microfacet D×G×F BRDF of
// brdf.cl (with kd/π); whole models and user code plug in here, reading their
// parameters p[0..6] from IntegralSpec::p.
static inline real spec_brdf(__global const IntegralSpec* s, real3 i, real3 o) {
#ifdef MFV_USER_BRDF
  return user_brdf_adapter(s, i, o);
#endif
  if (s->model > 0u && s->model < MFV_MODEL_CATALOG_END) {
    // Whole models need not be reciprocal, so the albedo is taken per light:
    // the estimator's fixed direction o is the light, the sampled i the
    // view, and the integral is E(l) = ∫ f(l, v) (n·v) dv, the energy a beam
    // from l reflects (twin: spec_brdf in host/reference/estimators.cpp).
    real p[7] = {s->p[0], s->p[1], s->p[2], s->p[3], s->p[4], s->p[5], s->p[6]};  // p[6]: a second width (0: isotropic)
    return eval_model((int)s->model, o, i, p);
  }
  if (spec_aniso(s)) return brdf_eval_aniso(s->d, s->g, s->f, i, o, s->pd, s->pd2, s->pg, s->pg2, s->f0, s->f1, s->kd);
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
  if (spec_aniso(s)) return eval_G1_aniso(s->g, co, o.x, o.y, s->pg, s->pg2);
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
// By components (m = (mx, my, mz)), as the isotropic pdf_slope.
static inline real pdf_m_aniso_c(real mx, real my, real mz, real wx, real wy) {
  real tx = mx / wx, ty = my / wy;
  real k = mz * mz + tx * tx + ty * ty;
  return MIX_COS * mz * MFV_INV_PI + (R(1.0) - MIX_COS) * (R(1.0) / (R(2.0) * MFV_PI * wx * wy * k * sqrt(k)));
}

static inline real pdf_m_aniso(real3 m, real wx, real wy) { return pdf_m_aniso_c(m.x, m.y, m.z, wx, wy); }

// m from the cosine lobe (as sample_m_c) or from the stretched Cauchy slopes,
// by components: both candidates formed and one selected, the azimuth from
// sincos_2pi (no library call, no branch: kernels/aniso_values.cl vectorizes).
static inline void sample_m_aniso_c(bool cosine, real u_phi, real u_r, real wx, real wy, real* mx, real* my, real* c,
                                    real* s2) {
  real2 sc = sincos_2pi(u_phi);
  real t = sqrt(u_r * (R(2.0) - u_r)) / (R(1.0) - u_r);  // |slope| of unit width, as sample_m_c
  real sx = wx * t * sc.y, sy = wy * t * sc.x;
  real t2 = sx * sx + sy * sy;
  real ct = R(1.0) / sqrt(R(1.0) + t2);
  real stc = sqrt(u_r);  // the cosine lobe (Malley): disk radius² = sin²θ
  *c = cosine ? sqrt(R(1.0) - u_r) : ct;
  *s2 = cosine ? u_r : t2 / (R(1.0) + t2);
  *mx = cosine ? stc * sc.y : sx * ct;
  *my = cosine ? stc * sc.x : sy * ct;
}

static inline real3 sample_m_aniso(real u_pick, real u_phi, real u_r, real wx, real wy, real* c, real* s2) {
  real mx, my;
  sample_m_aniso_c(u_pick < MIX_COS, u_phi, u_r, wx, wy, &mx, &my, c, s2);
  return (real3)(mx, my, *c);
}

// Stratum k of n equal cells of the unit square (anisotropic d_norm, whose
// integrand depends on the azimuth too): n_phi columns, n_phi the largest
// power of 2 with n_phi² <= n that divides n; neighbouring k share a row.
// That is 2^min(floor(log2(n) / 2), trailing zeros of n), formed without a
// loop (a loop keeps PoCL from vectorizing the caller); n < 2^32 (strata).
static inline void stratum_2d(ulong k, ulong n, real* u_r, real* u_phi) {
  uint n32 = (uint)n, half_log2 = (31u - (uint)clz(max(n32, 1u))) / 2u, tz = (uint)popcount((n32 & (0u - n32)) - 1u);
  ulong n_phi = 1ul << min(half_log2, tz);
  *u_r = min(((real)(k / n_phi) + *u_r) / (real)(n / n_phi), R(0x1.fffffep-1));
  *u_phi = ((real)(k % n_phi) + *u_phi) / (real)n_phi;
}

// The view of masking and albedo: cos θ = cos_o at azimuth phi_o (in the
// xz-plane, phi_o = 0, for every isotropic spec), by components; the azimuth
// through sincos_2pi (exact at phi_o = 0: (so, 0, co)), its turns reduced to
// [0, 1) by a conversion (floor() is a call that keeps PoCL from vectorizing;
// |phi_o| < 2^31 turns).
static inline void spec_view_c(real co, real phi_o, real* ox, real* oy) {
  real so = sqrt(sin2_from_cos(co)), u = phi_o * (R(0.5) * MFV_INV_PI);
  u -= (real)(int)u;
  real2 sc = sincos_2pi(u < R(0.0) ? u + R(1.0) : u);
  *ox = so * sc.y;
  *oy = so * sc.x;
}

static inline real3 spec_view(__global const IntegralSpec* s) {
  real ox, oy;
  spec_view_c(s->cos_o, s->phi_o, &ox, &oy);
  return (real3)(ox, oy, s->cos_o);
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
  real pm = spec_stretched(s) ? pdf_m_aniso((real3)(hx, hy, hz), w, s->width_y) : pdf_m(hz, hs2, w);
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

// Owen-scrambled 2D Sobol points (Owen 1995; the hash form of Burley 2020,
// "Practical Hash-based Owen Scrambling", JCGT 9(4), Listings 1-2, with the
// hash of Vegdahl 2021, "Building a Better LK Hash", for Listing 1's): point
// k of a replicate whose two scrambles have seeds s0, s1. Sobol's first
// dimension is the bit-reversed index; its second, digit i (most significant
// first) the XOR of the index bits j whose bits contain i's (the Pascal
// matrix mod 2, by Lucas's theorem), formed in five steps, no loop. The
// scramble flips each digit by a hash of the digits before it, on the
// bit-reversed word (a multiply by an even constant carries bits upward
// only), so every point is uniform and any 2^m consecutive points from an
// aligned start remain a (0, m, 2)-net. Twin: owen_sobol_2d in
// host/reference/estimators.cpp (a loop over direction numbers instead).
// The bit reversal: bytes swapped (LLVM emits llvm.bswap, which Oclgrind
// runs), then the bits within each byte, the pairs by a delta swap
// (t = (x ^ x >> 1) & m; x ^= t ^ t << 1). Written as five mask-and-shift
// swaps, LLVM folded the whole chain into llvm.bitreverse.i32, which
// Oclgrind 21.10 does not implement (clCreateKernel failed with -46); the
// XOR step ends that idiom's match. Same bits as the swaps for all 2^32
// inputs (checked exhaustively); PoCL's cost in docs/performance.md.
static inline uint reverse_bits32(uint x) {
  x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
  x = (x >> 16) | (x << 16);
  uint t = ((x >> 1) ^ x) & 0x55555555u;
  x ^= t ^ (t << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  return ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
}

static inline uint owen_hash(uint x, uint seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

static inline void owen_sobol_2d(uint k, uint s0, uint s1, real* u0, real* u1) {
  uint y = k;  // Sobol's second dimension, digits in index-bit order
  y ^= (y >> 1) & 0x55555555u;
  y ^= (y >> 2) & 0x33333333u;
  y ^= (y >> 4) & 0x0F0F0F0Fu;
  y ^= (y >> 8) & 0x00FF00FFu;
  y ^= (y >> 16) & 0x0000FFFFu;
  *u0 = u01_open(reverse_bits32(owen_hash(k, s0)));
  *u1 = u01_open(reverse_bits32(owen_hash(y, s1)));
}

// mfv energy's proposal (MFV_CHECK_ALBEDO_RQMC / MFV_CHECK_EAVG_RQMC): o reflected
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

// The anisotropic GGX *shape* of widths (wx, wy) along (t, b), for mfv
// run's albedo outside the isotropic catalog grid (albedo_mis_general):
// D_w(h) = 1 / (π wx wy (h_z² + (h_x/wx)² + (h_y/wy)²)²) for unit h (Heitz
// 2014, "Understanding the masking-shadowing function", anisotropic GGX)
// and its Smith G1(o) = 2 o_z / (o_z + sqrt(o_z² + wx² o_x² + wy² o_y²))
// (eq. 72's Λ at the view's projected width, "anisotropic distributions"), so the
// pdf of i = reflect(o, h) for a visible h, G1(o) (o·h) D_w(h) / o_z times
// 1 / (4 o·h), is D_w(h) / (2 (o_z + sqrt(...))), as vis_pdf_i at wx = wy.
static inline real vis_pdf_i_aniso(real hx, real hy, real hz, real ox, real oy, real oz, real wx, real wy) {
  real tx = hx / wx, ty = hy / wy;
  real k = hz * hz + tx * tx + ty * ty;
  return R(1.0) / (MFV_PI * wx * wy * k * k) / (R(2.0) * (oz + sqrt(oz * oz + wx * wx * ox * ox + wy * wy * oy * oy)));
}

// A visible normal of that shape at o (Dupuy & Benyoub 2023, Listing 3:
// stretch o by (wx, wy), draw from the spherical cap, unstretch the normal).
// Takes v_r = 1 - u_r (sample_vis_aniso_c below gives it 1 - u_r; mfv run's
// albedo, albedo_mis_geometry_c, a v_r formed without that rounding).
static inline void sample_vis_aniso_v(real vx, real vy, real vz, real u_phi, real v_r, real wx, real wy, real* mx,
                                      real* my, real* mz) {
  real ox = wx * vx, oy = wy * vy, oz = vz;
  real inv = rsqrt(ox * ox + oy * oy + oz * oz);
  ox *= inv;
  oy *= inv;
  oz *= inv;
  real z = v_r * (R(1.0) + oz) - oz;
  real st = sqrt(clamp(R(1.0) - z * z, R(0.0), R(1.0)));
  real2 sc = sincos_2pi(u_phi);
  real hx = wx * (st * sc.y + ox), hy = wy * (st * sc.x + oy), hz = z + oz;
  real len2 = hx * hx + hy * hy + hz * hz;
  real r = len2 > R(0.0) ? rsqrt(len2) : R(0.0);
  *mx = hx * r;
  *my = hy * r;
  *mz = hz * r;
}

static inline void sample_vis_aniso_c(real vx, real vy, real vz, real u_phi, real u_r, real wx, real wy, real* mx,
                                      real* my, real* mz) {
  sample_vis_aniso_v(vx, vy, vz, u_phi, R(1.0) - u_r, wx, wy, mx, my, mz);
}

// A visible normal of D_w at o by spherical caps (Dupuy & Benyoub 2023,
// Listing 3, isotropic): the anisotropic sampler at wx = wy = w, which
// gives the same roundings (records_unchanged compares its samples).
// Returns 0 where the sample degenerates (h = 0).
static inline void sample_vis_c(real vx, real vy, real vz, real u_phi, real u_r, real w, real* mx, real* my,
                                real* mz) {
  sample_vis_aniso_c(vx, vy, vz, u_phi, u_r, w, w, mx, my, mz);
}

// The stretched Cauchy slopes alone (pdf_m_aniso_c without its cosine share).
static inline real pdf_slope_aniso(real mx, real my, real mz, real wx, real wy) {
  real tx = mx / wx, ty = my / wy;
  real k = mz * mz + tx * tx + ty * ty;
  return R(1.0) / (R(2.0) * MFV_PI * wx * wy * k * sqrt(k));
}

static inline real3 sample_vis(real3 o, real u_phi, real u_r, real w) {
  real mx, my, mz;
  sample_vis_c(o.x, o.y, o.z, u_phi, u_r, w, &mx, &my, &mz);
  return (real3)(mx, my, mz);
}

