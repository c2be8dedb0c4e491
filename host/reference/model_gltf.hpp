// The glTF 2.0 metallic-roughness BRDF in double (twin of kernels/model_gltf.cl),
// written plainly from the specification's Appendix B formulas. One colour
// channel; p[0..5] = alpha, metallic, base, f0, f0_max, weight as declared in
// host/catalog/models.cpp ("gltf").
#pragma once

#include <glm/vec3.hpp>

namespace mfv::ref {

// f(l, v), l = light, v = view, unit (taken as given, as the other whole
// models: host/reference/models.hpp), n = +z; 0 below either horizon.
double model_gltf(const glm::dvec3& l, const glm::dvec3& v, const double* p);
// KHR_materials_clearcoat over it: p[0..6] = alpha, metallic, base, f0, f0_max,
// clearcoat_alpha, clearcoat ("gltf_clearcoat"; V = l, see kernels/model_gltf.cl).
double model_gltf_clearcoat(const glm::dvec3& l, const glm::dvec3& v, const double* p);
// Exact albedo where known: a dielectric without a specular layer (metallic 0,
// weight 0) is Lambert, E = base; NaN elsewhere.
double albedo_gltf(double cos_l, const double* p);

}  // namespace mfv::ref
