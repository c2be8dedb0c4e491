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
// hlsl's sincos(x, out s, out c) (its out arguments by address, as a user
// function's), and a scalar's (or a vector's first component's) swizzle
// x.xxx, which host/user/dialect_matrix.cpp writes mfv_splatN(x)
#define MFV_SINCOS_SPLAT(T)                                                        \
  MFV_OVL void mfv_g_sincos(T x, T* s, T* c) { *s = sin(x); *c = cos(x); }        \
  MFV_OVL float2 mfv_splat2(T x) { return (float2)(((T)(x)).s0); }                \
  MFV_OVL float3 mfv_splat3(T x) { return (float3)(((T)(x)).s0); }                \
  MFV_OVL float4 mfv_splat4(T x) { return (float4)(((T)(x)).s0); }
MFV_SINCOS_SPLAT(float2)
MFV_SINCOS_SPLAT(float3)
MFV_SINCOS_SPLAT(float4)
#undef MFV_SINCOS_SPLAT
MFV_OVL void mfv_g_sincos(float x, float* s, float* c) { *s = sin(x); *c = cos(x); }
MFV_OVL float2 mfv_splat2(float x) { return (float2)(x); }
MFV_OVL float3 mfv_splat3(float x) { return (float3)(x); }
MFV_OVL float4 mfv_splat4(float x) { return (float4)(x); }
// integers: abs alone (min/max/clamp of ints go through float, exact below
// 2^24, so that max(x, 0) on a float x is not ambiguous)
MFV_OVL int mfv_g_abs(int x) { return abs(x); }

