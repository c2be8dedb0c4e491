// The glTF 2.0 metallic-roughness BRDF in double (twin of kernels/model_gltf.cl),
// written plainly from the specification's Appendix B formulas.
#pragma once

#include "reference/brdf.hpp"

#include <glm/vec3.hpp>

#include <cstdint>

namespace mfv::ref {

// IntegralSpec::model of the glTF model (MFV_MODEL_GLTF in kernels/model_gltf.cl).
constexpr uint32_t kModelGltf = 1000;

// One colour channel; see kernels/model_gltf.cl for the meaning of each.
struct GltfChannel {
  double alpha = 0.25, metallic = 0, base = 1, f0 = 0.04, f0_max = 0.04, weight = 1;
};

double gltf_pbr(const GltfChannel& p, const glm::dvec3& wi, const glm::dvec3& wo);
double gltf_pbr(const GltfChannel& p, const Shading& c);  // from the cosines (shading_from)

}  // namespace mfv::ref
