// Batched Monte Carlo integrals for the conformance checks (DESIGN.md §3-4).
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
// mfv energy (host/checks/energy.cpp): the albedo estimator's proposal with
// its three components taken deterministically (multi-sample MIS, balance
// heuristic) on randomized quasi-Monte Carlo points; each integral is one
// randomization (its stream picks the random shift), so the spread over
// several integrals gives the standard error. Twin: albedo_rqmc in estimators.cpp.
#define CHECK_ALBEDO_RQMC 3  // E(o) at cos_o, as CHECK_ALBEDO
#define CHECK_EAVG_RQMC 4    // E_avg = ∫ E(μ) 2μ dμ: μ drawn with density 2μ per point

#define MIX_COS R(0.25)   // share of the cosine lobe in the microfacet proposal (a power of 2: see d_norm)
#define MIX_I_COS R(0.2)  // share of cosine-weighted light directions (albedo)

// 16 four-byte fields; host twin: IntegralSpec in host/checks/integrate.hpp.
typedef struct {
  int check, d, g, f;
  float pd, pg, f0, f1;
  float kd, width, cos_o, p5;
  uint stream, strata, model, unused3;  // strata: samples of a stratified integral, 0 = iid
} IntegralSpec;

// The BRDF integral `s` checks: model 0 is the microfacet D×G×F BRDF of
// brdf.cl (with kd/π); whole models and user code plug in here, reading their
// parameters p[0..5] from pd, pg, f0, f1, kd, p5.
static inline real spec_brdf(__global const IntegralSpec* s, real3 i, real3 o) {
#ifdef MFV_WITH_GLTF
  if (s->model == MFV_MODEL_GLTF) return model_gltf_pbr(i, o, s->pd, s->pg, s->f0, s->f1, s->kd, s->p5);
#endif
  return brdf_eval(s->d, s->g, s->f, i, o, s->pd, s->pg, s->f0, s->f1, s->kd);
}

// Cauchy slopes in solid angle: p_slope(s) / cos³θ with
// p_slope = 1/(2πw²) (1 + tan²θ/w²)^(-3/2), which simplifies to
// 1 / (2π w² (cos² + sin²/w²)^(3/2)): no singularity at the normal or horizon.
static inline real pdf_slope(real c, real s2, real w) {
  real w2 = w * w;
  real k = c * c + s2 / w2;
  return R(1.0) / (R(2.0) * MFV_PI * w2 * k * sqrt(k));
}

static inline real pdf_m(real c, real s2, real w) {
  return MIX_COS * c * MFV_INV_PI + (R(1.0) - MIX_COS) * pdf_slope(c, s2, w);
}

// Draws m from the mixture; returns it with cos θ and sin²θ formed without
// cancellation (sin² from the sampled radius, not from 1 - cos²).
static inline real3 sample_m(real u_pick, real u_phi, real u_r, real w, real* c, real* s2) {
  real phi = R(2.0) * MFV_PI * u_phi;
  real st;
  if (u_pick < MIX_COS) {
    *s2 = u_r;                       // Malley: disk radius² = sin²θ
    *c = sqrt(R(1.0) - u_r);
    st = sqrt(u_r);
  } else {
    real t = w * sqrt(u_r * (R(2.0) - u_r)) / (R(1.0) - u_r);  // inverse CDF of |slope|: tanθ
    real t2 = t * t;
    *c = R(1.0) / sqrt(R(1.0) + t2);
    *s2 = t2 / (R(1.0) + t2);
    st = t * *c;
  }
  return (real3)(st * cos(phi), st * sin(phi), *c);
}

// f(i,o) (n·i) / pdf(i) for the albedo proposal: the union of a cosine lobe
// and o reflected about an m from the mixture.
static inline real albedo_weight(__global const IntegralSpec* s, real3 i, real3 o, real w) {
  if (i.z <= R(0.0)) return R(0.0);
  real3 sum = i + o;
  real len = length(sum);
  real3 h = sum / len;
  real oh = R(0.5) * len;  // o·h = |i + o| / 2, as in brdf_eval
  real hs2 = h.x * h.x + h.y * h.y;
  real pdf = MIX_I_COS * i.z * MFV_INV_PI + (R(1.0) - MIX_I_COS) * pdf_m(h.z, hs2, w) / (R(4.0) * oh);
  real f = spec_brdf(s, i, o);
  return f * i.z / pdf;
}

