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

// log(cos θ) from both cos and sin²: ½ log1p(-sin²) near the normal, where
// cos has lost the small angle, and log(cos) elsewhere, where 1 - sin² cancels.
static inline real log_cos(real c, real sin2) {
  return sin2 < R(0.5) ? R(0.5) * log1p(-sin2) : log(c);
}
