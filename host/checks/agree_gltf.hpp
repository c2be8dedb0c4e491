// Pointwise agreement of the glTF metallic-roughness model (kernels/model_gltf.cl)
// with its double reference (host/reference/model_gltf.cpp): one case of mfv agree.
#pragma once

#include "checks/agree.hpp"

namespace mfv {

// ULPs of the float result allowed: D (8) + height-correlated G (8) + the
// Fresnel mix and the products around them.
constexpr double kGltfUlpBudget = 48;

// `prog` holds the agree_gltf kernel (built with TermSelection::gltf).
AgreeResult agree_gltf(Runtime& rt, cl::Program& prog, const AgreeOptions& opt, uint32_t stream,
                       double& kernel_seconds, double& reference_seconds);

}  // namespace mfv
