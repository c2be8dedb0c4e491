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
// (mfv run's same-sample comparison) stays. agree's kernels (agree.cl)
// carry it too: with Phong by components and mfv_exp/mfv_log1p inlined
// (issue 31), every whole model's agree came out 0 or 1e307 on Intel.
#define MFV_NO_IMPLICIT_VECTORIZE __attribute__((vec_type_hint(float4)))

// The terms (terms_d/g/f.cl) sit between MFV_TERMS_BEGIN and MFV_TERMS_END:
// every function there is inlined where it is called (PoCL vectorizes a
// kernel only where no call is left; see mfv_exp below), but only where the
// host asks (MFV_INLINE_TERMS: the integration programs on PoCL,
// runtime/integrator.cpp). Intel's CPU runtime miscompiles the whole-model
// agree kernels of a program whose terms are all forced inline (mfv agree:
// lambert 0 or inf; the Intel portability test). MFV_ALWAYS_INLINE marks
// the integrands the kernels specialized per term pair call
// (runtime/specialize.cpp): inlined, their term ids become constants and
// the select chains of eval_D/eval_G fold to one term.
#ifdef MFV_INLINE_TERMS
#define MFV_TERMS_BEGIN _Pragma("clang attribute push(__attribute__((always_inline)), apply_to = function)")
#define MFV_TERMS_END _Pragma("clang attribute pop")
#define MFV_ALWAYS_INLINE __attribute__((always_inline))
#else
#define MFV_TERMS_BEGIN
#define MFV_TERMS_END
#define MFV_ALWAYS_INLINE
#endif

#define MFV_PI R(3.14159265358979323846)
#define MFV_INV_PI R(0.31830988618379067154)
#define MFV_SQRT_PI R(1.77245385090551602730)

// The helpers below are inlined with the terms (MFV_INLINE_TERMS): a select
// chain of two Beckmann Smith terms calls mfv_erfc from two places, and
// LLVM's inliner then keeps it out of line (cost 490 > 225), which stops
// PoCL vectorizing the caller (the specialized albedo_mis_values of
// smith_beckmann, the anisotropic masking).
MFV_TERMS_BEGIN
static inline real saturate(real x) { return clamp(x, R(0.0), R(1.0)); }
static inline real safe_sqrt(real x) { return sqrt(max(x, R(0.0))); }
static inline real sqr(real x) { return x * x; }

// exp, log, log1p, erfc and acos without a library call in float programs
// (the terms and whole models call these). PoCL's are out-of-line calls
// (SLEEF, cost above LLVM's inline threshold), and one call in a kernel
// stops PoCL running its work-items in SIMD lanes. Branch-free (selects), no table; double programs
// (the reference twin) take the library's. Errors, measured against the
// double library over every float in [-104, 89] (exp) and [2^-149, 2^128)
// (log) by tests/test_fast_math.cpp: see there.
#ifdef MFV_DOUBLE
static inline real mfv_exp(real x) { return exp(x); }
static inline real mfv_log(real x) { return log(x); }
static inline real mfv_log1p(real x) { return log1p(x); }
static inline real mfv_erfc(real x) { return erfc(x); }
static inline real mfv_pow(real x, real y) { return pow(x, y); }
static inline real mfv_acos(real x) { return acos(x); }
#else
// 2^k for an integer k in [-126, 127], from its bits.
static inline float mfv_pow2i(int k) { return as_float((k + 127) << 23); }

// exp(x) = 2^n e^r: n = round(x / ln 2), r = x - n ln 2 with ln 2 in two
// parts (Cody and Waite 1980: n·ln2_hi is exact for |n| < 2^9, as ln2_hi has
// 16 significant bits), e^r on |r| <= ln2/2 by its Taylor polynomial to r^7
// (truncation below 0.347^8/8! = 5e-9 relative). 2^n in two factors, so
// that results down to the subnormals scale exactly once. Below -104 the
// result is under half the smallest subnormal: 0; above 89: inf.
static inline float mfv_exp(float x) {
  float xc = clamp(x, -104.0f, 89.0f);
  float n = floor(xc * 1.44269504088896341f + 0.5f);
  float r = (xc - n * 0.693145751953125f) - n * 1.428606765330187e-6f;
  float p = 1.0f + r * (1.0f + r * (0.5f + r * (1.6666667e-1f + r * (4.1666668e-2f + r * (8.3333338e-3f +
                                                                  r * (1.3888889e-3f + r * 1.9841270e-4f))))));
  int ni = (int)n, n1 = ni / 2;
  float y = p * mfv_pow2i(n1) * mfv_pow2i(ni - n1);
  return x != x ? x : y;  // NaN stays NaN (clamp may drop it)
}

