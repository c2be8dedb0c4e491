// mfv check --dialect glsl|hlsl: the dialect's constructors and built-ins,
// for the user's files only. Built only with -DMFV_USER_BRDF, right before
// the user's files, which host/user/dialect.cpp translated token by token:
// vecN/floatN constructors call mfv_vecN, the built-ins OpenCL C lacks or
// names otherwise call mfv_g_NAME (GLSL 4.60 spec §8 and HLSL's intrinsic
// reference define each one's semantics, written plainly below). Every
// function the user's files define is overloadable (the attribute pushed
// below, popped by kernels/user_brdf.cl), and #if on an undefined name is an
// error, as -Werror=undef.

#define MFV_OVL static inline __attribute__((overloadable))

// The double twin (-DMFV_USER_TWIN; host/user/user_twin.cpp): the same
// files with every float type double (and, by the host, literals without
// their f suffix), so that kf - kd on the same samples is the float
// rounding of the user's code and nothing else. Popped by user_brdf.cl.
#pragma push_macro("float")
#pragma push_macro("float2")
#pragma push_macro("float3")
#pragma push_macro("float4")
#ifdef MFV_USER_TWIN
#pragma clang diagnostic push
#pragma clang diagnostic ignored "-Wkeyword-macro"
#define float double
#define float2 double2
#define float3 double3
#define float4 double4
#pragma clang diagnostic pop
#endif

#if MFV_USER_DIALECT != 0
// constructors: from scalars, vectors and their concatenations
MFV_OVL float2 mfv_vec2(float x) { return (float2)(x); }
MFV_OVL float2 mfv_vec2(float x, float y) { return (float2)(x, y); }
MFV_OVL float2 mfv_vec2(float2 v) { return v; }
MFV_OVL float2 mfv_vec2(float3 v) { return v.xy; }
MFV_OVL float2 mfv_vec2(float4 v) { return v.xy; }
MFV_OVL float3 mfv_vec3(float x) { return (float3)(x); }
MFV_OVL float3 mfv_vec3(float x, float y, float z) { return (float3)(x, y, z); }
MFV_OVL float3 mfv_vec3(float2 v, float z) { return (float3)(v, z); }
MFV_OVL float3 mfv_vec3(float x, float2 v) { return (float3)(x, v); }
MFV_OVL float3 mfv_vec3(float3 v) { return v; }
MFV_OVL float3 mfv_vec3(float4 v) { return v.xyz; }
MFV_OVL float4 mfv_vec4(float x) { return (float4)(x); }
MFV_OVL float4 mfv_vec4(float x, float y, float z, float w) { return (float4)(x, y, z, w); }
MFV_OVL float4 mfv_vec4(float3 v, float w) { return (float4)(v, w); }
MFV_OVL float4 mfv_vec4(float x, float3 v) { return (float4)(x, v); }
MFV_OVL float4 mfv_vec4(float2 a, float2 b) { return (float4)(a, b); }
MFV_OVL float4 mfv_vec4(float2 a, float z, float w) { return (float4)(a, z, w); }
MFV_OVL float4 mfv_vec4(float x, float y, float2 b) { return (float4)(x, y, b); }
MFV_OVL float4 mfv_vec4(float x, float2 b, float w) { return (float4)(x, b, w); }
MFV_OVL float4 mfv_vec4(float4 v) { return v; }