// Square matrices, N = 2, 3, 4 (host/user/dialect_matrix.cpp): c holds
// glsl's columns or hlsl's rows, in the order the constructor's arguments
// come in both. GLSL 4.60 §5.4.2, §5.10: m * v = sum v_i c_i, v * m =
// (v.c_i), column j of a * b = a * b.c_j; matN(matM) keeps the upper-left
// part and fills the rest from the identity. HLSL mul(M, v) = (row_i . v),
// mul(v, M) = sum v_i row_i, rows of mul(A, B) = those of A times B:
// mfv_hmul(x, y) is glsl's y * x on the rows, and mul of two vectors is
// their dot product.
typedef struct { float2 c[2]; } mfv_mat2;
typedef struct { float3 c[3]; } mfv_mat3;
typedef struct { float4 c[4]; } mfv_mat4;
MFV_OVL mfv_mat2 mfv_mat2_make(float2 a, float2 b) { mfv_mat2 m = {{a, b}}; return m; }
MFV_OVL mfv_mat3 mfv_mat3_make(float3 a, float3 b, float3 c) { mfv_mat3 m = {{a, b, c}}; return m; }
MFV_OVL mfv_mat4 mfv_mat4_make(float4 a, float4 b, float4 c, float4 d) { mfv_mat4 m = {{a, b, c, d}}; return m; }
MFV_OVL mfv_mat2 mfv_mat2_make(float s) { return mfv_mat2_make((float2)(s, 0.0f), (float2)(0.0f, s)); }
MFV_OVL mfv_mat3 mfv_mat3_make(float s) {
  return mfv_mat3_make((float3)(s, 0.0f, 0.0f), (float3)(0.0f, s, 0.0f), (float3)(0.0f, 0.0f, s));
}
MFV_OVL mfv_mat4 mfv_mat4_make(float s) {
  return mfv_mat4_make((float4)(s, 0.0f, 0.0f, 0.0f), (float4)(0.0f, s, 0.0f, 0.0f), (float4)(0.0f, 0.0f, s, 0.0f),
                       (float4)(0.0f, 0.0f, 0.0f, s));
}
MFV_OVL mfv_mat2 mfv_mat2_make(float a, float b, float c, float d) {
  return mfv_mat2_make((float2)(a, b), (float2)(c, d));
}
MFV_OVL mfv_mat3 mfv_mat3_make(float a, float b, float c, float d, float e, float f, float g, float h, float i) {
  return mfv_mat3_make((float3)(a, b, c), (float3)(d, e, f), (float3)(g, h, i));
}
MFV_OVL mfv_mat4 mfv_mat4_make(float a, float b, float c, float d, float e, float f, float g, float h, float i,
                               float j, float k, float l, float m, float n, float o, float p) {
  return mfv_mat4_make((float4)(a, b, c, d), (float4)(e, f, g, h), (float4)(i, j, k, l), (float4)(m, n, o, p));
}
MFV_OVL mfv_mat2 mfv_mat2_make(mfv_mat2 m) { return m; }
MFV_OVL mfv_mat3 mfv_mat3_make(mfv_mat3 m) { return m; }
MFV_OVL mfv_mat4 mfv_mat4_make(mfv_mat4 m) { return m; }
MFV_OVL mfv_mat2 mfv_mat2_make(mfv_mat3 m) { return mfv_mat2_make(m.c[0].xy, m.c[1].xy); }
MFV_OVL mfv_mat2 mfv_mat2_make(mfv_mat4 m) { return mfv_mat2_make(m.c[0].xy, m.c[1].xy); }
MFV_OVL mfv_mat3 mfv_mat3_make(mfv_mat4 m) { return mfv_mat3_make(m.c[0].xyz, m.c[1].xyz, m.c[2].xyz); }
MFV_OVL mfv_mat3 mfv_mat3_make(mfv_mat2 m) {
  return mfv_mat3_make((float3)(m.c[0], 0.0f), (float3)(m.c[1], 0.0f), (float3)(0.0f, 0.0f, 1.0f));
}
MFV_OVL mfv_mat4 mfv_mat4_make(mfv_mat3 m) {
  return mfv_mat4_make((float4)(m.c[0], 0.0f), (float4)(m.c[1], 0.0f), (float4)(m.c[2], 0.0f),
                       (float4)(0.0f, 0.0f, 0.0f, 1.0f));
}
MFV_OVL mfv_mat4 mfv_mat4_make(mfv_mat2 m) { return mfv_mat4_make(mfv_mat3_make(m)); }
MFV_OVL mfv_mat2 mfv_transpose(mfv_mat2 m) {
  return mfv_mat2_make((float2)(m.c[0].x, m.c[1].x), (float2)(m.c[0].y, m.c[1].y));
}
MFV_OVL mfv_mat3 mfv_transpose(mfv_mat3 m) {
  return mfv_mat3_make((float3)(m.c[0].x, m.c[1].x, m.c[2].x), (float3)(m.c[0].y, m.c[1].y, m.c[2].y),
                       (float3)(m.c[0].z, m.c[1].z, m.c[2].z));
}
MFV_OVL mfv_mat4 mfv_transpose(mfv_mat4 m) {
  return mfv_mat4_make((float4)(m.c[0].x, m.c[1].x, m.c[2].x, m.c[3].x), (float4)(m.c[0].y, m.c[1].y, m.c[2].y, m.c[3].y),
                       (float4)(m.c[0].z, m.c[1].z, m.c[2].z, m.c[3].z), (float4)(m.c[0].w, m.c[1].w, m.c[2].w, m.c[3].w));
}
MFV_OVL float2 mfv_mul(mfv_mat2 m, float2 v) { return m.c[0] * v.x + m.c[1] * v.y; }
MFV_OVL float3 mfv_mul(mfv_mat3 m, float3 v) { return m.c[0] * v.x + m.c[1] * v.y + m.c[2] * v.z; }
MFV_OVL float4 mfv_mul(mfv_mat4 m, float4 v) { return m.c[0] * v.x + m.c[1] * v.y + m.c[2] * v.z + m.c[3] * v.w; }
MFV_OVL float2 mfv_mul(float2 v, mfv_mat2 m) { return (float2)(dot(v, m.c[0]), dot(v, m.c[1])); }
MFV_OVL float3 mfv_mul(float3 v, mfv_mat3 m) { return (float3)(dot(v, m.c[0]), dot(v, m.c[1]), dot(v, m.c[2])); }
MFV_OVL float4 mfv_mul(float4 v, mfv_mat4 m) {
  return (float4)(dot(v, m.c[0]), dot(v, m.c[1]), dot(v, m.c[2]), dot(v, m.c[3]));
}
MFV_OVL mfv_mat2 mfv_mul(mfv_mat2 a, mfv_mat2 b) { return mfv_mat2_make(mfv_mul(a, b.c[0]), mfv_mul(a, b.c[1])); }
MFV_OVL mfv_mat3 mfv_mul(mfv_mat3 a, mfv_mat3 b) {
  return mfv_mat3_make(mfv_mul(a, b.c[0]), mfv_mul(a, b.c[1]), mfv_mul(a, b.c[2]));
}
MFV_OVL mfv_mat4 mfv_mul(mfv_mat4 a, mfv_mat4 b) {
  return mfv_mat4_make(mfv_mul(a, b.c[0]), mfv_mul(a, b.c[1]), mfv_mul(a, b.c[2]), mfv_mul(a, b.c[3]));
}
// a matrix and a scalar, and hlsl's mul() (the same products on the rows), for each size
#define MFV_MATRIX_SCALAR(M, V)                                                          \
  MFV_OVL M mfv_mul(M a, float s) {                                                      \
    for (int i = 0; i < (int)(sizeof(a.c) / sizeof(a.c[0])); ++i) a.c[i] = a.c[i] * s;  \
    return a;                                                                            \
  }                                                                                      \
  MFV_OVL M mfv_mul(float s, M a) {                                                      \
    for (int i = 0; i < (int)(sizeof(a.c) / sizeof(a.c[0])); ++i) a.c[i] = s * a.c[i];  \
    return a;                                                                            \
  }                                                                                      \
  MFV_OVL V mfv_hmul(M m, V v) { return mfv_mul(v, m); }                                 \
  MFV_OVL V mfv_hmul(V v, M m) { return mfv_mul(m, v); }                                 \
  MFV_OVL M mfv_hmul(M a, M b) { return mfv_mul(b, a); }                                 \
  MFV_OVL M mfv_hmul(M a, float s) { return mfv_mul(a, s); }                             \
  MFV_OVL M mfv_hmul(float s, M a) { return mfv_mul(s, a); }
