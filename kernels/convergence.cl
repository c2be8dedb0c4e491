// mfv convergence's estimators. Needs estimators.cl and albedo.cl.
#include "abi/integral.h"  // IntegralSpec, MFV_CHECK_*, MFV_EST_*, MFV_SLOT_* (shared with the host)

// ---- mfv convergence (host/checks/convergence.cpp): estimators chosen by
// IntegralSpec::estimator for d_norm and albedo; 0 is the check's own
// estimator (the conformance MIS proposal above, unchanged). Reference
// twins: convergence_value in host/reference/estimators.cpp, same uniforms.
// The estimators' ids: MFV_EST_* in abi/integral.h.

// The D of the proposal's own shape (not the catalog's term: a wrong D under
// test must still show). GGX: Walter et al. 2007 eq. 33 as α²/(π(c²α² + s²)²);
// Beckmann: eq. 28, exp(-tan²/α²)/(π α² cos⁴).
static inline real conv_shape_D(uint est, real c, real s2, real w) {
  real w2 = w * w;
  if (est == MFV_EST_DSAMPLE_BECKMANN) {
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
  real t2 = est == MFV_EST_DSAMPLE_BECKMANN ? -w * w * log1p(-u_r) : w * w * u_r / (R(1.0) - u_r);
  *c = rsqrt(R(1.0) + t2);
  *s2 = t2 / (R(1.0) + t2);
  return conv_direction(*c, *s2, u_phi);
}

// One sample of integral `s` under estimator s->estimator (!= 0).
static inline real convergence_value(__global const IntegralSpec* s, ulong seed, ulong index) {
  uint est = s->estimator;
  real w = s->width;
  real u_phi, u_r;
  if (est == MFV_EST_RQMC) {
    // albedo: mfv energy's visible-normal proposal on the same points
    if (s->check != MFV_CHECK_D_NORM) return albedo_rqmc_value(s, rqmc_shift(s, seed), index).x;
    uint4 shift = rqmc_shift(s, seed);
    uint k = (uint)index;
    u_phi = u01_open(shift.x + k * RQMC_G1);
    u_r = u01_open(shift.y + k * RQMC_G2);
  } else {
    uint4 r = mfv_philox(seed, s->stream, spec_draw(s, 0u), index);
    u_phi = u01_open(r.z);
    u_r = u01_open(r.w);
  }
  if (s->check == MFV_CHECK_D_NORM) {
    real c, s2;
    if (est == MFV_EST_UNIFORM) {
      c = u_r;  // cos θ uniform on (0, 1) is uniform over the hemisphere
      s2 = sin2_from_cos(c);
      return spec_D(s, conv_direction(c, s2, u_phi), c, s2) * c * (R(2.0) * MFV_PI);
    }
    if (est == MFV_EST_COSINE) {
      s2 = u_r;
      c = sqrt(R(1.0) - u_r);
      return spec_D(s, conv_direction(c, s2, u_phi), c, s2) * MFV_PI;  // D c / (c/π)
    }
    if (est == MFV_EST_RQMC) {
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
  if (est == MFV_EST_UNIFORM || est == MFV_EST_COSINE) {
    real c = est == MFV_EST_UNIFORM ? u_r : sqrt(R(1.0) - u_r);
    real3 i = conv_direction(c, est == MFV_EST_UNIFORM ? sin2_from_cos(c) : u_r, u_phi);
    real inv_pdf = est == MFV_EST_UNIFORM ? R(2.0) * MFV_PI : MFV_PI / c;
    return spec_brdf(s, i, o) * c * inv_pdf;
  }
  if (est == MFV_EST_DSAMPLE_GGX || est == MFV_EST_DSAMPLE_BECKMANN) {
    // i = reflect(o, h): pdf_i = D_w(h)(h·n) / (4 o·h) (Walter et al. 2007 eq. 14, 38)
    real c, s2;
    real3 h = conv_sample_shape(est, u_phi, u_r, w, &c, &s2);
    real oh = dot(o, h);
    if (oh <= R(0.0)) return R(0.0);
    real3 i = R(2.0) * oh * h - o;
    if (i.z <= R(0.0)) return R(0.0);
    return spec_brdf(s, i, o) * i.z * (R(4.0) * oh) / (conv_shape_D(est, c, s2, w) * c);
  }
  if (est == MFV_EST_VNDF) {
    real3 m = sample_vis(o, u_phi, u_r, w);
    if (!(m.z > R(0.0))) return R(0.0);
    real b;
    return energy_weight(s, m, o, so2, w, &b);
  }
  return NAN;
}

