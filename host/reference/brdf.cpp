#include "reference/brdf.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace mfv::ref {

Shading shading_from(const glm::dvec3& wi_in, const glm::dvec3& wo_in) {
  // f is a function of directions: float inputs are unit only to ~1e-7, and
  // for nearly opposite l and v that slack is larger than |l + v|^2 itself,
  // so the directions are made unit in double before anything else.
  const glm::dvec3 wi = glm::normalize(wi_in), wo = glm::normalize(wo_in);
  // seed 000: H = (L + V) / |L + V|. For unit L, V: V·H = (1 + L·V) / |L + V|
  // = |L + V| / 2, which keeps full precision where L and V are nearly
  // opposite and the dot product V·H would cancel.
  const glm::dvec3 sum = wi + wo;
  const double len = glm::length(sum);
  const glm::dvec3 h = sum / len;
  return {wi.z, wo.z, h.z, std::min(0.5 * len, 1.0), h.x * h.x + h.y * h.y};  // n = +z
}

double brdf(const BrdfSpec& s, const Shading& c) {
  if (c.NoL <= 0.0 || c.NoV <= 0.0) return 0.0;
  return brdf_of_terms(s, c, eval_d_iso(s, c), s.f->ref_f(c.VoH, s.f0, s.f1), eval_g_iso(s, c));
}

double brdf_of_terms(const BrdfSpec& s, const Shading& c, double D, double F, double G) {
  // seed 000: BRDF = Kd/π + D(H) F(L,H) G(L,V,H) / (4 (L·N)(V·N))
  if (c.NoL <= 0.0 || c.NoV <= 0.0) return 0.0;
  return s.kd / M_PI + D * F * G / (4.0 * c.NoL * c.NoV);
}

double eval_d_iso(const BrdfSpec& s, const Shading& c) {
  return c.sin2H >= 0.0 ? eval_d_cs(s, c.NoH, c.sin2H) : s.d->ref_d(c.NoH, s.pd);
}

double eval_g_iso(const BrdfSpec& s, const Shading& c) { return s.g->ref_g(c.NoL, c.NoV, c.NoH, c.VoH, s.pg); }

double eval_d(const BrdfSpec& s, const glm::dvec3& m) {
  if (s.aniso() && s.d->aniso) return s.d->ref_d_aniso(m, s.pd, s.pd2);
  const double len2 = glm::dot(m, m);
  return eval_d_cs(s, m.z / std::sqrt(len2), (m.x * m.x + m.y * m.y) / len2);
}

double eval_d_cs(const BrdfSpec& s, double c, double s2) {
  if (s.d->ref_d_cs && c > 0.0) return s.d->ref_d_cs(c * c, s2, s.pd);
  return s.d->ref_d(c, s.pd);
}

double eval_g(const BrdfSpec& s, const glm::dvec3& wi, const glm::dvec3& wo, const Shading& c) {
  if (s.aniso() && s.g->aniso) return s.g->ref_g_aniso(wi, wo, c.VoH, s.pg, s.pg2);
  return s.g->ref_g(c.NoL, c.NoV, c.NoH, c.VoH, s.pg);
}

double eval_g1(const BrdfSpec& s, const glm::dvec3& v) {
  if (s.aniso() && s.g->aniso) return s.g->ref_g1_aniso(v, s.pg, s.pg2);
  return s.g->ref_g1(v.z / glm::length(v), s.pg);
}

double brdf(const BrdfSpec& s, const glm::dvec3& wi, const glm::dvec3& wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return 0.0;  // below the horizon; also keeps L + V != 0
  if (!s.aniso()) return brdf(s, shading_from(wi, wo));
  // seed 000's BRDF with the anisotropic D(h) and G(l, v) (unit directions)
  const glm::dvec3 l = glm::normalize(wi), v = glm::normalize(wo);
  const Shading c = shading_from(l, v);
  const glm::dvec3 h = glm::normalize(l + v);
  return s.kd / M_PI + eval_d(s, h) * s.f->ref_f(c.VoH, s.f0, s.f1) * eval_g(s, l, v, c) / (4.0 * c.NoL * c.NoV);
}

}  // namespace mfv::ref
