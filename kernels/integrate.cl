// Batched Monte Carlo integrals for the conformance checks (docs/design.md §3-4).
// Each work-group owns one slice of one integral and reduces sum and sum of
// squares in local memory, in double where the device has it; the host adds
// the slices. Needs the generated eval_D/eval_G/eval_F, brdf.cl and the
// integration files before it (runtime/integrator.cpp integration_sources):
// estimators.cl (proposals and integrands), albedo.cl, convergence.cl,
// btdf.cl and transmission.cl.
// Reference twin of the estimators: host/reference/estimators.cpp.

#ifdef MFV_ACC_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double acc_t;
#else
typedef float acc_t;
#endif

#include "abi/integral.h"  // IntegralSpec, MFV_CHECK_*, MFV_EST_*, MFV_SLOT_* (shared with the host)

// d_norm and masking samples of an isotropic microfacet integral
// (spec_is_microfacet), by components and with selects as
// albedo_value_microfacet, so that d_norm_values and masking_values
// vectorize; sample_value takes the same functions, so the general kernel and
// the fast path give the same samples to the bit.

// d_norm, stratified: sample `index` of `strata` (see sample_value).
static inline MFV_ALWAYS_INLINE real d_norm_value_c(int d, real pd, real w, uint strata, uint index, real u_phi, real u_r) {
  uint n_cos = strata / 4u;
  bool cosine = index < n_cos;
  uint k = cosine ? index : index - n_cos, n = cosine ? n_cos : strata - n_cos;
  u_r = min(((real)k + u_r) / (real)n, R(0x1.fffffep-1));
  real mx, my, c, s2;
  sample_m_c(cosine, u_phi, u_r, w, &mx, &my, &c, &s2);
  return eval_D(d, c, s2, pd) * c / pdf_mix(c, pdf_slope(c, s2, w));  // pdf_m at w > 0, without its loop
}

// masking in two parts (masking_values below runs them as three kernels):
// the D- and G-free geometry of a sample (microfacet normal cos θ = c,
// sin²θ = s2, o·m = om, and the proposal density times cos_o, den) and its
// weight from G and D; v = ((G D) om) / den, the rounding of one piece.
static inline MFV_ALWAYS_INLINE void masking_geometry_c(real w, real co, real u_pick, real u_phi, real u_r, real* c,
                                                        real* s2, real* om, real* den) {
  real ox = sqrt(sin2_from_cos(co));  // spec_view at phi_o = 0
  real mx, my;
  sample_m_c(u_pick < MIX_COS, u_phi, u_r, w, &mx, &my, c, s2);
  *om = ox * mx + co * *c;
  *den = pdf_mix(*c, pdf_slope(*c, *s2, w)) * co;
}

static inline MFV_ALWAYS_INLINE real masking_weight_g(int g, real pg, real co, real c, real om, real den, real dv) {
  real v = eval_G(g, R(1.0), co, c, om, pg) * dv * om / den;
  return om <= R(0.0) ? R(0.0) : v;  // select form: see terms_d.cl
}

static inline MFV_ALWAYS_INLINE real masking_value_c(int d, int g, real pd, real pg, real w, real co, real u_pick, real u_phi,
                                   real u_r) {
  real c, s2, om, den;
  masking_geometry_c(w, co, u_pick, u_phi, u_r, &c, &s2, &om, &den);
  return masking_weight_g(g, pg, co, c, om, den, eval_D(d, c, s2, pd));
}

