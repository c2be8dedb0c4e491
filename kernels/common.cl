// Shared by every program: the working precision, constants, named helpers.
// Build with -DMFV_DOUBLE for a float64 program (needs cl_khr_fp64).
#ifdef MFV_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double real;
typedef double3 real3;
typedef double2 real2;
#define R(x) (x)
#else
typedef float real;
typedef float3 real3;
typedef float2 real2;
#define R(x) (x##f)
#endif

// Kernels that evaluate whole models take MFV_NO_IMPLICIT_VECTORIZE: Intel's
// CPU runtime (2026.2) vectorizes a kernel across work-items unless it
// carries a vector vec_type_hint, and that vectorizer miscompiles these
// kernels (issue 19; docs/portability.md): with lambert, eon and gltf in
// one program the lambert albedo came out 0.18 to 0.42 instead of 1, a
// different value on each run, while width 1 (CL_CONFIG_CPU_VECTORIZER_MODE=1),
// PoCL, rusticl and Oclgrind (no invalid access, no race) agree with the
// reference. The hint is standard OpenCL C (6.7.2), a hint only: other
// implementations may ignore it. The reference comparison that caught it
// (mfv run's same-sample comparison) stays.
#define MFV_NO_IMPLICIT_VECTORIZE __attribute__((vec_type_hint(float4)))

#define MFV_PI R(3.14159265358979323846)
#define MFV_INV_PI R(0.31830988618379067154)
#define MFV_SQRT_PI R(1.77245385090551602730)

static inline real saturate(real x) { return clamp(x, R(0.0), R(1.0)); }
static inline real safe_sqrt(real x) { return sqrt(max(x, R(0.0))); }
static inline real sqr(real x) { return x * x; }

// sin^2 from cos without cancellation: (1-c)(1+c); 1-c is exact for
// c in [0.5, 1] (Sterbenz), where 1-c*c would lose every digit near c = 1.
// Dot products that round above 1 give 0, never a negative square.
static inline real sin2_from_cos(real c) { return max((R(1.0) - c) * (R(1.0) + c), R(0.0)); }

// tan^2 = sin^2 / cos^2; callers guard cos <= 0 (tan -> infinity) themselves.
static inline real tan2_from_cos(real c) { return sin2_from_cos(c) / (c * c); }

// (sin 2πu, cos 2πu) for u in [0, 1]. In float: reduce to the nearest
// quarter turn q (4u - q is exact: no rounding, unlike 2π·u), then Taylor
// polynomials on |x| <= π/4 (truncation below 3e-8, under half an ulp of 1).
// No library call and no branch (PoCL's sin/cos are out-of-line calls with
// a slow-path argument reduction): the albedo integrand runs 1.6x faster
// with this and brdf_eval's component arithmetic. Double programs take sin/cos. Reference twin: std::sin/cos(2π u) in estimators.cpp.
static inline real2 sincos_2pi(real u) {
#ifdef MFV_DOUBLE
  real phi = R(2.0) * MFV_PI * u;
  return (real2)(sin(phi), cos(phi));
#else
  int q = (int)(u * R(4.0) + R(0.5));
  real x = (u * R(4.0) - (real)q) * (MFV_PI * R(0.5));
  real x2 = x * x;
  real sp = x + x * x2 * (R(-1.6666667e-1) + x2 * (R(8.3333333e-3) + x2 * (R(-1.9841270e-4) + x2 * R(2.7557319e-6))));
  real cp = R(1.0) + x2 * (R(-0.5) + x2 * (R(4.1666667e-2) + x2 * (R(-1.3888889e-3) + x2 * R(2.4801587e-5))));
  real a = (q & 1) ? cp : sp, b = (q & 1) ? sp : cp;  // quarter turns swap sin and cos...
  return (real2)((q & 2) ? -a : a, ((q + 1) & 2) ? -b : b);  // ...and flip their signs
#endif
}

// The half vector of l and v from their sum (sx, sy, sz), by components (no
// float3 operations or length() call: see sincos_2pi): h = sum / |sum|;
// returns |sum| = 2 (v·h). Where |sum|² is below 2^-120 (opposite grazing
// directions: |l + v| down to ~1e-20) the squares would lose bits or
// underflow, so the sum is scaled by 2^100 first, exactly, as length()
// rescales. (Tested on |sum|², not on max |component|: the two fabs of a max
// become a 2-lane SLP vector that stops PoCL vectorizing albedo_values.)
static inline real normalize_sum(real sx, real sy, real sz, real* hx, real* hy, real* hz) {
  bool tiny = sx * sx + sy * sy + sz * sz < R(0x1p-120);
  real k = tiny ? R(0x1p100) : R(1.0);
  sx *= k;
  sy *= k;
  sz *= k;
  real len = sqrt(sx * sx + sy * sy + sz * sz);
  real inv = R(1.0) / len;
  *hx = sx * inv;
  *hy = sy * inv;
  *hz = sz * inv;
  return len * (tiny ? R(0x1p-100) : R(1.0));  // exactly len / k, without a division
}

// log(cos θ) from both cos and sin²: ½ log1p(-sin²) near the normal, where
// cos has lost the small angle, and log(cos) elsewhere, where 1 - sin² cancels.
static inline real log_cos(real c, real sin2) {
  return sin2 < R(0.5) ? R(0.5) * log1p(-sin2) : log(c);
}
