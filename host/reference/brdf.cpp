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
  return {wi.z, wo.z, h.z, std::min(0.5 * len, 1.0)};  // n = +z
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