// One sample of d_norm, masking or the iid albedo (MFV_CHECK_D_NORM,
// MFV_CHECK_MASKING, MFV_CHECK_ALBEDO) from Philox draw 0.
static inline real iid_sample_value(__global const IntegralSpec* s, ulong seed, ulong index) {
  uint4 r = mfv_philox(seed, s->stream, spec_draw(s, 0u), index);
  real u_branch = u01_open(r.x), u_pick = u01_open(r.y), u_phi = u01_open(r.z), u_r = u01_open(r.w);
  if (spec_is_aniso_microfacet(s)) return aniso_sample_value(s, (uint)index, u_branch, u_pick, u_phi, u_r);
  real w = s->width;
  if (s->check == MFV_CHECK_D_NORM) {
    // ∫ D(m) (m·n) dm = 1. The integrand depends on θ only (isotropic D), so
    // the radial uniform is stratified (multi-sample MIS, Veach 1997 §9.2):
    // the first strata/4 samples drive the cosine lobe, the rest the Cauchy
    // slopes, each over its own strata, so no stratum holds the jump between
    // the two and the balance-heuristic weights are exactly MIX_COS. The
    // error falls much faster than 1/sqrt(N); the host estimates it from
    // pairs of neighbouring strata.
    real c, s2;
    const bool aniso = spec_stretched(s);
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
      real3 m = sample_m_aniso(u_pick, u_phi, u_r, w, s->width_y, &c, &s2);
      return spec_D(s, m, c, s2) * c / pdf_m_aniso(m, w, s->width_y);
    }
    real3 m = sample_m(u_pick, u_phi, u_r, w, &c, &s2);
    return spec_D(s, m, c, s2) * c / pdf_m(c, s2, w);
  }
  real co = s->cos_o;
  real3 o = spec_view(s);
  if (s->check == MFV_CHECK_MASKING) {
    // weak white furnace (Heitz 2014 eq. 19): ∫ G1(o,m) D(m) max(0, o·m) dm / (o·n) = 1,
    // with G1(o,m) = G2(light at the normal, o, m), the Smith G1 for Smith G2s
    if (spec_is_microfacet(s)) return masking_value_c(s->d, s->g, s->pd, s->pg, w, co, u_pick, u_phi, u_r);
    real c, s2;
    if (spec_stretched(s)) {
      real3 m = sample_m_aniso(u_pick, u_phi, u_r, w, s->width_y, &c, &s2);
      real om = dot(o, m);
      if (om <= R(0.0)) return R(0.0);
      return spec_G1(s, o, m, co, c, om) * spec_D(s, m, c, s2) * om / (pdf_m_aniso(m, w, s->width_y) * co);
    }
    real3 m = sample_m(u_pick, u_phi, u_r, w, &c, &s2);
    real om = dot(o, m);
    if (om <= R(0.0)) return R(0.0);
    return spec_G1(s, o, m, co, c, om) * spec_D(s, m, c, s2) * om / (pdf_m(c, s2, w) * co);
  }
  return albedo_value(s, u_branch, u_pick, u_phi, u_r);
}

// One sample of the estimator of integral `s`: a closed dispatch on the
// check id (host twin: ref::sample_value). A check id with no case here has
// no integrand, and its samples are NaN, so that it fails every test that
// reads them (tests/test_checks_complete.cpp plants one) rather than
// integrating another check's integrand.
static inline real sample_value(__global const IntegralSpec* s, ulong seed, ulong index) {
  if (s->estimator != 0u) return convergence_value(s, seed, index);
  switch (s->check) {
    case MFV_CHECK_D_NORM:
    case MFV_CHECK_MASKING:
    case MFV_CHECK_ALBEDO: return iid_sample_value(s, seed, index);
    case MFV_CHECK_ALBEDO_RQMC:
    case MFV_CHECK_EAVG_RQMC: return albedo_rqmc_value(s, rqmc_shift(s, seed), index).x;
    case MFV_CHECK_ALBEDO_RQMC_B: return albedo_rqmc_value(s, rqmc_shift(s, seed), index).y;
    case MFV_CHECK_ALBEDO_MIS: return albedo_mis_value(s, seed, index);
    case MFV_CHECK_BSDF_FLUX: return bsdf_flux_value(s, seed, index);
    case MFV_CHECK_MASKING_T: return masking_t_value(s, seed, index);
    case MFV_CHECK_BSDF_AVG: return bsdf_avg_value(s, seed, index);
    default: return NAN;  // no integrand for this check id
  }
}

