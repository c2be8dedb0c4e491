// The materials a scene uses (issue 7): glTF 2.0 (.gltf, .glb) metallic-
// roughness materials with KHR_materials_ior / KHR_materials_specular /
// KHR_materials_anisotropy, or a native material file (.json) naming D, G, F
// and their parameters directly. Everything is validated here (issue 17: typed,
// strict); what cannot be checked right is an mfv::Error (exit 2). Only the
// materials are read (issue 21): buffers are never needed, images only for the
// ranges of textured parameters; each material carries an account of what is
// checked over which range and what is not checked, and why.
#pragma once

#include "catalog/catalog.hpp"
#include "catalog/models.hpp"

#include <array>
#include <string>
#include <vector>

namespace mfv {

// A parameter a texture scales: checked at its ends and inside (issue 21).
// lo = hi for a plain factor.
struct ParamRange {
  double lo = 0, hi = 0;
  std::string source;  // how the range was found: "factor", "texture 'mr.png' G: [0.2, 0.9] x factor 0.8", ...
  bool varies() const { return lo < hi; }
};

// glTF 2.0 metallic-roughness factors (the largest values textures can give).
struct GltfFactors {
  std::array<double, 3> base{1, 1, 1};            // baseColorFactor (rgb; alpha is coverage, not reflectance)
  double metallic = 1, roughness = 1;             // metallicFactor, roughnessFactor
  double ior = 1.5;                               // KHR_materials_ior
  double specular = 1;                            // KHR_materials_specular specularFactor
  std::array<double, 3> specular_color{1, 1, 1};  // specularColorFactor
  double anisotropy_strength = 0;                 // KHR_materials_anisotropy anisotropyStrength, [0, 1]
  double anisotropy_rotation = 0;                 // anisotropyRotation (radians; recorded, see SceneMaterial::channels)
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
// The catalog's glTF model (host/catalog/models.cpp "gltf") and its clearcoat layering ("gltf_clearcoat").
const Model& gltf_model();
const Model& gltf_clearcoat_model();
const Model& gltf_sheen_model();
const Model& gltf_clearcoat_aniso_model();
const Model& gltf_transmission_model();
// Its albedo must stay <= 1 where fresnel_mix is not involved: a pure metal
// (one GGX lobe with F <= 1), no diffuse base, or no specular layer (a
// Lambert base <= 1); elsewhere it may exceed 1 (kGltfFresnelMixGain).
Expect gltf_energy_expect(const GltfChannelParams& c);

// A whole model at one parameter point of a material, with what the checks
// expect there (the glTF model, or "gltf_clearcoat" for a coated material).
struct WholePoint {
  const Model* model = nullptr;
  ModelParams p{};
  Expect energy = Expect::Hold;
  std::string energy_why;
  Expect reciprocity = Expect::Hold;
  std::string reciprocity_why;
  std::string key() const;  // "gltf alpha=... metallic=..." : one set per distinct point
};

struct SceneMaterial {
  std::string name;    // as the scene names it ("material #3" when unnamed)
  std::string origin;  // where it came from: "materials[3]", "default material (primitive without one)"
  bool gltf = true;    // glTF metallic-roughness model; else a D x G x F BRDF
  GltfFactors factors;
  double alpha = 0;  // glTF: roughness² (at least kSceneMinAlpha); D/G/F: the shared width
  // D x G x F (material files): terms and native parameters, Lambert kd
  const Term *d = nullptr, *g = nullptr, *f = nullptr;
  double pd = 0, pg = 0, f0 = 0, f1 = 0, kd = 0;
  std::vector<std::string> warnings;
  // glTF: the ranges the checks cover (factor alone, or [texel range] x factor)
  ParamRange roughness, metallic, specular, anisotropy_strength;
  // KHR_materials_clearcoat: clearcoat = clearcoatFactor x texture R, its
  // roughness = clearcoatRoughnessFactor x texture G; checked through the
  // "gltf_clearcoat" model where coat_checked (host/scene/scene_points.cpp)
  ParamRange clearcoat, clearcoat_roughness;
  bool coat_checked = false;
  // KHR_materials_sheen: sheenColor = sheenColorFactor x texture RGB (sRGB),
  // sheenRoughness = sheenRoughnessFactor x texture A; checked through the
  // "gltf_sheen" model where sheen_checked (host/scene/scene_points.cpp)
  std::array<ParamRange, 3> sheen_color;
  ParamRange sheen_roughness;
  bool sheen_checked = false;
  // KHR_materials_ior with 1 <= ior <= 10 (the dielectric F term's range): the
  // specular lobe is also checked with the exact dielectric Fresnel at eta = ior
  bool ior_exact = false;
  std::array<ParamRange, 3> base, specular_color;
  // KHR_materials_transmission: transmission = transmissionFactor x texture R.
  // Thin-walled (no KHR_materials_volume thickness): checked through the
  // "gltf_transmission" model where thin_checked; with thickness > 0 a
  // refracting boundary: the catalog's Walter BSDF at eta = ior, roughness²
  // where volume_checked (host/scene/scene_checks.cpp, issue 29)
  ParamRange transmission;
  bool thin_checked = false, volume_checked = false;
  // What is checked and what is not, one line each ("KHR_materials_volume: nothing to check on a surface BSDF").
  std::vector<std::string> account;
  // Non-empty: the material is not checked at all, and why (KHR_materials_transmission, unlit, ...).
  std::string not_checked;