// Kronecker (additive recurrence) sequence of Roberts 2018: point k is
// frac(shift + k·g), g_j = 1/φ^j with φ the real root of x⁴ = x + 1 (the
// 3-dimensional generalized golden ratio), in 32-bit fixed point so that
// k·g mod 1 is exact. Cranley-Patterson shift from Philox draw 2 of the
// integral's stream. Host twin: kRqmcG in estimators.cpp.
#define RQMC_G1 3518319155u
#define RQMC_G2 2882110345u
#define RQMC_G3 2360945575u

// One point of CHECK_ALBEDO_RQMC / CHECK_EAVG_RQMC: the same proposal as the
// albedo check, but each of its three components (cosine-lobe light, o
// reflected about a cosine-lobe m, o reflected about a Cauchy m) gets one
// direction from the point's (u_phi, u_r), weighted by its mixture share:
// Σ_c p_c E_c[f cos / pdf] is the integral when pdf = Σ_c p_c pdf_c.
static inline real albedo_rqmc_value(__global const IntegralSpec* s, ulong seed, ulong index) {
  uint4 shift = mfv_philox(seed, s->stream, 2, 0);
  uint k = (uint)index;
  real u_phi = u01_open(shift.x + k * RQMC_G1), u_r = u01_open(shift.y + k * RQMC_G2);
  real co = s->cos_o;
  if (s->check == CHECK_EAVG_RQMC) co = sqrt(u01_open(shift.z + k * RQMC_G3));  // density 2μ
  real3 o = (real3)(sqrt(sin2_from_cos(co)), R(0.0), co);
  real w = s->width;
  real st = sqrt(u_r), phi = R(2.0) * MFV_PI * u_phi;
  real3 i = (real3)(st * cos(phi), st * sin(phi), sqrt(R(1.0) - u_r));
  real v = MIX_I_COS * albedo_weight(s, i, o, w);
  real c, s2;
  real3 m = sample_m(R(0.0), u_phi, u_r, w, &c, &s2);  // u_pick = 0: the cosine lobe
  v += (R(1.0) - MIX_I_COS) * MIX_COS * albedo_weight(s, R(2.0) * dot(o, m) * m - o, o, w);
  m = sample_m(R(1.0), u_phi, u_r, w, &c, &s2);        // u_pick = 1: Cauchy slopes
  v += (R(1.0) - MIX_I_COS) * (R(1.0) - MIX_COS) * albedo_weight(s, R(2.0) * dot(o, m) * m - o, o, w);
  return v;
}

// One sample of the estimator of integral `s`.
static inline real sample_value(__global const IntegralSpec* s, ulong seed, ulong index) {
  if (s->check >= CHECK_ALBEDO_RQMC) return albedo_rqmc_value(s, seed, index);
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
    if (s->strata > 0u) {
      ulong n_cos = (ulong)s->strata / 4u;
      bool cosine = index < n_cos;
      ulong k = cosine ? index : index - n_cos;
      ulong n = cosine ? n_cos : (ulong)s->strata - n_cos;
      u_pick = cosine ? R(0.0) : R(1.0);
      u_r = min(((real)k + u_r) / (real)n, R(0x1.fffffep-1));
    }
    sample_m(u_pick, u_phi, u_r, w, &c, &s2);
    return eval_D(s->d, c, s2, s->pd) * c / pdf_m(c, s2, w);
  }
  real co = s->cos_o;
  real3 o = (real3)(sqrt(sin2_from_cos(co)), R(0.0), co);
  if (s->check == CHECK_MASKING) {
    // weak white furnace (Heitz 2014 eq. 19): ∫ G1(o,m) D(m) max(0, o·m) dm / (o·n) = 1,
    // with G1(o,m) = G2(light at the normal, o, m), the Smith G1 for Smith G2s
    real c, s2;
    real3 m = sample_m(u_pick, u_phi, u_r, w, &c, &s2);
    real om = dot(o, m);
    if (om <= R(0.0)) return R(0.0);
    real g1 = eval_G(s->g, R(1.0), co, c, om, s->pg);
    return g1 * eval_D(s->d, c, s2, s->pd) * om / (pdf_m(c, s2, w) * co);
  }
  // directional albedo E(o) = ∫ f(i,o) (n·i) di; i from a cosine lobe or by
  // reflecting o about an m from the mixture; the pdf is that of the union.
  real3 i;
  if (u_branch < MIX_I_COS) {
    real st = sqrt(u_r), phi = R(2.0) * MFV_PI * u_phi;
    i = (real3)(st * cos(phi), st * sin(phi), sqrt(R(1.0) - u_r));
  } else {
    real c, s2;
    real3 m = sample_m(u_pick, u_phi, u_r, w, &c, &s2);
    i = R(2.0) * dot(o, m) * m - o;
  }
  return albedo_weight(s, i, o, w);
}

