// mfv energy --scene and mfv stability --scene: the scene's materials turned
// into those commands' filters, and what the scene learns from their results.
#pragma once

#include "checks/energy.hpp"
#include "checks/stability.hpp"
#include "scene/scene.hpp"

#include <string>
#include <vector>

namespace mfv {

// mfv energy's selection for a scene: the D x G tables of its D/G/F materials
// (by "d/g"), and the glTF model at each glTF material's distinct channels
// and as a white metal (F = 1: the specular lobe's own loss); nothing else.
void scene_energy_options(const Scene& scene, EnergyOptions& opt);
// Console: tables and points run against the full catalog, and each
// material's E_avg and energy loss 1 - E_avg: glTF at its own parameters,
// D/G/F at its own alpha (interpolated in log alpha).
void print_scene_energy(const Scene& scene, const EnergyReport& rep);

// Stability case names (kernels the scene's materials evaluate): "D ggx",
// "G smith_ggx_correlated", "G1 smith_ggx", "F schlick", "BRDF ggx/smith_ggx_correlated/schlick".
std::vector<std::string> scene_stability_cases(const Scene& scene);
// The cases above, and the glTF model swept at the scene's own parameter points (issue 21).
void scene_stability_options(const Scene& scene, StabilityOptions& opt);
void print_scene_stability(const Scene& scene, const StabilityReport& rep);

}  // namespace mfv
