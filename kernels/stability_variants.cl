// Alternative formulations of the same quantities, compiled only for
// `mfv stability` (never for the conformance checks): the report shows, side
// by side with the kernel defaults, where each form breaks. Each variant
// reads one record (kernels/abi/pointwise.h, mode PW_VARIANT); the host's
// table in host/checks/stability_variants.cpp names them, marks the default
// and gives the double reference each one is compared with.
//
// Families and their inputs:
//   D_ggx:     PW_H_X = h.x, PW_H_Z = h.z (the half vector's components, h.y = 0), PW_PD = alpha
//   Lambda_ggx, G1_smith_ggx: PW_NOV, PW_PG = alpha
//   half vector: PW_WI_X..PW_WO_Z = wi, wo (unit, above the horizon)
#include "abi/pointwise.h"
#define MFV_STABILITY_VARIANTS  // kernels/pointwise.cl dispatches PW_VARIANT here

#define VAR_D_GGX_TAN2 0
#define VAR_D_GGX_COS 1
#define VAR_D_GGX_SIN2 2
#define VAR_LAMBDA_GGX_TAN2 3
#define VAR_LAMBDA_GGX_COS 4
#define VAR_LAMBDA_GGX_DEFAULT 5
#define VAR_G1_GGX_LAMBDA 6
#define VAR_G1_GGX_CLOSED 7
#define VAR_VOH_DOT 8
#define VAR_VOH_HALF_LENGTH 9
#define VAR_SIN2H_FROM_COS 10
#define VAR_SIN2H_CROSS 11

// tan²θ as seed 000 defines it: tanθ = sqrt(1 - (v·N)²) / (v·N).
static inline real tan2_seed000(real c) { return (R(1.0) - c * c) / (c * c); }

static inline real D_ggx_tan2(real NoH, real alpha) {
  // seed 000 "GGX", first form: α² / (π (n·h)⁴ (α² + tan²θ)²), Walter et al. 2007 eq. 33.
  // tan² from the cosine cancels near the normal; cos⁴ underflows and tan² overflows at grazing.
  if (NoH <= R(0.0)) return R(0.0);
  real a2 = alpha * alpha;
  real c2 = NoH * NoH;
  return a2 / (MFV_PI * c2 * c2 * sqr(a2 + tan2_seed000(NoH)));
}

static inline real D_ggx_cos(real NoH, real alpha) {
  // seed 000 "GGX", second form: α² / (π ((n·h)²(α² - 1) + 1)²).
  // α² - 1 rounds to -1 for α² below half an ulp of 1, and the bracket cancels to 0 at n·h = 1.
  if (NoH <= R(0.0)) return R(0.0);
  real a2 = alpha * alpha;
  return a2 / (MFV_PI * sqr(NoH * NoH * (a2 - R(1.0)) + R(1.0)));
}

static inline real Lambda_ggx_tan2(real NoV, real alpha) {
  // Heitz 2014 eq. 72 as printed: Λ = (-1 + sqrt(1 + α² tan²θ)) / 2, tan² from seed 000.
  if (NoV >= R(1.0)) return R(0.0);
  if (NoV <= R(0.0)) return INFINITY;
  return R(0.5) * (sqrt(R(1.0) + alpha * alpha * tan2_seed000(NoV)) - R(1.0));
}

static inline real Lambda_ggx_cos(real NoV, real alpha) {
  // Heitz 2014 eq. 72 through cosθ only (the form of Filament's V_SmithGGXCorrelated):
  // Λ = (sqrt(α² + (1 - α²) cos²θ) / cosθ - 1) / 2.
  if (NoV >= R(1.0)) return R(0.0);
  if (NoV <= R(0.0)) return INFINITY;
  real a2 = alpha * alpha;
  return R(0.5) * (sqrt(a2 + (R(1.0) - a2) * NoV * NoV) / NoV - R(1.0));
}

static inline real G1_smith_ggx_closed(real NoV, real alpha) {
  // seed 000 "GGX" closed form: 2 / (1 + sqrt(1 + α² tan²θ)), with seed 000's
  // guards ((v·n) >= 1 or tanθ = 0: 1) and tan² from the stable sin2_from_cos.
  if (NoV >= R(1.0)) return R(1.0);
  if (NoV <= R(0.0)) return R(0.0);             // θ -> π/2: G1 -> 0
  real t2 = tan2_from_cos(NoV);
  if (t2 <= R(0.0)) return R(1.0);
  return R(2.0) / (R(1.0) + sqrt(R(1.0) + alpha * alpha * t2));  // t2 = inf gives 0, the limit
}

static inline real stability_variant(int v, const real* r) {
  real3 wi = (real3)(r[PW_WI_X], r[PW_WI_Y], r[PW_WI_Z]), wo = (real3)(r[PW_WO_X], r[PW_WO_Y], r[PW_WO_Z]);
  real NoV = r[PW_NOV], aG = r[PW_PG];
  switch (v) {
    case VAR_D_GGX_TAN2: return D_ggx_tan2(r[PW_H_Z], r[PW_PD]);
    case VAR_D_GGX_COS: return D_ggx_cos(r[PW_H_Z], r[PW_PD]);
    case VAR_D_GGX_SIN2: return D_ggx(r[PW_H_Z], r[PW_H_X] * r[PW_H_X], r[PW_PD]);  // the kernel default, sin² = |n×h|²
    case VAR_LAMBDA_GGX_TAN2: return Lambda_ggx_tan2(NoV, aG);
    case VAR_LAMBDA_GGX_COS: return Lambda_ggx_cos(NoV, aG);
    case VAR_LAMBDA_GGX_DEFAULT: return Lambda_ggx(NoV, aG);
    case VAR_G1_GGX_LAMBDA: return G1_smith_ggx(NoV, aG);  // the kernel default, 1 / (1 + Λ)
    case VAR_G1_GGX_CLOSED: return G1_smith_ggx_closed(NoV, aG);
    // Half vector, seed 000: H = (L + V) / |L + V|.
    case VAR_VOH_DOT: return dot(wo, normalize(wi + wo));  // textbook: cancels as l -> -v
    case VAR_VOH_HALF_LENGTH: return min(R(0.5) * length(wi + wo), R(1.0));  // brdf.cl default
    case VAR_SIN2H_FROM_COS: return sin2_from_cos(normalize(wi + wo).z);  // 1 - (n·h)²: n·h lost the angle
    case VAR_SIN2H_CROSS: {  // brdf.cl default: |n×h|² from the components
      real3 s = wi + wo;
      real3 h = s / length(s);
      return h.x * h.x + h.y * h.y;
    }
  }
  return NAN;
}