// Built-ins for a float type T (scalar S, so that mixed vector-scalar
// calls resolve as they do in the shading languages).
#define MFV_SHADING_BUILTINS(T)                                                        \
  MFV_OVL T mfv_g_abs(T x) { return fabs(x); }                                       \
  MFV_OVL T mfv_g_fract(T x) { return x - floor(x); }                                \
  MFV_OVL T mfv_g_mod(T x, T y) { return x - y * floor(x / y); }                     \
  MFV_OVL T mfv_g_atan(T y, T x) { return atan2(y, x); }                             \
  MFV_OVL T mfv_g_atan(T x) { return atan(x); }                                      \
  MFV_OVL T mfv_g_pow(T x, T y) { return pow(x, y); }                                \
  MFV_OVL T mfv_g_saturate(T x) { return clamp(x, (T)(0.0f), (T)(1.0f)); }           \
  MFV_OVL T mfv_g_rcp(T x) { return 1.0f / x; }                                      \
  MFV_OVL T mfv_g_mad(T a, T b, T c) { return a * b + c; }                           \
  MFV_OVL T mfv_g_min(T x, T y) { return fmin(x, y); }                               \
  MFV_OVL T mfv_g_max(T x, T y) { return fmax(x, y); }                               \
  MFV_OVL T mfv_g_clamp(T x, T lo, T hi) { return fmin(fmax(x, lo), hi); }           \
  MFV_OVL T mfv_g_mix(T x, T y, T a) { return x + (y - x) * a; }                     \
  MFV_OVL T mfv_g_step(T edge, T x) { return x < edge ? (T)(0.0f) : (T)(1.0f); }
MFV_SHADING_BUILTINS(float)
// vectors: x < edge compares per component; select per component
#undef MFV_SHADING_BUILTINS
#define MFV_SHADING_BUILTINS(T)                                                        \
  MFV_OVL T mfv_g_abs(T x) { return fabs(x); }                                       \
  MFV_OVL T mfv_g_fract(T x) { return x - floor(x); }                                \
  MFV_OVL T mfv_g_mod(T x, T y) { return x - y * floor(x / y); }                     \
  MFV_OVL T mfv_g_mod(T x, float y) { return x - y * floor(x / y); }                 \
  MFV_OVL T mfv_g_atan(T y, T x) { return atan2(y, x); }                             \
  MFV_OVL T mfv_g_atan(T x) { return atan(x); }                                      \
  MFV_OVL T mfv_g_pow(T x, T y) { return pow(x, y); }                                \
  MFV_OVL T mfv_g_saturate(T x) { return clamp(x, 0.0f, 1.0f); }                     \
  MFV_OVL T mfv_g_rcp(T x) { return 1.0f / x; }                                      \
  MFV_OVL T mfv_g_mad(T a, T b, T c) { return a * b + c; }                           \
  MFV_OVL T mfv_g_min(T x, T y) { return fmin(x, y); }                               \
  MFV_OVL T mfv_g_min(T x, float y) { return fmin(x, (T)(y)); }                      \
  MFV_OVL T mfv_g_max(T x, T y) { return fmax(x, y); }                               \
  MFV_OVL T mfv_g_max(T x, float y) { return fmax(x, (T)(y)); }                      \
  MFV_OVL T mfv_g_clamp(T x, T lo, T hi) { return fmin(fmax(x, lo), hi); }           \
  MFV_OVL T mfv_g_clamp(T x, float lo, float hi) { return fmin(fmax(x, (T)(lo)), (T)(hi)); } \
  MFV_OVL T mfv_g_mix(T x, T y, T a) { return x + (y - x) * a; }                     \
  MFV_OVL T mfv_g_mix(T x, T y, float a) { return x + (y - x) * a; }                 \
  MFV_OVL T mfv_g_step(T edge, T x) { return step(edge, x); }                        \
  MFV_OVL T mfv_g_step(float edge, T x) { return step(edge, x); }                    \
  MFV_OVL T mfv_g_reflect(T i, T n) { return i - 2.0f * dot(n, i) * n; }
MFV_SHADING_BUILTINS(float2)
MFV_SHADING_BUILTINS(float3)
MFV_SHADING_BUILTINS(float4)
#undef MFV_SHADING_BUILTINS
// integers: abs alone (min/max/clamp of ints go through float, exact below
// 2^24, so that max(x, 0) on a float x is not ambiguous)
MFV_OVL int mfv_g_abs(int x) { return abs(x); }

#pragma clang attribute push(__attribute__((overloadable)), apply_to = function)
#endif

#pragma clang diagnostic push
#pragma clang diagnostic error "-Wundef"
// v.rgb, as the shading languages write it, is OpenCL C 3.0 (and works before)
#pragma clang diagnostic ignored "-Wopencl-unsupported-rgba"
// the suite's one-letter macro R(x) is not the user's
#pragma push_macro("R")
#undef R
