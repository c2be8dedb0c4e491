// Whole reflectance models in the one catalog (docs/design.md §1): BRDFs the seeds
// give as one formula rather than as a D x G x F product (Lambert, Oren-Nayar,
// Toon, Phong, Blinn, Ward, seed 004's Cook-Torrance k-mix, seed 003's
// Torrance-Sparrow, seed 002's compute_radiance). Each is declared once: up
// to six parameters p[0..5], source, kernel function (kernels/models.cl),
// reference twin (host/reference/models.cpp), the proposal width the albedo
// estimator takes from its roughness-like parameter, and the parameter points
// mfv run checks with the verdicts expected there and why.
#pragma once

#include "catalog/catalog.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace mfv {

// What the catalog predicts for one check at one point: it must hold, it must
// fail (a deficiency large enough to show at any seed), or it may fail.
enum class Expect { Hold, Fail, May };

using ref::kModelParams;  // p[0..6], see reference/twins.hpp
using ModelParams = std::array<double, kModelParams>;

using ref::RefAlbedo;
using ref::RefModel;

// How a model with a second width p[width_param2] forms its proposal's width
// from the two (each mapped by Model::width).
enum class TwoWidths {
  One,            // p[width_param2] unused
  GeometricMean,  // anisotropic: sqrt(a b); a where b = 0 (isotropic)
  Narrower,       // two lobes (a coat over a base): min(a, b)
};

struct ModelCase {
  std::string label;  // "n=1", shown in the group name
  ModelParams p{};
  Expect energy = Expect::Hold;  // albedo <= 1 (or = the closed form) at every light direction
  std::string energy_why;
  Expect reciprocity = Expect::Hold;
  std::string reciprocity_why;
};

// One whole model: its declaration, and (from ref::ModelTwins) its reference twins.
struct Model : ref::ModelTwins {
  std::string id;             // catalog name, distinct from every term id
  std::string kernel_fn;      // function in kernels/models.cl (gltf: kernels/model_gltf.cl)
  std::string source;         // seed file and formula, or paper and equation
  std::string formula;        // the BRDF, one line
  std::vector<Param> params;  // at most kModelParams
  // Non-empty where the seed gives reflected radiance per unit irradiance,
  // f (n·l), rather than f: how the catalog's BRDF was formed from it.
  std::string radiance;
  // Where the albedo estimator's proposal width comes from (never the formula):
  // p[width_param] mapped by `width` (None: no lobe, width 1).
  Roughness width = Roughness::None;
  TwoWidths two_widths = TwoWidths::One;
  int width_param = -1, width_param2 = -1;
  std::string albedo_doc;  // where ref_albedo's closed form holds and why
  double ulp_budget = 64;  // kernel float vs double reference, identical inputs
  double abs_floor = 1e-30;
  std::vector<ModelCase> cases;  // the points mfv run checks, with expected verdicts
  // Non-empty: where mfv stability's census finds the float32 kernel NaN or
  // Inf though the reference is finite (measured); such a model is reported,
  // not gated. Empty: finite wherever its reference is (gated).
  std::string unstable;

  double proposal_width(const double* p) const;
  uint32_t number() const;  // IntegralSpec::model: 1..999 (0 is the D x G x F BRDF)
};

const std::vector<Model>& models();
const Model* try_find_model(const std::string& id);
const Model* model_by_number(uint32_t number);                    // nullptr for 0 and numbers no model of this list has
const char* expect_name(Expect e);                                // "hold", "fail", "may fail"
std::string model_case_name(const Model& m, const ModelCase& c);  // "phong_004[n=1]"
// Why a glTF dielectric may reflect more than it receives (the "gltf" model's cases, mfv run --scene).
extern const char* const kGltfFresnelMixGain;
// Why gltf_sheen with a sheen lobe may gain energy at grazing light (its albedo table is clamped below mu = 1/32).
extern const char* const kGltfSheenTableClamp;
// Parameter values checked at the boundary, as validate_param for terms.
void validate_model_param(const Model& m, size_t index, double value);
// The defaults p[i] = params[i].fallback, zero past the model's count.
ModelParams model_defaults(const Model& m);

}  // namespace mfv
