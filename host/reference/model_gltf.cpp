#include "reference/model_gltf.hpp"

#include <cmath>

namespace mfv::ref {

double gltf_pbr(const GltfChannel& p, const Shading& c) {
  if (c.NoL <= 0.0 || c.NoV <= 0.0) return 0.0;  // χ⁺: no reflection below the horizon
  // cosines that rounded above 1 are the normal itself (seed 000)
  const double NoL = std::min(c.NoL, 1.0), NoV = std::min(c.NoV, 1.0), NoH = std::min(c.NoH, 1.0), VoH = c.VoH;
  const double a2 = p.alpha * p.alpha;
  // Appendix B.3.2: D = α² χ⁺(n·h) / (π ((n·h)²(α² − 1) + 1)²)
  if (NoH <= 0.0) return 0.0;
  const double k = NoH * NoH * (a2 - 1.0) + 1.0;
  const double D = a2 / (M_PI * k * k);
  // Appendix B.3.2: Vis = G / (4 |n·l| |n·v|) for the height-correlated Smith G
  // = 1 / (2 (|n·v| √(α² + (1 − α²)(n·l)²) + |n·l| √(α² + (1 − α²)(n·v)²)))
  const double vis = 1.0 / (2.0 * (NoV * std::sqrt(a2 + (1.0 - a2) * NoL * NoL) +
                                   NoL * std::sqrt(a2 + (1.0 - a2) * NoV * NoV)));
  const double specular = D * vis;
  const double fw = std::pow(1.0 - VoH, 5.0);
  // KHR_materials_specular fresnel_mix: layer weighted by weight·fr, base by 1 − weight·max_rgb(fr)
  const double fr = p.f0 + (1.0 - p.f0) * fw;
  const double fr_max = p.f0_max + (1.0 - p.f0_max) * fw;
  const double dielectric = (1.0 - p.weight * fr_max) * p.base / M_PI + p.weight * fr * specular;
  // B.3.4 conductor_fresnel with f0 = baseColor
  const double metal = specular * (p.base + (1.0 - p.base) * fw);
  // B.3.5 material = mix(dielectric_brdf, metal_brdf, metallic)
  return (1.0 - p.metallic) * dielectric + p.metallic * metal;
}

double gltf_pbr(const GltfChannel& p, const glm::dvec3& wi, const glm::dvec3& wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return 0.0;  // below the horizon; also keeps l + v != 0
  return gltf_pbr(p, shading_from(wi, wo));
}

}  // namespace mfv::ref
