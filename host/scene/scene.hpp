// The materials a scene uses (issue 7): glTF 2.0 (.gltf, .glb) metallic-
// roughness materials with KHR_materials_ior / KHR_materials_specular, or a
// native material file (.json) naming D, G, F and their parameters directly.
// Everything is validated here; what cannot be checked right is an mfv::Error
// (exit 2), what is checked with a simplification is a warning on the material.
#pragma once

#include "catalog/catalog.hpp"
#include "catalog/models.hpp"

#include <array>
#include <string>
#include <vector>

namespace mfv {

// glTF 2.0 metallic-roughness factors (textures are not sampled).
struct GltfFactors {
  std::array<double, 3> base{1, 1, 1};  // baseColorFactor (rgb; alpha is coverage, not reflectance)
  double metallic = 1, roughness = 1;   // metallicFactor, roughnessFactor
  double ior = 1.5;                     // KHR_materials_ior
  double specular = 1;                  // KHR_materials_specular specularFactor
  std::array<double, 3> specular_color{1, 1, 1};  // specularColorFactor
  double anisotropy_strength = 0;       // KHR_materials_anisotropy anisotropyStrength, [0, 1]
  double anisotropy_rotation = 0;       // anisotropyRotation (radians; recorded, see SceneMaterial::channels)
};

// The smallest width the suite's float32 estimators resolve (its d_norm grid
// starts there); glTF roughness below 0.01 is checked at this alpha.
constexpr double kSceneMinAlpha = 1e-4;

// One colour channel of a glTF material as the model's six parameters
// (kernels/model_gltf.cl); channels with identical values are one set.
struct GltfChannelParams {
  double alpha, metallic, base, f0, f0_max, weight;
  double alpha_b = 0;  // KHR_materials_anisotropy: width along b (alpha is then alpha_t); 0 = isotropic
  bool operator==(const GltfChannelParams& o) const;
  ModelParams params() const { return {alpha, metallic, base, f0, f0_max, weight, alpha_b}; }
};
// The catalog's glTF model (host/catalog/models.cpp "gltf").
const Model& gltf_model();
// Its albedo must stay <= 1 where fresnel_mix is not involved: a pure metal
// (one GGX lobe with F <= 1), no diffuse base, or no specular layer (a
// Lambert base <= 1); elsewhere it may exceed 1 (kGltfFresnelMixGain).
Expect gltf_energy_expect(const GltfChannelParams& c);

struct SceneMaterial {
  std::string name;    // as the scene names it ("material #3" when unnamed)
  std::string origin;  // where it came from: "materials[3]", "default material (primitive without one)"
  bool gltf = true;    // glTF metallic-roughness model; else a D x G x F BRDF
  GltfFactors factors;
  double alpha = 0;    // glTF: roughness² (at least kSceneMinAlpha); D/G/F: the shared width
  // D x G x F (material files): terms and native parameters, Lambert kd
  const Term *d = nullptr, *g = nullptr, *f = nullptr;
  double pd = 0, pg = 0, f0 = 0, f1 = 0, kd = 0;
  std::vector<std::string> warnings;

  std::vector<GltfChannelParams> channels() const;  // distinct channels (glTF)
  std::string model() const;                        // "gltf" or "d/g/f"
};

struct Scene {
  std::string path;
  std::string format;  // "gltf", "glb", "materials"
  std::vector<SceneMaterial> materials;  // the materials the scene uses, in file order
  size_t materials_in_file = 0;          // including ones no mesh uses
  std::vector<std::string> warnings;     // about the file as a whole
};

// Reads and validates a scene; throws mfv::Error naming the file and the cause.
Scene load_scene(const std::string& path);

// Validates glTF factors (ranges, NaN); throws mfv::Error naming the material.
void validate_gltf_factors(const std::string& material, const GltfFactors& f);

}  // namespace mfv
