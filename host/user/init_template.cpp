#include "user/init_template.hpp"

#include "util/error.hpp"

#include <fmt/format.h>

namespace mfv {

namespace {

// Each template checks as it is (tests/test_check_dialects.cpp): a GGX with
// height-correlated Smith visibility and Schlick's Fresnel stands where the
// engine's function goes.
const char* kGlsl = R"(// mfv check adapter (GLSL): maps mfv's brdf(wi, wo, params) onto your
// engine's shading function. Check it with
//   mfv check --include path/to/your_brdf.glsl --brdf this_file.glsl \
//             --as ggx/smith_ggx_correlated/schlick --map alpha=roughness^2
// (--as and --map only if the code claims a catalog model: mfv list terms).
//
// Frame: n = +z; wi = light, wo = view, both pointing away from the surface.
// Your files compile as they are: vecN, constructors, overloads, structs,
// out/inout, file-scope const, GLSL built-ins (docs/cli/check.md "GLSL").
// Configuration macros your file tests: --define NAME=VALUE (an #if on an
// undefined name is an error).
//
// One `mfv: param NAME LO HI [default V] [roughness|perceptual]` line per
// parameter, params[k] in this order (at most 6):
// mfv: param roughness 0.0316 1 default 0.5 perceptual
// mfv: param f0 0 1 default 0.04

// ---- replace this block with your engine's function (or --include its file)
const float PI = 3.14159265358979;
float engineSpecular(vec3 n, vec3 l, vec3 v, float roughness, vec3 f0, out vec3 F) {
    float a = roughness * roughness, a2 = a * a;
    vec3 h = normalize(l + v);
    float NoL = dot(n, l), NoV = dot(n, v), NoH = dot(n, h), VoH = dot(v, h);
    float d = NoH * NoH * (a2 - 1.0) + 1.0;
    float D = a2 / (PI * d * d);
    float V = 0.5 / (NoL * sqrt(NoV * NoV * (1.0 - a2) + a2) + NoV * sqrt(NoL * NoL * (1.0 - a2) + a2));
    F = f0 + (1.0 - f0) * pow(1.0 - VoH, 5.0);
    return D * V;
}
// ---- end of the engine's part

// The adapter: mfv calls this (RGB, cosine not included).
vec3 brdf(vec3 wi, vec3 wo, float params[6]) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return vec3(0.0);
    vec3 F;
    float DV = engineSpecular(vec3(0.0, 0.0, 1.0), wi, wo, params[0], vec3(params[1]), F);
    return DV * F;
}
)";

const char* kHlsl = R"(// mfv check adapter (HLSL): maps mfv's brdf(wi, wo, params) onto your
// engine's shading function. Check it with
//   mfv check --include path/to/your_brdf.hlsl --brdf this_file.hlsl \
//             --as ggx/smith_ggx_correlated/schlick --map alpha=roughness^2
// (--as and --map only if the code claims a catalog model: mfv list terms).
//
// Frame: n = +z; wi = light, wo = view, both pointing away from the surface.
// Your files compile as they are: floatN, constructors, overloads, structs,
// out/inout, static const, HLSL intrinsics (lerp, saturate, rcp, frac, ...;
// docs/cli/check.md "HLSL"). Configuration macros: --define NAME=VALUE.
//
// One `mfv: param NAME LO HI [default V] [roughness|perceptual]` line per
// parameter, params[k] in this order (at most 6):
// mfv: param roughness 0.0316 1 default 0.5 perceptual
// mfv: param f0 0 1 default 0.04

// ---- replace this block with your engine's function (or --include its file)
static const float PI = 3.14159265358979f;
float EngineSpecular(float3 N, float3 L, float3 V, float Roughness, float3 F0, out float3 F)
{
    float a = Roughness * Roughness, a2 = a * a;
    float3 H = normalize(L + V);
    float NoL = saturate(dot(N, L)), NoV = saturate(dot(N, V)), NoH = saturate(dot(N, H));
    float VoH = saturate(dot(V, H));
    float d = (NoH * a2 - NoH) * NoH + 1;
    float D = a2 / (PI * d * d);
    float Vis = 0.5 * rcp(NoL * sqrt(NoV * (NoV - NoV * a2) + a2) + NoV * sqrt(NoL * (NoL - NoL * a2) + a2));
    F = F0 + (1 - F0) * pow(1 - VoH, 5);
    return D * Vis;
}
// ---- end of the engine's part

// The adapter: mfv calls this (RGB, cosine not included).
float3 brdf(float3 wi, float3 wo, float params[6])
{
    if (wi.z <= 0 || wo.z <= 0) return float3(0, 0, 0);
    float3 F;
    float DV = EngineSpecular(float3(0, 0, 1), wi, wo, params[0], float3(params[1], params[1], params[1]), F);
    return DV * F;
}
)";

}  // namespace

std::string init_template(const std::string& dialect) {
  if (dialect == "glsl") return kGlsl;
  if (dialect == "hlsl") return kHlsl;
  throw Error(fmt::format("--init {}: name glsl or hlsl", dialect));
}

}  // namespace mfv
