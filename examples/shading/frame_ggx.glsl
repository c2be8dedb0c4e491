// An engine-style GLSL file (written for mfv's tests in the way real-time
// engines write theirs; not copied from any engine) that shades in a
// tangent frame: a TBN matrix built from a rotated tangent, directions
// taken into it by mat3 products on either side, a packed vec4 read back
// with vec3(vec4), function-like macros (one of them over two lines),
// two-argument atan, precision statements and const in parameters.
// Checked as it is, with its adapter at the end:
//   mfv check --brdf examples/shading/frame_ggx.glsl --as ggx/smith_ggx_correlated/schlick --map alpha=roughness^2
// tests/data/shading/frame_ggx_port.cl is its hand port to OpenCL C; the
// two give the same values (tests/test_check_dialects.cpp).
//
// Terms: GGX D (Walter et al. 2007 eq. 33), height-correlated Smith
// visibility (Heitz 2014 eq. 99, as V = G2 / (4 n.l n.v)), Schlick's
// Fresnel (Schlick 1994 eq. 15).
// mfv: param roughness 0.0316 1 default 0.5 perceptual
// mfv: param f0 0 1 default 0.04

#version 300 es
precision highp float;
precision mediump int;

#define PI 3.14159265358979
#define SQ(x) ((x) * (x))
#define SATURATE_DOT(a, b) \
    clamp(dot(a, b), 0.0, 1.0)

const float TANGENT_ROTATION = 0.6435011;  // the tangent's angle in the surface
#ifndef FRAME_TILT
#define FRAME_TILT 0.0  /* the shading normal's tilt (tests: --define FRAME_TILT=0.3) */
#endif

struct Frame {
    mat3 TBN;      // columns: tangent, bitangent, normal
    vec4 packedSpecular;   // f0 in rgb, roughness in a
};

Frame makeFrame(const in vec3 n, float roughness, float f0) {
    float phi = atan(sin(TANGENT_ROTATION), cos(TANGENT_ROTATION));
    vec3 t0 = vec3(cos(phi), sin(phi), 0.0);
    vec3 t = normalize(t0 - n * dot(n, t0));  // Gram-Schmidt against the normal
    vec3 b = cross(n, t);
    Frame f;
    f.TBN = mat3(t, b, n);
    f.packedSpecular = vec4(vec3(f0), roughness);
    return f;
}

float D_GGX(float a, float NoH, float sin2) {
    float a2 = a * a;
    float k = SQ(NoH) + sin2 / a2;
    return 1.0 / (PI * a2 * k * k);
}

float V_SmithGGXCorrelated(float a, const in float NoV, const in float NoL) {
    float a2 = a * a;
    float lv = NoL * sqrt(NoV * NoV * (1.0 - a2) + a2);
    float ll = NoV * sqrt(NoL * NoL * (1.0 - a2) + a2);
    return 0.5 / max(lv + ll, 1e-30);
}

vec3 F_Schlick(const in vec3 f0, float VoH) {
    float f = pow(1.0 - VoH, 5.0);
    return f0 + (vec3(1.0) - f0) * f;
}

vec3 shadeInFrame(const in Frame frame, vec3 l, vec3 v) {
    // world to tangent space: transpose(TBN) * x, written both ways engines write it
    mat3 toLocal = transpose(frame.TBN);
    vec3 L = toLocal * l;
    vec3 V = v * frame.TBN;
    mat3 I = toLocal * frame.TBN;  // the identity, up to rounding
    if (L.z <= 0.0 || V.z <= 0.0) return vec3(0.0);
    vec3 s = L + V;
    float len = length(s);
    vec3 H = s / len;
    float a = SQ(frame.packedSpecular.a);
    float D = D_GGX(a, H.z, H.x * H.x + H.y * H.y);
    float Vis = V_SmithGGXCorrelated(a, V.z, L.z);
    vec3 F = F_Schlick(vec3(frame.packedSpecular), min(0.5 * len, 1.0));
    return D * Vis * F * SATURATE_DOT(I[2], vec3(0.0, 0.0, 1.0));
}

vec3 brdf(vec3 wi, vec3 wo, float params[6]) {
    Frame frame = makeFrame(normalize(vec3(FRAME_TILT, 0.0, 1.0)), params[0], params[1]);
    return shadeInFrame(frame, wi, wo);
}

float D(vec3 m, float params[6]) {
    if (m.z <= 0.0) return 0.0;
    return D_GGX(SQ(params[0]), m.z, m.x * m.x + m.y * m.y);
}