// The work-group's two sums (sum, sumsq: each work-item's) into its slots
// of `sums`, through local memory: `integrate`'s and MFV_INTEGRATE_IID's.
#define MFV_INTEGRATE_REDUCE                                                                                      \
  __local acc_t* ssum = scratch;                                                                                 \
  __local acc_t* ssq = scratch + lsize;                                                                          \
  ssum[lid] = sum;                                                                                               \
  ssq[lid] = sumsq;                                                                                              \
  barrier(CLK_LOCAL_MEM_FENCE);                                                                                  \
  for (size_t step = lsize / 2; step > 0; step >>= 1) {                                                          \
    if (lid < step) {                                                                                            \
      ssum[lid] += ssum[lid + step];                                                                             \
      ssq[lid] += ssq[lid + step];                                                                               \
    }                                                                                                            \
    barrier(CLK_LOCAL_MEM_FENCE);                                                                                \
  }                                                                                                              \
  if (lid == 0) {                                                                                                \
    sums[MFV_SUM_SLOTS * group + MFV_SLOT_SUM] = ssum[0];                                                        \
    sums[MFV_SUM_SLOTS * group + MFV_SLOT_SECOND] = ssq[0];                                                      \
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
  } else if (s->check == MFV_CHECK_ALBEDO_RQMC) {
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
  MFV_INTEGRATE_REDUCE
}

// MFV_INTEGRATE_IID(name, FN): `integrate` for the iid integrals (strata 0,
// estimator 0) of one check, whose sample_value case is FN(s, seed, index):
// the same loop and reduction, so the same sums to the bit, without the other
// checks' code, which makes the generic kernel PoCL's costliest compile
// (docs/performance.md, "Cold start"). Defined where the host asks
// (runtime/specialize.cpp generate_check_kernels: the transmission checks).
#define MFV_INTEGRATE_IID(NAME, FN)                                                                               \
  __kernel MFV_NO_IMPLICIT_VECTORIZE void NAME(__global const IntegralSpec* specs, uint slices, uint per_item,     \
                                               ulong seed, __global acc_t* sums, __local acc_t* scratch,         \
                                               ulong first) {                                                    \
    size_t group = get_group_id(0), lid = get_local_id(0), lsize = get_local_size(0);                            \
    __global const IntegralSpec* s = specs + group / slices;                                                     \
    ulong base = first + ((ulong)(group % slices) * lsize + lid) * per_item;                                     \
    acc_t sum = 0, sumsq = 0;                                                                                    \
    for (uint k = 0; k < per_item; ++k) {                                                                        \
      acc_t v = (acc_t)FN(s, seed, base + k);                                                                    \
      sum += v;                                                                                                  \
      sumsq += v * v;                                                                                            \
    }                                                                                                            \
    MFV_INTEGRATE_REDUCE                                                                                         \
  }

// albedo_values, the fast path for isotropic microfacet albedo integrals: kernels/albedo.cl

