// The assembled reference BRDF, in double with GLM (twin of kernels/brdf.cl).
#pragma once

#include "catalog/catalog.hpp"
#include "catalog/models.hpp"

#include <glm/vec3.hpp>

namespace mfv::ref {

// One BRDF: a D, G and F term with their native parameters, plus a Lambert
// diffuse albedo kd (0 for a pure microfacet BRDF).
struct BrdfSpec {
  const Term* d = nullptr;
  const Term* g = nullptr;
  const Term* f = nullptr;
  double pd = 0, pg = 0, f0 = 0, f1 = 0, kd = 0;
  // A whole model instead of D x G x F: its p[0..5] are pd, pg, f0, f1, kd, p5.
  const Model* model = nullptr;
  double p5 = 0;
};

// The cosines a microfacet BRDF depends on, formed from the directions.
struct Shading {
  double NoL, NoV, NoH, VoH;
};

Shading shading_from(const glm::dvec3& wi, const glm::dvec3& wo);  // n = +z
double brdf(const BrdfSpec& s, const Shading& c);
double brdf(const BrdfSpec& s, const glm::dvec3& wi, const glm::dvec3& wo);

}  // namespace mfv::ref
