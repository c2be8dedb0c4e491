// tests/data/btdf/walter_ggx.cl as a GLSL engine writes it: one bsdf for
// both hemispheres with the flip at the top (pbrt-v4's DielectricBxDF::f):
// light from below is light from above with both directions mirrored and
// the relative index inverted. mfv check --dialect glsl (from the extension).
// Radiance form: the transmitted part carries (eta_o / eta_i)^2 (Walter et
// al. 2007 eq. 21 in relative indices).
// mfv: param roughness 0.15 1 default 0.5 perceptual
// mfv: param ior 1.2 2.5 default 1.5 eta
const float PI = 3.14159265358979;

float D_GGX(vec3 m, float a) {
    if (m.z <= 0.0) return 0.0;
    float a2 = a * a;
    float t = dot(m.xy, m.xy) + a2 * m.z * m.z;
    return a2 / (PI * t * t);
}

float Lambda_GGX(vec3 v, float a) {
    float z2 = v.z * v.z;
    if (z2 <= 0.0) return 1e30;
    float t = a * a * dot(v.xy, v.xy) / z2;
    if (isinf(t)) return 0.5 * a * length(v.xy) / abs(v.z);
    return t / (2.0 * (1.0 + sqrt(1.0 + t)));
}

float F_Dielectric(float c, float n) {
    float g2 = n * n - 1.0 + c * c;
    if (g2 <= 0.0) return 1.0;
    float g = sqrt(g2);
    float a = (g - c) / (g + c);
    float b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

vec3 bsdf(vec3 wi, vec3 wo, float params[6]) {
    float a = params[0] * params[0];
    float eta = params[1];
    if (wi.z < 0.0) {
        wi = -wi;
        wo = -wo;
        eta = 1.0 / eta;
    }
    if (wi.z < 1e-20 || abs(wo.z) < 1e-20) return vec3(0.0);  // at the horizon: masked (and 1/cos overflows)
    float G = 1.0 / (1.0 + Lambda_GGX(wi, a) + Lambda_GGX(wo, a));
    if (wo.z > 0.0) {
        vec3 h = normalize(wi + wo);
        float F = F_Dielectric(dot(wi, h), eta);
        return vec3(F * G * D_GGX(h, a) / (4.0 * wi.z) / wo.z);
    }
    vec3 s = wi + eta * wo;
    float len = length(s);
    if (!(len > 0.0)) return vec3(0.0);
    vec3 h = -s / len;
    if (h.z < 0.0) h = -h;
    float ih = dot(wi, h);
    float oh = dot(wo, h);
    if (ih <= 0.0 || oh >= 0.0) return vec3(0.0);
    float F = F_Dielectric(ih, eta);
    float den = ih + eta * oh;
    return vec3((ih / wi.z) * (oh / wo.z) * eta * eta * (1.0 - F) * G * D_GGX(h, a) / (den * den));
}