#ifndef MFV_USER_BRDF
// mfv run's albedo (MFV_CHECK_ALBEDO_MIS) with one point per work-item, as
// albedo_values: row `row0 + get_global_id(1)` is replicate (row % replicates)
// of integral (row / replicates); work-item k takes point k of it. Three
// kernels, kernels/albedo.cl albedo_mis_microfacet's three parts, one after
// the other on the same rows: albedo_mis_geometry (no D, no G) stores each
// point's iz, hz, hs2, oh and q in five planes of `rows x points` reals
// (planes, not 5-tuples, as albedo_rqmc_values' E and B), and F in one more
// buffer, `df`; albedo_mis_df (MFV_ALBEDO_MIS_DF(name, D)) turns F into D F
// there, in place (a buffer of its own, so that its loads and stores cannot
// alias the planes it reads and PoCL vectorizes it); albedo_mis_values
// (MFV_ALBEDO_MIS_VALUES(name, G)) stores the point's value. The last two are
// specialized per D and per G (runtime/specialize.cpp), so a run compiles
// one kernel per D and one per G instead of one per pair (docs/performance.md,
// "Cold start"); a stored real is exact, so the floats are those of
// albedo_mis_microfacet in one piece. sum_values then reduces each row. The
// replicate's shift depends on the row only, so it is computed once per
// work-group loop, not per point.
#define MIS_AT (get_global_id(1) * get_global_size(0) + get_global_id(0))
#define MIS_PLANE(i) geometry[(i) * (get_global_size(0) * get_global_size(1)) + MIS_AT]
__kernel void albedo_mis_geometry(__global const IntegralSpec* restrict specs, ulong seed, uint replicates, uint row0,
                                  __global real* restrict geometry, __global real* restrict df) {
  size_t k = get_global_id(0), row = row0 + get_global_id(1);
  __global const IntegralSpec* s = specs + row / replicates;
  uint4 shift = mis_shift(s, seed, (uint)(row % replicates));
  real iz, hz, hs2, oh, q, fv;
  albedo_mis_geometry_c(s->f, s->f0, s->f1, s->width, s->cos_o, shift, (uint)k, s->points, &iz, &hz, &hs2, &oh, &q,
                        &fv);
  MIS_PLANE(0) = iz;
  MIS_PLANE(1) = hz;
  MIS_PLANE(2) = hs2;
  MIS_PLANE(3) = oh;
  MIS_PLANE(4) = q;
  df[MIS_AT] = fv;
}

#define MFV_ALBEDO_MIS_DF(NAME, D)                                                                                \
  __kernel void NAME(__global const IntegralSpec* restrict specs, uint replicates, uint row0,                     \
                     __global const real* restrict geometry, __global real* restrict df) {                       \
    __global const IntegralSpec* s = specs + (row0 + get_global_id(1)) / replicates;                             \
    df[MIS_AT] = albedo_mis_df_c(D, s->pd, MIS_PLANE(1), MIS_PLANE(2), df[MIS_AT]);                              \
  }
MFV_ALBEDO_MIS_DF(albedo_mis_df, s->d)

// MFV_ALBEDO_MIS_VALUES(name, G): as MFV_MASKING_VALUES, by G only.
#define MFV_ALBEDO_MIS_VALUES(NAME, G)                                                                            \
  __kernel void NAME(__global const IntegralSpec* restrict specs, uint replicates, uint row0,                     \
                     __global const real* restrict geometry, __global const real* restrict df,                   \
                     __global float* restrict values) {                                                          \
    size_t k = get_global_id(0);                                                                                 \
    __global const IntegralSpec* s = specs + (row0 + get_global_id(1)) / replicates;                             \
    values[get_global_id(1) * get_global_size(0) + k] = (float)albedo_mis_weight_g(                              \
        G, s->pg, s->kd, s->cos_o, (uint)k, s->points, MIS_PLANE(0), MIS_PLANE(1), MIS_PLANE(3), MIS_PLANE(4),   \
        df[MIS_AT]);                                                                                             \
  }
MFV_ALBEDO_MIS_VALUES(albedo_mis_values, s->g)

// MFV_ALBEDO_MIS_PAIR(name, D, G): the three kernels above in one,
// albedo_mis_microfacet in one piece with the pair's ids as constants, laid
// out as albedo_mis_values (no planes: one launch, no stores between the
// parts). Defined only for a program that specializes one (D, G) pair
// (runtime/specialize.cpp: `mfv bench --case`, a one-model run or energy
// table), where it replaces the three kernels' launches, fills and planes
// (docs/performance.md, "One kernel for one pair"); the floats are the three
// kernels', as theirs are the one-piece estimator's.
#define MFV_ALBEDO_MIS_PAIR(NAME, D, G)                                                                           \
  __kernel void NAME(__global const IntegralSpec* restrict specs, ulong seed, uint replicates, uint row0,         \
                     __global float* restrict values) {                                                          \
    size_t k = get_global_id(0), row = row0 + get_global_id(1);                                                  \
    __global const IntegralSpec* s = specs + row / replicates;                                                   \
    uint4 shift = mis_shift(s, seed, (uint)(row % replicates));                                                  \
    values[get_global_id(1) * get_global_size(0) + k] = (float)albedo_mis_microfacet(                            \
        D, G, s->f, s->pd, s->pg, s->f0, s->f1, s->kd, s->width, s->cos_o, shift, (uint)k, s->points);           \
  }