// Work-group g integrates slice (g % slices) of integral (g / slices): each
// work-item takes per_item consecutive sample indices.
__kernel void integrate(__global const IntegralSpec* specs, uint slices, uint per_item, ulong seed,
                        __global acc_t* sums, __local acc_t* scratch) {
  size_t group = get_group_id(0), lid = get_local_id(0), lsize = get_local_size(0);
  __global const IntegralSpec* s = specs + group / slices;
  ulong base = ((ulong)(group % slices) * lsize + lid) * per_item;
  acc_t sum = 0, sumsq = 0;
  if (s->strata > 0u) {
    // stratified: sumsq collects squared differences of neighbouring strata
    // (per_item is even, so pairs never straddle work-items)
    for (uint k = 0; k < per_item; k += 2) {
      acc_t v0 = (acc_t)sample_value(s, seed, base + k), v1 = (acc_t)sample_value(s, seed, base + k + 1);
      sum += v0 + v1;
      sumsq += (v0 - v1) * (v0 - v1);
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

// The per-sample values of n samples of each integral, for the reference's
// same-sample comparison: the first n, or for a stratified integral n spread
// over all its strata (so both mixture components are compared).
__kernel void sample_values(__global const IntegralSpec* specs, uint n, ulong seed, __global float* out) {
  size_t i = get_global_id(0);
  __global const IntegralSpec* s = specs + i / n;
  ulong stride = s->strata >= n ? (ulong)(s->strata / n) : 1ul;
  out[i] = (float)sample_value(s, seed, (ulong)(i % n) * stride);
}

// Reciprocity: |f(i,o) - f(o,i)| / max(|f(i,o)|, |f(o,i)|) over pairs drawn
// by kind (index % 4): uniform hemisphere, grazing, near-retro, near-mirror.
// Each work-item writes its worst asymmetry and the sample index where it was.
__kernel void reciprocity(__global const IntegralSpec* specs, uint per_item, ulong seed, __global float* worst,
                          __global uint* worst_index) {
  size_t gid = get_global_id(0), lid = get_local_id(0), lsize = get_local_size(0);
  __global const IntegralSpec* s = specs + get_group_id(0);
  float w = 0.0f;
  uint wi = 0;
  for (uint k = 0; k < per_item; ++k) {
    uint index = (uint)lid * per_item + k;
    uint4 r = mfv_philox(seed, s->stream, 1, index);
    real ca = u01_open(r.x), pa = R(2.0) * MFV_PI * u01_open(r.y);
    real cb = u01_open(r.z), pb = R(2.0) * MFV_PI * u01_open(r.w);
    uint kind = index % 4;
    if (kind == 1) { ca *= R(1e-3); cb *= R(1e-3); }                 // both grazing
    real sa = sqrt(sin2_from_cos(ca));
    real3 a = (real3)(sa * cos(pa), sa * sin(pa), ca);
    real3 b;
    if (kind == 2 || kind == 3) {
      // a small offset from the retro (b = a) or mirror (b = reflect a) direction
      real3 base = kind == 2 ? a : (real3)(-a.x, -a.y, a.z);
      b = normalize(base + R(1e-3) * (real3)(cb - R(0.5), u01_open(r.w) - R(0.5), R(0.0)));
      if (b.z <= R(0.0)) b.z = -b.z;
    } else {
      real sb = sqrt(sin2_from_cos(cb));
      b = (real3)(sb * cos(pb), sb * sin(pb), cb);
    }
    real f1 = spec_brdf(s, a, b);
    real f2 = spec_brdf(s, b, a);
    real m = max(fabs(f1), fabs(f2));
    float asym = m > R(0.0) ? (float)(fabs(f1 - f2) / m) : 0.0f;
    if (!(asym <= w)) {  // NaN counts as the worst
      w = isnan(asym) ? INFINITY : asym;
      wi = index;
    }
  }
  worst[gid] = w;
  worst_index[gid] = wi;
}
