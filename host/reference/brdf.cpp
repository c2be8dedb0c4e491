#include "reference/brdf.hpp"

#include <glm/geometric.hpp>

#include <cmath>

namespace mfv::ref {

Shading shading_from(const glm::dvec3& wi, const glm::dvec3& wo) {
  const glm::dvec3 n(0.0, 0.0, 1.0);
  const glm::dvec3 h = glm::normalize(wi + wo);  // seed 000: H = (L + V) / |L + V|
  return {glm::dot(n, wi), glm::dot(n, wo), glm::dot(n, h), glm::dot(wo, h)};
}

double brdf(const BrdfSpec& s, const Shading& c) {
  // seed 000: BRDF = Kd/π + D(H) F(L,H) G(L,V,H) / (4 (L·N)(V·N))
  if (c.NoL <= 0.0 || c.NoV <= 0.0) return 0.0;
  const double D = s.d->ref_d(c.NoH, s.pd);
  const double F = s.f->ref_f(c.VoH, s.f0, s.f1);
  const double G = s.g->ref_g(c.NoL, c.NoV, c.NoH, c.VoH, s.pg);
  return s.kd / M_PI + D * F * G / (4.0 * c.NoL * c.NoV);
}

double brdf(const BrdfSpec& s, const glm::dvec3& wi, const glm::dvec3& wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return 0.0;  // below the horizon; also keeps L + V != 0
  return brdf(s, shading_from(wi, wo));
}

}  // namespace mfv::ref