#endif

// MFV_MIS_ROWS(name, FN): a replicate kernel laid out as albedo_mis_values,
// in every program, not vectorized (its integrand branches), point k of the
// row's replicate from FN(s, shift, k, n).
#define MFV_MIS_ROWS(NAME, FN)                                                                                    \
  __kernel MFV_NO_IMPLICIT_VECTORIZE void NAME(__global const IntegralSpec* restrict specs, ulong seed,           \
                                               uint replicates, uint row0, __global float* restrict values) {     \
    size_t k = get_global_id(0), row = row0 + get_global_id(1);                                                  \
    __global const IntegralSpec* s = specs + row / replicates;                                                   \
    uint4 shift = mis_shift(s, seed, (uint)(row % replicates));                                                  \
    values[get_global_id(1) * get_global_size(0) + k] = (float)FN(s, shift, (uint)k, s->points);                 \
  }
// The other AlbedoMis integrals (albedo_mis_general: anisotropic terms, whole models, user code)
MFV_MIS_ROWS(albedo_mis_general_values, albedo_mis_general)
// bsdf_furnace's flux (MFV_CHECK_BSDF_FLUX, kernels/transmission.cl bsdf_flux_mis)
MFV_MIS_ROWS(bsdf_flux_mis_values, bsdf_flux_mis)

#ifndef MFV_USER_BRDF
// d_norm (stratified) of isotropic microfacet integrals
// (spec_is_microfacet) with two samples per work-item, as albedo_values:
// work-item (k, j) of a launch n wide takes samples first + k and first +
// k + n of integral j, the samples `integrate` takes there. sum_pairs
// reduces (neighbouring strata are stored side by side, as before).
// MFV_D_NORM_VALUES(name, D) defines d_norm_values with the term id D: s->d
// here, a constant in the kernels specialized per D (runtime/specialize.cpp),
// where the select chain of eval_D folds to the one term.
#define MFV_D_NORM_VALUES(NAME, D)                                                                                \
  MFV_SAMPLE_VALUES_2(NAME,                                                                                       \
                      d_norm_value_c(D, s->pd, s->width, s->strata, (uint)(first + k), u01_open(r.z), u01_open(r.w)))
MFV_D_NORM_VALUES(d_norm_values, s->d)

// masking in three kernels, as AlbedoMis (albedo_mis_geometry above), one
// after the other on the same samples: masking_geometry (no D, no G) stores
// masking_geometry_c's c, s2, om and den in four planes of `integrals x
// samples` reals; masking_d (MFV_MASKING_D(name, D)) stores D(c, s2) in a
// buffer of its own, `dv`; masking_values (MFV_MASKING_VALUES(name, G)) the
// sample's value masking_weight_g. The last two are specialized per D and
// per G (runtime/specialize.cpp), so a run compiles one kernel per D and one
// per G instead of one per pair; a stored real is exact, so the floats are
// masking_value_c's, `integrate`'s.
__kernel void masking_geometry(__global const IntegralSpec* restrict specs, ulong seed, ulong first,
                               __global real* restrict geometry) {
  size_t k = get_global_id(0), j = get_global_id(1);
  __global const IntegralSpec* s = specs + j;
  uint4 r = mfv_philox(seed, s->stream, spec_draw(s, 0u), first + k);
  real c, s2, om, den;
  masking_geometry_c(s->width, s->cos_o, u01_open(r.y), u01_open(r.z), u01_open(r.w), &c, &s2, &om, &den);
  MIS_PLANE(0) = c;
  MIS_PLANE(1) = s2;
  MIS_PLANE(2) = om;
  MIS_PLANE(3) = den;
}

