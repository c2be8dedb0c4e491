// An engine-style GLSL sheen lobe (written for mfv's tests; not copied from
// any engine), checked as it is with its adapter at the end:
//   mfv check --brdf examples/shading/sheen.glsl
// Charlie sheen distribution (Estevez and Kulla 2017, eq. 2) and Neubelt and
// Pettineo's visibility 1 / (4 (n.l + n.v - n.l n.v)) (2013, "Crafting a
// next-gen material pipeline for The Order: 1886").
// mfv: param sheenRoughness 0.3 1 default 0.5 roughness
// mfv: param sheenColor 0 1 default 1

const float PI = 3.14159265358979;

float D_Charlie(float roughness, float NoH) {
    float invAlpha = 1.0 / roughness;
    float cos2h = NoH * NoH;
    float sin2h = max(1.0 - cos2h, 0.0078125);  // 2^-7: keeps the power finite in fp16 engines
    return (2.0 + invAlpha) * pow(sin2h, invAlpha * 0.5) / (2.0 * PI);
}

float V_Neubelt(float NoV, float NoL) {
    return 1.0 / max(4.0 * (NoL + NoV - NoL * NoV), 1e-30);  // no infinity where both cosines underflow
}

vec3 sheenLobe(vec3 sheenColor, float roughness, float NoV, float NoL, float NoH) {
    return sheenColor * (D_Charlie(roughness, NoH) * V_Neubelt(NoV, NoL));
}

vec3 brdf(vec3 wi, vec3 wo, float params[6]) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return vec3(0.0);
    vec3 h = normalize(wi + wo);
    return sheenLobe(vec3(params[1]), params[0], wo.z, wi.z, h.z);
}