  // glTF: every distinct parameter point the checks run at: each colour
  // channel at the ends (and inside, for roughness and anisotropy) of every
  // range (host/scene/scene_points.cpp).
  std::vector<GltfChannelParams> channels() const;
  // glTF: the distinct specular lobes (alpha_t, alpha_b) among channels(), and the roughness widths.
  std::vector<std::pair<double, double>> lobes() const;
  std::vector<double> alphas() const;
  // coat_checked: the "gltf_clearcoat" model's points (base channels x coat
  // ranges) and the coat's GGX widths
  std::vector<ModelParams> coat_points() const;
  std::vector<double> coat_alphas() const;
  // glTF: every specular lobe as a white metal (F = 1: the lobe's own loss),
  // lobes() and the coat's (alpha_b 0): the furnace of mfv run --scene and
  // the white points of mfv energy --scene
  std::vector<GltfChannelParams> white_lobes() const;
  // ... and over the anisotropic channel points: the "gltf_clearcoat_aniso" model's
  std::vector<ModelParams> coat_aniso_points() const;
  // sheen_checked: the "gltf_sheen" model's points (isotropic base channels x
  // each sheen channel and the largest of the other two x sheen roughness)
  std::vector<ModelParams> sheen_points() const;
  // glTF: the whole-model points energy and reciprocity run at (channels(), or coat_points())
  std::vector<WholePoint> whole_points() const;
  // thin_checked: the "gltf_transmission" points of the derived expectation
  // (white base, full transmission, no metal: R + T = the F = 1 albedo), one per roughness point
  std::vector<ModelParams> thin_identity_points() const;
  std::string model() const;  // "gltf" or "d/g/f"
};

struct Scene {
  std::string path;
  std::string format;                    // "gltf", "glb", "materials"
  std::vector<SceneMaterial> materials;  // the materials the scene uses, in file order
  size_t materials_in_file = 0;          // including ones no mesh uses
  std::vector<std::string> warnings;     // about the file as a whole
};

// Reads and validates a scene; throws mfv::Error naming the file and the cause.
Scene load_scene(const std::string& path);

// Validates glTF factors (ranges, NaN); throws mfv::Error naming the material
// (who: "material 'x' (materials[2])").
void validate_gltf_factors(const std::string& who, const GltfFactors& f);
// Sets the ranges of a material whose parameters are the plain factors (no textures).
void set_factor_ranges(SceneMaterial& m);
// Accounts for a roughness range reaching below the float32 floor (a warning naming the floor).
void note_alpha_floor(SceneMaterial& m);

// glTF (.gltf, .glb) reading: host/scene/gltf_load.cpp.
Scene load_gltf(const std::string& path, bool binary);

}  // namespace mfv
