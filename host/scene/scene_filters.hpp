// mfv energy --scene and mfv stability --scene: the scene's materials turned
// into those commands' filters, and what the scene learns from their results.
#pragma once

#include "checks/energy.hpp"
#include "checks/stability.hpp"
#include "scene/scene.hpp"

#include <string>
#include <vector>

namespace mfv {

// "d/g" of every D x G the scene's materials use (glTF: ggx/smith_ggx_correlated).
std::vector<std::string> scene_energy_models(const Scene& scene);
// Console: tables run against the full catalog, and each material's E_avg and
// energy loss 1 - E_avg at its own alpha (interpolated in log alpha).
void print_scene_energy(const Scene& scene, const EnergyReport& rep);

// Stability case names (kernels the scene's materials evaluate): "D ggx",
// "G smith_ggx_correlated", "G1 smith_ggx", "F schlick", "BRDF ggx/smith_ggx_correlated/schlick".
std::vector<std::string> scene_stability_cases(const Scene& scene);
void print_scene_stability(const Scene& scene, const StabilityReport& rep);

}  // namespace mfv
