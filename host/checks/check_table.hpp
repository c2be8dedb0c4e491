// The table of checks: one row per check of mfv run's D x G x F grid (and
// the whole-model and reciprocity checks), naming how it is integrated
// (kind, base samples, grid), how it is tested (one- or two-sided) and how
// its expected verdict follows from the catalog. The plan builder
// (checks/suite_plans.cpp) turns rows and "what to check" into integrals.
#pragma once

#include "catalog/catalog.hpp"
#include "runtime/integrator.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace mfv {

// Samples per masking or furnace integral at scale 1; every check's count is
// proportional to the scale.
constexpr uint64_t kSuiteBaseSamples = 4096;

// Which F terms a row pairs with D x G.
enum class FSet {
  None,     // no F (masking), or F = 1 ("none": the white furnace)
  Real,     // every F of the catalog but "none", at its check points (Term::check_points)
  Schlick,  // Schlick's F alone (the diffuse + specular sum of seed 000)
};

struct CheckRow {
  const char* check;
  IntegralKind kind;
  uint64_t base_samples;  // per integral at --scale 1
  int n_alpha = 0;        // widths: n_alpha of suite_alphas(), evenly thinned (0: the D's own d_norm grid)
  int n_view = 0;         // view cosines: view_cosines(n_view) (0: the normal only)
  FSet fs = FSet::None;
  std::vector<double> kds = {0.0};  // Lambertian albedos added (energy_diffuse)
  bool upper_only = false;          // one-sided (albedo <= 1) rather than two-sided (== expected)
  const char* verdict;              // how the expected verdict follows from the catalog (expect())
};

// The D x G x F rows in plan order: d_norm, masking, furnace, energy, energy_diffuse.
const std::vector<CheckRow>& dgf_check_rows();
// mfv energy's rows, per D x G (F = none) and width of its grid, or per whole
// model point: energy_mu, E(mu) and (same points) B at each view cosine of
// the grid; energy_avg, E_avg with mu drawn with density 2 mu (view unused:
// the normal). n_alpha and n_view give the default grid; --grid replaces it.
const std::vector<CheckRow>& energy_check_rows();
// The row of `check` (d_norm ... energy_diffuse, energy_mu, energy_avg); throws mfv::Error for another name.
const CheckRow& check_row(const std::string& check);

// D's and G's native parameters at the shared width alpha (catalog/roughness.hpp);
// G's is clamped to the top of its range (its G1 is flat beyond).
struct NativeWidths {
  double pd = 0, pg = 0;
};
NativeWidths native_widths(const Term& d, const Term& g, double alpha);

// Whole models (catalog/models.hpp): energy (albedo <= 1, one-sided, at
// kModelLights light directions) and closed_form (the exact albedo, two-sided).
constexpr int kModelLights = 10;
// Their samples: kSuiteBaseSamples at the scale, times these factors.
constexpr uint64_t kModelEnergyFactor = 2;  // spread over the 10 lights
constexpr uint64_t kClosedFormFactor = 8;   // few integrals, two-sided: sharp (standard error ~0.6 %)

}  // namespace mfv
