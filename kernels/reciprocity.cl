// The reciprocity check's pairs and kernels (one pair per work-item; host:
// Integrator::reciprocity). Needs estimators.cl (spec_brdf).
#include "abi/integral.h"  // IntegralSpec, MFV_CHECK_*, MFV_EST_*, MFV_SLOT_* (shared with the host)

// Reciprocity: |f(i,o) - f(o,i)| / max(|f(i,o)|, |f(o,i)|, 1e-4) over pairs
// drawn by kind (index % 4): uniform hemisphere, grazing, near-retro,
// near-mirror. Pair `index` (Philox draw 1; reference twin: reciprocity_pair
// in host/reference/estimators.cpp), by components: directions from sincos_2pi, the
// near-retro/mirror offsets normalised with rsqrt, both sides selected.
// reciprocity_pair_of: the pair from its draw r; reciprocity_pair_c draws it
// with mfv_philox_split (mfv_philox's bits: in the vectorized kernels below
// SLP would pair mfv_philox's two 64-bit products into a 2-lane multiply).
// flatten and MFV_ALWAYS_INLINE, so it is inlined with its Philox call also
// where a kernel calls it several times (reciprocity_values_microfacet: four).
static inline MFV_ALWAYS_INLINE void reciprocity_pair_of(uint4 r, uint index, real* ax, real* ay, real* az, real* bx,
                                                         real* by, real* bz) {
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

static inline MFV_ALWAYS_INLINE __attribute__((flatten)) void reciprocity_pair_c(__global const IntegralSpec* s,
                                                                                 ulong seed, uint index, real* ax,
                                                                                 real* ay, real* az, real* bx,
                                                                                 real* by, real* bz) {
  reciprocity_pair_of(mfv_philox_split(seed, s->stream, spec_draw(s, 1u), index), index, ax, ay, az, bx, by, bz);
}

// |f1 - f2| / max(|f1|, |f2|, 1e-4), 0 where both vanish: relative, except
// below f = 1e-4 /sr (a thousandth of a white Lambertian surface's 1/π),
// where float code loses its relative precision without consequence: F =
// (1 - v·h)^5 at F0 = 0 cancels when v·h -> 1, and intermediates go subnormal.
// (max and min in place of fabs: two fabs feeding a max become a 2-lane SLP
// vector that stops PoCL vectorizing, see normalize_sum)
// A NaN or Inf value is no evidence of symmetry (max() would drop a NaN):
// it is the worst asymmetry. Finite is tested as x - x == 0 (exactly 0 for
// every finite x, NaN for ±Inf and NaN): isfinite() keeps PoCL from
// vectorizing its caller ("instruction return type cannot be
// vectorized"); the results are the same.
static inline float reciprocity_asym(real f1, real f2) {
  real m = max(max(f1, f2), -min(f1, f2));  // max(|f1|, |f2|)
  // |f1 - f2| (f1 - f2 = -(f2 - f1) exactly, so the same float as max(f1 -
  // f2, f2 - f1)); a max here would be paired by SLP with max(m, 1e-4) below
  // into a 2-lane vector, which kept this kernel scalar on haswell (AVX2)
  real d = fabs(f1 - f2);
  float a = m > R(0.0) ? (float)(d / max(m, R(1e-4))) : 0.0f;
  return f1 - f1 == R(0.0) && f2 - f2 == R(0.0) ? a : INFINITY;
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
// The microfacet asymmetry of pair `index` (model 0, isotropic): the pair
// drawn once, f(a, b) and f(b, a) with brdf_above_c, the same floats
// reciprocity_values gives. brdf_eval_c's horizon test once for both
// values, in select form: a branch would leave the parameters' loads
// conditional (haswell: scalar).
static inline MFV_ALWAYS_INLINE float reciprocity_microfacet_asym(__global const IntegralSpec* s, ulong seed,
                                                                  uint index) {
  real ax, ay, az, bx, by, bz;
  reciprocity_pair_c(s, seed, index, &ax, &ay, &az, &bx, &by, &bz);
  bool below = fmin(az, bz) <= R(0.0);
  real fab = brdf_above_c(s->d, s->g, s->f, ax, ay, az, bx, by, bz, s->pd, s->pg, s->f0, s->f1, s->kd);
  real fba = brdf_above_c(s->d, s->g, s->f, bx, by, bz, ax, ay, az, s->pd, s->pg, s->f0, s->f1, s->kd);
  fab = below ? R(0.0) : fab;
  fba = below ? R(0.0) : fba;
  return reciprocity_asym(fab, fba);
}

// The microfacet kernel, four pairs per work-item: work-item (k, j) of a
// launch n = get_global_size(0) wide writes pairs k, k + n, k + 2n and k + 3n
// of integral j (the host launches a quarter of the pairs,
// Integrator::worst_of, kMicrofacetPairsPerItem). One pair is one long chain
// of dependent operations (Philox's ten rounds, the directions, then 7
// square roots and 17 divisions, 8 lanes at a time on haswell), longer than
// the core's out-of-order window reaches; independent chains in one body let
// the core overlap them, and the work-item's own costs are shared by four
// (docs/performance.md, "Reciprocity: two pairs per work-item" and "four
// pairs"; two pairs gave 17.7-18.3 % of the peak row, four 19.4-19.5 %,
// eight 17.5-19.0 %). Pairs k + mn, not k + m, so LLVM's SLP pass finds no
// adjacent stores from which to pair them into 2-lane vectors. n is a
// multiple of 4 (reciprocity_pairs' counts are multiples of 64), so the four
// are of one kind (index % 4). flatten inlines the calls; the terms and the
// generated eval_D/eval_G/eval_F under them are always_inline, so no call is
// left and PoCL vectorizes the work-item loop.
__kernel __attribute__((flatten)) void reciprocity_values_microfacet(__global const IntegralSpec* restrict specs,
                                                                     ulong seed, __global float* restrict asym) {
  size_t k = get_global_id(0), j = get_global_id(1), n = get_global_size(0);
  __global const IntegralSpec* s = specs + j;
  asym[j * 4 * n + k] = reciprocity_microfacet_asym(s, seed, (uint)k);
  asym[j * 4 * n + k + n] = reciprocity_microfacet_asym(s, seed, (uint)(k + n));
  asym[j * 4 * n + k + 2 * n] = reciprocity_microfacet_asym(s, seed, (uint)(k + 2 * n));
  asym[j * 4 * n + k + 3 * n] = reciprocity_microfacet_asym(s, seed, (uint)(k + 3 * n));
}

// The whole-model kernel for the constant model id MODEL, one per model
// (runtime/specialize.cpp, PoCL only, as MFV_MODEL_ALBEDO_VALUES):
// reciprocity_values' operations in the same order (spec_brdf(s, a, b) is
// eval_model(model, b, a, p)), so the same floats; with MODEL a constant,
// eval_model's switch folds to the one model, flatten leaves no call, and
// PoCL vectorizes the work-item loop where the model's code allows it
// (docs/performance.md). The pair is drawn with mfv_philox_split (the same
// bits): with the models in select form (models.cl above_horizons) SLP
// paired mfv_philox's two 64-bit products into a <2 x i64> multiply,
// which PoCL's work-item vectorizer refuses. f(b, a) + 0, not f(b, a): the
// two evaluations are one function of swapped directions, and each operation
// of reciprocity_asym on them was an isomorphic pair from which LLVM's SLP
// pass paired both evaluations into 2-lane vectors (toon_diffuse's and
// cook_torrance_004's kernels scalar; docs/performance.md, "oren_nayar,
// toon_diffuse and cook_torrance_004"); an fadd against the models' select is
// no pair. The same floats: + 0 turns -0 into +0 only, and reciprocity_asym
// gives the same value for either zero. No generic instance: see
// model_values.cl (Intel).
#define MFV_MODEL_RECIPROCITY_VALUES(NAME, MODEL)                                                                \
  __kernel __attribute__((flatten)) void NAME(__global const IntegralSpec* restrict specs, ulong seed,           \
                                              __global float* restrict asym) {                                   \
    size_t k = get_global_id(0), j = get_global_id(1);                                                           \
    __global const IntegralSpec* s = specs + j;                                                                  \
    real ax, ay, az, bx, by, bz;                                                                                 \
    reciprocity_pair_c(s, seed, (uint)k, &ax, &ay, &az, &bx, &by, &bz);                                          \
    real3 a = (real3)(ax, ay, az), b = (real3)(bx, by, bz);                                                      \
    real p[7] = {s->p[0], s->p[1], s->p[2], s->p[3], s->p[4], s->p[5], s->p[6]};                                 \
    real f1 = eval_model(MODEL, b, a, p) + R(0.0), f2 = eval_model(MODEL, a, b, p);                              \
    asym[j * get_global_size(0) + k] = reciprocity_asym(f1, f2);                                                 \
  }
#endif
