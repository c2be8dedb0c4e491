// A float32 GGX written the textbook way, as real-time engines ship it
// (written for mfv's tests; not copied from any engine): D as
// a^2 / (pi ((n.h)^2 (a^2 - 1) + 1)^2), which cancels in float for a narrow
// lobe, the height-correlated Smith visibility and Schlick's Fresnel at v.h.
// The formula is right: its double twin agrees with the catalog's
// ggx/smith_ggx_correlated/schlick, and what the float code adds is float
// conditioning (docs/cli/check.md "The double twin").
//   mfv check --brdf examples/shading/textbook_ggx.glsl --as ggx/smith_ggx_correlated/schlick --map alpha=roughness^2
// mfv: param roughness 0.0316 1 default 0.5 perceptual
// mfv: param f0 0 1 default 0.04

const float PI = 3.14159265359;

// Walter et al. 2007 eq. 33, in the expanded form engines use
float D_GGX(float NoH, float a) {
    float a2 = a * a;
    float f = (NoH * a2 - NoH) * NoH + 1.0;
    return a2 / (PI * f * f);
}

// Heitz 2014 eq. 99 as V = G2 / (4 n.l n.v)
float V_SmithGGXCorrelated(float NoV, float NoL, float a) {
    float a2 = a * a;
    float GGXL = NoV * sqrt((-NoL * a2 + NoL) * NoL + a2);
    float GGXV = NoL * sqrt((-NoV * a2 + NoV) * NoV + a2);
    return 0.5 / max(GGXV + GGXL, 1e-30);  // both cosines underflowing: large, not infinite
}

// Schlick 1994 eq. 15
vec3 F_Schlick(vec3 f0, float VoH) {
    float f = pow(1.0 - VoH, 5.0);
    return f + f0 * (1.0 - f);
}

vec3 brdf(vec3 wi, vec3 wo, float params[6]) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return vec3(0.0);
    float a = params[0] * params[0];
    vec3 h = normalize(wi + wo);
    float NoH = clamp(h.z, 0.0, 1.0);
    float VoH = clamp(dot(wo, h), 0.0, 1.0);
    return D_GGX(NoH, a) * V_SmithGGXCorrelated(wo.z, wi.z, a) * F_Schlick(vec3(params[1]), VoH);
}

float D(vec3 m, float params[6]) {
    if (m.z <= 0.0) return 0.0;
    return D_GGX(m.z, params[0] * params[0]);
}