// log(x) = e ln 2 + log(m), m in [√½, √2): log(m) = log(1+f) = 2 atanh(s),
// s = f/(2+f), |s| <= 0.172, written f - s(f - s²P(s²)) (2s = f - s·f), the
// series to s^9 (truncation below 2·0.172^11/11 = 7e-10). Subnormal x is
// scaled by 2^23 first; 0 gives -inf, inf inf, negative or NaN NaN.
static inline float mfv_log(float x) {
  bool sub = x < 0x1p-126f;
  int bits = as_int(sub ? x * 0x1p23f : x);
  int e = ((bits >> 23) & 0xff) - 127 - (sub ? 23 : 0);
  float m = as_float((bits & 0x007fffff) | 0x3f800000);  // [1, 2)
  bool big = m > 1.41421356f;
  m = big ? 0.5f * m : m;
  e = big ? e + 1 : e;
  float f = m - 1.0f;  // exact (Sterbenz)
  float s = f / (2.0f + f), s2 = s * s;
  float l = f - s * (f - s2 * (6.6666669e-1f + s2 * (4.0000001e-1f + s2 * (2.8571430e-1f + s2 * 2.2222222e-1f))));
  float fe = (float)e;
  float y = fe * 0.693145751953125f + (l + fe * 1.428606765330187e-6f);
  y = x == INFINITY ? x : y;
  y = x == 0.0f ? -INFINITY : y;
  return x < 0.0f || x != x ? NAN : y;
}

// log1p(x) = log(u) · x / (u - 1), u = 1 + x rounded (Goldberg 1991, "What
// every computer scientist should know about floating-point arithmetic",
// Theorem 4): the factor corrects the rounding of u.
static inline float mfv_log1p(float x) {
  float u = 1.0f + x, d = u - 1.0f;
  return d == 0.0f ? x : mfv_log(u) * (x / d);
}

// erfc(x) = exp(-x²) erfcx(x) for x >= 0, erfcx by the Chebyshev fit of
// Press et al., Numerical Recipes in C (2nd ed., §6.2, erfcc: fractional
// error below 1.2e-7 everywhere), t = 1/(1 + x/2); erfc(-x) = 2 - erfc(x).
static inline float mfv_erfc(float x) {
  float z = fabs(x), t = 1.0f / (1.0f + 0.5f * z);
  float p = -1.26551223f + t * (1.00002368f + t * (0.37409196f + t * (0.09678418f + t * (-0.18628806f +
            t * (0.27886807f + t * (-1.13520398f + t * (1.48851587f + t * (-0.82215223f + t * 0.17087277f))))))));
  float y = mfv_exp(-z * z) * (t * mfv_exp(p));
  return x < 0.0f ? 2.0f - y : y;
}

// acos(x) for x in [-1, 1] (eon's FON albedo), the method of Cephes acosf
// and asinf (Moshier, "Methods and Programs for Mathematical Functions",
// 1989; cephes/single/asinf.c, acosf.c, whose coefficients these are): for
// a = |x| <= 1/2, acos(a) = π/2 - asin(a), asin(a) = a + a z P(z) with z = a²,
// P of degree 4 (a minimax fit on [0, 1/4]); for a > 1/2, acos(a) =
// 2 asin(t) with t = sqrt((1 - a)/2) <= 1/2 (1 - a exact by Sterbenz, no
// cancellation near 1); acos(-a) = π - acos(a). Branch-free (selects).
// Ends: acos(±1) = 0 and π exactly (t = 0), acos(0) = π/2; a |x| above 1
// (a cosine rounded up) is taken as ±1; NaN stays NaN.
static inline float mfv_acos(float x) {
  float a = fmin(fabs(x), 1.0f);
  bool hi = a > 0.5f;
  float z = hi ? 0.5f * (1.0f - a) : a * a;
  float t = hi ? sqrt(z) : a;
  float p = t + t * z * (1.6666752422e-1f + z * (7.4953002686e-2f + z * (4.5470025998e-2f +
                                                 z * (2.4181311049e-2f + z * 4.2163199048e-2f))));
  float r = hi ? 2.0f * p : 1.57079632679489662f - p;
  r = x < 0.0f ? 3.14159265358979324f - r : r;
  return x != x ? x : r;
}

// x^y for x >= 0 and finite y (the Charlie Λ fit's x^c, c in (0, 1)):
// exp(y log x). 0^y for y > 0 is exp(-inf) = 0, x^0 = exp(0) = 1. The
// relative error is |y log x| times log's plus exp's own: y log x carries
// log's relative error into an absolute one in the exponent.
static inline float mfv_pow(float x, float y) { return mfv_exp(y * mfv_log(x)); }
#endif

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
  return sin2 < R(0.5) ? R(0.5) * mfv_log1p(-sin2) : mfv_log(c);
}
MFV_TERMS_END
