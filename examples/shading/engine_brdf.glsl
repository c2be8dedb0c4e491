// An engine-style GLSL shading library (written for mfv's tests in the way
// real-time engines write theirs; not copied from any engine). It is checked
// as it is: examples/shading/check_engine.glsl is the adapter.
//
// Terms: GGX D (Walter et al. 2007 eq. 33), height-correlated Smith
// visibility (Heitz 2014 eq. 99, as V = G2 / (4 n.l n.v)), Schlick's Fresnel
// with f90 (Schlick 1994 eq. 15), a Lambert diffuse.

#version 450
precision highp float;

#ifndef SPECULAR_QUALITY
#define SPECULAR_QUALITY 1  /* 0: fast, 1: reference */
#endif

const float PI = 3.14159265358979;
const float MIN_ROUGHNESS = 0.0001;

struct PixelParams {
    vec3 diffuseColor;
    float roughness;     // perceptual
    float alpha;         // roughness^2
    vec3 f0;
    float f90;
};

struct LightDots { float NoL; float NoV; float NoH; float LoH; };

float sq(float x) { return x * x; }
float saturate(float x) { return clamp(x, 0.0, 1.0); }

// "pow5" written the way shaders do
float pow5(float x) {
    float x2 = x * x;
    return x2 * x2 * x;
}

/* GGX / Trowbridge-Reitz normal distribution, with the cancellation-free
   form of 1 - NoH^2 from the half vector's components (the caller passes
   the sine squared). */
float D_GGX(float alpha, float NoH, float sin2) {
    float a2 = alpha * alpha;
    float k = NoH * NoH + sin2 / a2;
    return 1.0 / (PI * a2 * k * k);
}

float V_SmithGGXCorrelated(float alpha, float NoV, float NoL) {
    float a2 = alpha * alpha;
#if SPECULAR_QUALITY == 1
    float lv = NoL * sqrt(NoV * NoV * (1.0 - a2) + a2);
    float ll = NoV * sqrt(NoL * NoL * (1.0 - a2) + a2);
    return 0.5 / max(lv + ll, 1e-30);  // both cosines underflowing: large, not infinite
#else
    return 0.5 / mix(2.0 * NoL * NoV, NoL + NoV, alpha);
#endif
}

vec3 F_Schlick(const in vec3 f0, float f90, float VoH) {
    return f0 + (vec3(f90) - f0) * pow5(1.0 - VoH);
}

void computeDots(const in vec3 l, const in vec3 v, out LightDots dots, out float sin2) {
    vec3 s = l + v;
    float len = length(s);
    vec3 h = s / len;
    dots = LightDots(l.z, v.z, h.z, min(0.5 * len, 1.0));
    sin2 = (h.x * h.x + h.y * h.y);
}

void specularLobe(const PixelParams pixel, const LightDots dots, float sin2, inout vec3 color) {
    float D = D_GGX(pixel.alpha, dots.NoH, sin2);
    float V = V_SmithGGXCorrelated(pixel.alpha, dots.NoV, dots.NoL);
    vec3 F = F_Schlick(pixel.f0, pixel.f90, dots.LoH);
    color += (D * V) * F;
}

vec3 surfaceShading(const PixelParams pixel, vec3 l, vec3 v) {
    if (l.z <= 0.0 || v.z <= 0.0) return vec3(0.0);
    LightDots dots;
    float sin2;
    computeDots(l, v, dots, sin2);
    vec3 color = pixel.diffuseColor * (1.0 / PI);
    specularLobe(pixel, dots, sin2, color);
    return color;
}
