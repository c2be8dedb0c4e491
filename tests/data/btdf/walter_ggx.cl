// A rough dielectric as a renderer writes it, for mfv check's transmission
// checks (tests/test_check_btdf.cpp): Walter et al. 2007 with GGX's D, the
// height-correlated Smith G2 and the exact dielectric Fresnel, written from
// the paper for the tests (not from kernels/). Local frame n = +z, wi the
// light, wo the view, both pointing away from the surface. eta =
// eta_below / eta_above. Radiance form: btdf carries eta_o^2 (eq. 21).
// mfv: param alpha 0.02 1 default 0.3 roughness
// mfv: param eta 1.2 2.5 default 1.5 eta

// Walter et al. 2007 eq. 33 (GGX), written with |m| = 1: alpha^2 / (pi (sin^2 + alpha^2 cos^2)^2)
float D_ggx(float3 m, float a) {
  if (m.z <= 0.0f) return 0.0f;
  float a2 = a * a;
  float t = m.x * m.x + m.y * m.y + a2 * m.z * m.z;
  return a2 / (M_PI_F * t * t);
}

// Smith Lambda of GGX (Heitz 2014 eq. 72), tan^2 = (x^2 + y^2) / z^2, for either side
float Lambda_ggx(float3 v, float a) {
  float z2 = v.z * v.z;
  if (z2 <= 0.0f) return INFINITY;
  float t = a * a * (v.x * v.x + v.y * v.y) / z2;
  if (isinf(t)) return 0.5f * a * sqrt(v.x * v.x + v.y * v.y) / fabs(v.z);  // a tan / 2 where t overflows
  return t / (2.0f * (1.0f + sqrt(1.0f + t)));  // (-1 + sqrt(1 + t)) / 2, no cancellation
}

float G2_correlated(float3 wi, float3 wo, float a) {
  return 1.0f / (1.0f + Lambda_ggx(wi, a) + Lambda_ggx(wo, a));
}

// Walter et al. 2007 eq. 22: the exact dielectric Fresnel at cos c, relative index n seen from the incident side
float F_dielectric(float c, float n) {
  float g2 = n * n - 1.0f + c * c;
  if (g2 <= 0.0f) return 1.0f;  // total internal reflection
  float g = sqrt(g2);
  float a = (g - c) / (g + c);
  float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
  return 0.5f * a * a * (1.0f + b * b);
}

// eq. 20: reflection on either side
float3 brdf(float3 wi, float3 wo, const float* params) {
  float a = params[0], eta = params[1];
  if (wi.z * wo.z <= 0.0f) return (float3)(0.0f);
  float n = wi.z > 0.0f ? eta : 1.0f / eta;
  float3 h = normalize(wi + wo);
  if (h.z < 0.0f) h = -h;
  float F = F_dielectric(fabs(dot(wi, h)), n);
  // one cosine at a time: (n.i)(n.o) underflows near the horizon
  float v = F * G2_correlated(wi, wo, a) * D_ggx(h, a) / (4.0f * fabs(wi.z)) / fabs(wo.z);
  return (float3)(v);
}

// eq. 21 with h of eq. 16
float3 btdf(float3 wi, float3 wo, const float* params) {
  float a = params[0], eta = params[1];
  if (wi.z * wo.z >= 0.0f) return (float3)(0.0f);
  float ei = wi.z > 0.0f ? 1.0f : eta;  // the index on wi's side
  float eo = wi.z > 0.0f ? eta : 1.0f;  // and on wo's
  float3 s = ei * wi + eo * wo;
  float len = length(s);
  if (!(len > 0.0f)) return (float3)(0.0f);
  float3 h = -s / len;
  if (h.z < 0.0f) h = -h;
  float ih = dot(wi, h), oh = dot(wo, h);
  // refraction: each direction on its own side of the facet as of the surface
  if (ih * wi.z <= 0.0f || oh * wo.z <= 0.0f) return (float3)(0.0f);
  float F = F_dielectric(fabs(ih), eo / ei);
  float den = ei * ih + eo * oh;
  float v = fabs(ih / wi.z) * fabs(oh / wo.z) * eo * eo * (1.0f - F) * G2_correlated(wi, wo, a) * D_ggx(h, a) /
            (den * den);
  return (float3)(v);
}

// optional: transmission_masking (and d_norm, masking)
float D(float3 m, const float* params) { return D_ggx(m, params[0]); }

// Smith G1 of GGX with its orientation test chi+((v.m)/(v.n)), from either side
float G1(float3 v, float3 m, const float* params) {
  if (dot(v, m) * v.z <= 0.0f) return 0.0f;
  return 1.0f / (1.0f + Lambda_ggx(v, params[0]));
}