MFV_MATRIX_SCALAR(mfv_mat2, float2)
MFV_MATRIX_SCALAR(mfv_mat3, float3)
MFV_MATRIX_SCALAR(mfv_mat4, float4)
#undef MFV_MATRIX_SCALAR
// the other factors of a product chain that holds a matrix, as `*` computes them
#define MFV_MUL_VECTORS(T)                                       \
  MFV_OVL T mfv_mul(T a, T b) { return a * b; }                  \
  MFV_OVL T mfv_mul(T a, float s) { return a * s; }              \
  MFV_OVL T mfv_mul(float s, T a) { return s * a; }              \
  MFV_OVL float mfv_hmul(T a, T b) { return dot(a, b); }         \
  MFV_OVL T mfv_hmul(T a, float s) { return a * s; }             \
  MFV_OVL T mfv_hmul(float s, T a) { return s * a; }
MFV_MUL_VECTORS(float2)
MFV_MUL_VECTORS(float3)
MFV_MUL_VECTORS(float4)
#undef MFV_MUL_VECTORS
MFV_OVL float mfv_mul(float a, float b) { return a * b; }
MFV_OVL float mfv_hmul(float a, float b) { return a * b; }

#pragma clang attribute push(__attribute__((overloadable)), apply_to = function)
#endif

#pragma clang diagnostic push
#pragma clang diagnostic error "-Wundef"
// v.rgb, as the shading languages write it, is OpenCL C 3.0 (and works before)
#pragma clang diagnostic ignored "-Wopencl-unsupported-rgba"
// the suite's one-letter macro R(x) is not the user's
#pragma push_macro("R")
#undef R