#define MFV_MASKING_D(NAME, D)                                                                                    \
  __kernel void NAME(__global const IntegralSpec* restrict specs, __global const real* restrict geometry,         \
                     __global real* restrict dv) {                                                               \
    __global const IntegralSpec* s = specs + get_global_id(1);                                                   \
    dv[MIS_AT] = eval_D(D, MIS_PLANE(0), MIS_PLANE(1), s->pd);                                                   \
  }
MFV_MASKING_D(masking_d, s->d)

#define MFV_MASKING_VALUES(NAME, G)                                                                               \
  __kernel void NAME(__global const IntegralSpec* restrict specs, __global const real* restrict geometry,         \
                     __global const real* restrict dv, __global float* restrict values) {                        \
    __global const IntegralSpec* s = specs + get_global_id(1);                                                   \
    values[MIS_AT] = (float)masking_weight_g(G, s->pg, s->cos_o, MIS_PLANE(0), MIS_PLANE(2), MIS_PLANE(3),       \
                                             dv[MIS_AT]);                                                        \
  }
MFV_MASKING_VALUES(masking_values, s->g)
#endif

#ifndef MFV_USER_BRDF
// mfv energy's RQMC integrals of isotropic microfacet BRDFs
// (MFV_CHECK_ALBEDO_RQMC, and MFV_CHECK_EAVG_RQMC, stratified) with one point
// per work-item, as albedo_values: work-item (k, j) takes point first + k of
// integral j and stores E at j N + k and B one plane (N x integrals) later
// (two planes, not (E, B) pairs: SLP would pair those two stores into a
// 2-lane vector, which keeps PoCL from vectorizing across work-items);
// sum_rqmc reduces. The points and values are those `integrate` takes
// (albedo_rqmc_value).
#define MFV_ALBEDO_RQMC_VALUES(NAME, D, G)                                                                        \
  __kernel void NAME(__global const IntegralSpec* restrict specs, ulong seed, ulong first,                       \
                     __global float* restrict values) {                                                          \
    size_t k = get_global_id(0), j = get_global_id(1);                                                           \
    __global const IntegralSpec* s = specs + j;                                                                  \
    uint4 shift = rqmc_shift(s, seed);                                                                           \
    uint i = (uint)(first + k);                                                                                  \
    real ju, eavg = eavg_cos(shift, i, s->strata, &ju), cos_o = s->cos_o; /* loads unconditional (haswell) */    \
    const bool avg = s->check == MFV_CHECK_EAVG_RQMC;                                                            \
    real co = avg ? eavg : cos_o, jv = avg ? ju : R(1.0);                                                        \
    real b;                                                                                                      \
    real e = albedo_rqmc_microfacet(D, G, s->f, s->pd, s->pg, s->f0, s->f1, s->kd, s->width, co, shift, i, &b);  \
    size_t at = j * get_global_size(0) + k;                                                                      \
    values[at] = (float)(e * jv);                                                                                \
    values[get_global_size(0) * get_global_size(1) + at] = (float)(b * jv);                                      \
  }
MFV_ALBEDO_RQMC_VALUES(albedo_rqmc_values, s->d, s->g)
#endif

// The run a summing work-item g reads. The grid is rounded up to whole
// work-groups (runtime/work_group.hpp): a work-item past the last run reads
// the last run (a select, not a branch, so the loop over work-items
// vectorizes on AVX2 too) and writes a padding slot of the sums buffer.
inline size_t counted_row(size_t g, ulong groups) { return g < groups ? g : (size_t)(groups - 1); }

