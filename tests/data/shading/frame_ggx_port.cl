// The hand ports of examples/shading/frame_ggx.glsl (PORT_HLSL 0) and
// frame_ggx.hlsl (--define PORT_HLSL=1) to OpenCL C, written from each
// language's rules: GLSL 4.60's mat3 is column-major, m * v = sum v_i col_i,
// v * m = (v . col_i); HLSL's float3x3(T, B, N) holds rows, mul(M, v) =
// (row_i . v), mul(v, M) = sum v_i row_i; atan(y, x) = atan2, saturate =
// clamp to [0, 1], lerp(x, y, a) = x + (y - x) a, min/max of floats as
// fmin/fmax, unsuffixed literals in float. tests/test_check_dialects.cpp
// checks that mfv check gives each file and its port the same values.
// Terms: GGX D (Walter et al. 2007 eq. 33), height-correlated Smith
// visibility (Heitz 2014 eq. 99), Schlick's Fresnel (Schlick 1994 eq. 15).
// mfv: param roughness 0.0316 1 default 0.5 perceptual
// mfv: param f0 0 1 default 0.04

#ifndef PORT_HLSL
#define PORT_HLSL 0
#endif
#ifndef FRAME_TILT
#define FRAME_TILT 0.0f
#endif
#define PORT_PI 3.14159265358979f
#define SQ(x) ((x) * (x))

float port_d_ggx(float a, float NoH, float sin2) {
  float a2 = a * a;
  float k = SQ(NoH) + sin2 / a2;
  return 1.0f / (PORT_PI * a2 * k * k);
}

float port_v_smith(float a, float NoV, float NoL) {
  float a2 = a * a;
  float lv = NoL * sqrt(NoV * NoV * (1.0f - a2) + a2);
  float ll = NoV * sqrt(NoL * NoL * (1.0f - a2) + a2);
  return 0.5f / fmax(lv + ll, 1e-30f);
}

float3 brdf(float3 wi, float3 wo, const float* params) {
#if PORT_HLSL
  float3 n = (float3)(FRAME_TILT, 0.0f, 1.0f);
  n = n * rsqrt(dot(n, n));
#else
  float3 n = normalize((float3)(FRAME_TILT, 0.0f, 1.0f));
#endif
  float phi = atan2(sin(0.6435011f), cos(0.6435011f));
  float3 t0 = (float3)(cos(phi), sin(phi), 0.0f);
  float3 t = normalize(t0 - n * dot(n, t0));
  float3 b = cross(n, t);
  // the rows of transpose(TBN) (t, b, n as columns): (t.x, b.x, n.x), (t.y, b.y, n.y), (t.z, b.z, n.z)
  float3 r0 = (float3)(t.x, b.x, n.x), r1 = (float3)(t.y, b.y, n.y), r2 = (float3)(t.z, b.z, n.z);
#if PORT_HLSL
  float3 L = (float3)(dot(wi, t), dot(wi, b), dot(wi, n));  // mul(TB, L), TB's rows t, b, n
  float3 V = r0 * wo.x + r1 * wo.y + r2 * wo.z;              // mul(V, transpose(TB))
  float3 I2 = t * t.z + b * b.z + n * n.z;  // row 2 of mul(transpose(TB), TB) = sum_k row_k^T row_k
#else
  float3 L = r0 * wi.x + r1 * wi.y + r2 * wi.z;              // transpose(TBN) * l
  float3 V = (float3)(dot(wo, t), dot(wo, b), dot(wo, n));  // v * TBN
  float3 I2 = r0 * n.x + r1 * n.y + r2 * n.z;  // transpose(TBN) * TBN, third column
#endif
  if (L.z <= 0.0f || V.z <= 0.0f) return (float3)(0.0f);
  float3 s = L + V;
  float len = length(s);
  float3 H = s / len;
  float a = SQ(params[0]);
  float D = port_d_ggx(a, H.z, H.x * H.x + H.y * H.y);
  float Vis = port_v_smith(a, V.z, L.z);
  float3 f0 = (float3)(params[1]);
  float f = pow(1.0f - fmin(0.5f * len, 1.0f), 5.0f);
  float3 F = f0 + ((float3)(1.0f) - f0) * f;
#if PORT_HLSL
  return D * Vis * F * clamp(dot(I2, (float3)(0.0f, 0.0f, 1.0f)), 0.0f, 1.0f);
#else
  return D * Vis * F * fmin(fmax(dot(I2, (float3)(0.0f, 0.0f, 1.0f)), 0.0f), 1.0f);
#endif
}

float D(float3 m, const float* params) {
  if (m.z <= 0.0f) return 0.0f;
  return port_d_ggx(SQ(params[0]), m.z, m.x * m.x + m.y * m.y);
}
