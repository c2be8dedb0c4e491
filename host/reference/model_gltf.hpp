// The glTF 2.0 metallic-roughness BRDF in double (twin of kernels/model_gltf.cl),
// written plainly from the specification's Appendix B formulas. One colour
// channel; p[0..5] = alpha, metallic, base, f0, f0_max, weight as declared in
// host/catalog/models.cpp ("gltf").
#pragma once

#include "reference/models.hpp"

#include <vector>

namespace mfv::ref {

// f(l, v), l = light, v = view, unit (taken as given, as the other whole
// models: host/reference/models.hpp), n = +z; 0 below either horizon.
ModelFn model_gltf;
// KHR_materials_clearcoat over it: p[0..6] = alpha, metallic, base, f0, f0_max,
// clearcoat_alpha, clearcoat ("gltf_clearcoat"; V = l, see kernels/model_gltf.cl).
ModelFn model_gltf_clearcoat;
// The same over the anisotropic base: p[0..6] = alpha_t, metallic, base, f0,
// clearcoat_alpha, clearcoat, alpha_b ("gltf_clearcoat_aniso").
ModelFn model_gltf_clearcoat_aniso;
// KHR_materials_sheen over it: p[0..6] = alpha, metallic, base, f0, sheen_alpha,
// sheen, sheen_others ("gltf_sheen"; see kernels/model_gltf.cl).
ModelFn model_gltf_sheen;
// KHR_materials_transmission, thin-walled: p[0..4] = alpha, metallic, base,
// f0, transmission ("gltf_transmission"): the BSDF folded onto v's hemisphere,
// f(l, v) + f(l, v mirrored below), so that its albedo is R + T.
ModelFn model_gltf_transmission;
// E_sheen(mu, alpha) from the table kernels/model_gltf.cl holds (parsed from
// its text, bilinear in (mu, log10 alpha), written here independently).
double sheen_albedo_table(double mu, double alpha);
// The table's numbers, [alpha][mu], and its side N.
const std::vector<double>& sheen_table_values();
int sheen_table_side();
// Exact albedo where known: a dielectric without a specular layer (metallic 0,
// weight 0) is Lambert, E = base; NaN elsewhere.
double albedo_gltf(double cos_l, const double* p);

}  // namespace mfv::ref