// The sums `integrate` leaves for the RQMC integrals from the E and B planes
// of albedo_rqmc_values (B `plane` values after E), per run of `per_group`
// values (a multiple of 2; run g belongs to integral g / slices): the sum of
// E and, in the second slot, the sum of B (MFV_CHECK_ALBEDO_RQMC) or the
// squared differences of neighbouring strata's E (stratified: E_avg).
__kernel void sum_rqmc(__global const float* restrict values, uint per_group, ulong plane,
                       __global const IntegralSpec* restrict specs, uint slices, __global acc_t* restrict sums,
                       ulong groups) {
  size_t g = get_global_id(0), r = counted_row(g, groups);
  __global const float* v = values + r * per_group;
  __global const float* b = v + plane;
  bool stratified = specs[r / slices].strata > 0u;
  acc_t s = 0, q = 0;
  for (uint k = 0; k < per_group; k += 2) {
    acc_t e0 = (acc_t)v[k], e1 = (acc_t)v[k + 1];
    s += e0 + e1;
    q += stratified ? (e0 - e1) * (e0 - e1) : (acc_t)b[k] + (acc_t)b[k + 1];
  }
  sums[MFV_SUM_SLOTS * g + MFV_SLOT_SUM] = s;
  sums[MFV_SUM_SLOTS * g + MFV_SLOT_SECOND] = q;
}

// Sum and the sum of squared differences of neighbouring samples (pairs
// 2i, 2i + 1: neighbouring strata) of each run of `per_group` values (a
// multiple of 4), as `integrate` leaves a stratified integral's work-groups.
__kernel void sum_pairs(__global const float* restrict values, uint per_group, __global acc_t* restrict sums,
                        ulong groups) {
  size_t g = get_global_id(0), r = counted_row(g, groups);
  __global const float* v = values + r * per_group;
  acc_t s[2] = {0, 0}, q[2] = {0, 0};
  for (uint k = 0; k < per_group; k += 4) {
#pragma unroll
    for (uint j = 0; j < 2; ++j) {
      acc_t a = (acc_t)v[k + 2 * j], b = (acc_t)v[k + 2 * j + 1];
      s[j] += a + b;
      q[j] += (a - b) * (a - b);
    }
  }
  sums[MFV_SUM_SLOTS * g + MFV_SLOT_SUM] = s[0] + s[1];
  sums[MFV_SUM_SLOTS * g + MFV_SLOT_SECOND] = q[0] + q[1];
}

// Sum and sum of squares of each run of `per_group` consecutive values (a
// multiple of 4) into sums[2g], sums[2g + 1], as `integrate` leaves its
// work-groups' sums; four partial sums each keep the adds from waiting on
// one another.
__kernel void sum_values(__global const float* restrict values, uint per_group, __global acc_t* restrict sums,
                         ulong groups) {
  size_t g = get_global_id(0), r = counted_row(g, groups);
  __global const float* v = values + r * per_group;
  acc_t s[4] = {0, 0, 0, 0}, q[4] = {0, 0, 0, 0};
  for (uint k = 0; k < per_group; k += 4) {
#pragma unroll
    for (uint j = 0; j < 4; ++j) {
      acc_t a = (acc_t)v[k + j];
      s[j] += a;
      q[j] += a * a;
    }
  }
  sums[MFV_SUM_SLOTS * g + MFV_SLOT_SUM] = (s[0] + s[1]) + (s[2] + s[3]);
  sums[MFV_SUM_SLOTS * g + MFV_SLOT_SECOND] = (q[0] + q[1]) + (q[2] + q[3]);
}

// The per-sample values of n samples of each integral, for the reference's
// same-sample comparison: the first n, or for a stratified integral n spread
// over all its strata (so both mixture components are compared). In a
// MFV_DOUBLE program (the double twin, host/checks/reference_compare.cpp)
// the values are doubles. Work-item k writes value first + k of the `total`
// (specs x n); the host launches it in chunks of one work-group size.
__kernel MFV_NO_IMPLICIT_VECTORIZE void sample_values(__global const IntegralSpec* specs, uint n, ulong seed,
                                                      __global real* out, ulong first, ulong total) {
  ulong i = first + get_global_id(0);
  if (i >= total) return;
  __global const IntegralSpec* s = specs + i / n;
  ulong stride = s->strata >= n ? (ulong)(s->strata / n) : 1ul;
  out[i] = sample_value(s, seed, (ulong)(i % n) * stride);
}

