// mfv energy: energy-loss tables and Kulla-Conty compensation data (issue 4).
//
// For every chosen D x G (F = none) on a grid of view cosines mu and widths
// alpha: the directional albedo E(mu, alpha) = ∫ f(i,o)(n·i) di, the Schlick
// split-sum terms A and B (E_F = F0·A + F90·B) and the average albedo
// E_avg(alpha) = 2∫E(mu) mu dmu, each with a standard error.
//
// Estimator: the conformance albedo estimator (MIS of a cosine lobe and
// Cauchy slopes of width alpha; independent of the D/G under test) fed with
// randomized QMC points (kernels/integrate.cl, CHECK_ALBEDO_RQMC): R
// independently shifted Kronecker point sets per quantity, the radial
// coordinate (and E_avg's mu²) periodized (rqmc_radial, kernels/albedo.cl);
// the standard error is the spread of the R replicate means / sqrt(R). Each
// quantity's point count is sized by two pilot runs on streams of their own
// (which measure its error's rate), then its estimate is a fresh run of that
// count (so the standard error is unbiased).
//
// Whole models (catalog/models.hpp) get the same treatment at parameter
// points (their catalog cases, or points a caller gives): E(mu) with mu the
// light's cosine (a whole model need not be reciprocal; E is the energy a
// beam from l reflects), E_avg and the energy loss 1 - E_avg, with the
// proposal width taken from the model's roughness-like parameter.
#pragma once

#include "catalog/bsdfs.hpp"
#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "checks/baseline.hpp"
#include "checks/unit_plan.hpp"
#include "runtime/opencl.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace mfv {

// A whole model at one parameter point.
struct ModelPoint {
  const Model* model = nullptr;
  std::string name;  // "phong_004[n=1]" for a catalog case; a caller's label otherwise
  ModelParams p{};
  Expect expect = Expect::Hold;  // the catalog's energy expectation (E <= 1 at every light), and why
  std::string why;
};

struct EnergyOptions {
  std::vector<std::string> models;       // substrings of "d/g" or "model[case]"; empty = every D x G and model case
  bool tables = true;                    // the D x G tables
  bool catalog_models = true;            // whole models at their catalog cases
  std::vector<ModelPoint> model_points;  // more whole-model points (mfv energy --scene)
  double gain_alpha = 1e-3;              // family-wise false-alarm rate of "gains energy" over every model cell
  int n_mu = 32, n_alpha = 32;
  // Axes given by the caller (issue 33; checks/energy_axes.hpp): empty = the
  // built-in grid above. `paired`: cell i is (mu[i], alpha[i]) (mfv energy
  // --at), not the product of the two axes. `roughness`: the values the
  // caller gave when alpha = roughness² (--roughness r2), else empty.
  std::vector<double> mu_axis, alpha_axis, roughness;
  bool paired = false;
  std::string layout;  // a layout's name (checks/energy_layouts.hpp), or empty
  // A glass layout (issue 33): per width, the relative index of refraction
  // the light sees (> 1 entering, < 1 leaving the medium), the widths then
  // being the (eta, roughness) pairs, eta slowest. Empty: no BSDF tables.
  std::vector<double> eta;
  bool fp64 = false;   // the energy kernels in double (cl_khr_fp64)
  double target = 1e-4;  // standard error per cell
  uint64_t seed = 1;
  int replicates = 32;              // randomizations per quantity (stderr has R-1 degrees of freedom; docs/cli/energy.md)
  uint64_t min_points = 1024;       // points per replicate on the first pass
  uint64_t max_points = 1u << 14;   // cap on points per replicate
  uint32_t reference_samples = 32;  // kernel vs double reference on identical samples
  int reference_every = 97;         // ... for every k-th integral
};

struct Cell {
  double mean = 0, se = 0;
};

// One cell of a table: its width index a, view index m and cell index c
// (a * n_mu + m on a grid; a = m = c on paired points).
struct CellAt {
  size_t a, m, c;
};

struct EnergyTable {
  const Term* d = nullptr;
  const Term* g = nullptr;
  // A glass table (rough dielectric BSDF, flux form): E = E_R + E_T, A holds
  // E_R and B holds E_T (E_R = E - E_T on the same points, as A = E - B), and
  // E_avg is the midpoint rule over the mu cells with its rule error.
  const Bsdf* bsdf = nullptr;
  std::vector<double> pd, pg;    // native parameters per alpha
  std::vector<Cell> E, A, B;     // index a * n_mu + m
  std::vector<uint64_t> points;  // points per replicate used, per cell
  std::vector<Cell> eavg;        // per alpha, its own integral (mu drawn with density 2mu)
  std::vector<Cell> eavg_quad;   // per alpha, midpoint rule over the mu grid (cross-check); se: noise + rule error
  std::string name() const;  // "d/g", or the BSDF's id
};

// One whole model at one parameter point: E per mu of the light.
struct ModelEnergy {
  ModelPoint point;
  std::vector<Cell> E;           // per mu
  std::vector<uint64_t> points;  // points per replicate used, per mu
  Cell eavg, eavg_quad;          // E_avg: its own integral; midpoint rule over the mu grid
  size_t max_at = 0;             // mu index of the largest E
  double excess_p = 1;           // one-sided p-value of E(mu[max_at]) <= 1 (Student t, R - 1 df)
  bool gains = false;            // E > 1 beyond noise and float rounding somewhere (Bonferroni over every model cell)
  bool unresolved = false;       // not gains, but a cell's standard error is above target and its upper bound above 1
  double loss() const { return 1 - eavg.mean; }
};

struct EnergyReport {
  EnergyOptions opt;
  std::vector<double> mu, alpha;  // default mu: midpoints (m + 1/2)/n; alpha: log-spaced 1e-3..1; or the caller's
  bool paired = false;            // cell i = (mu[i], alpha[i]) (opt.paired)
  bool midpoint_mu = true;        // mu is the midpoint grid: E_avg's quadrature cross-check applies
  // Every table cell in record order; cells per table.
  std::vector<CellAt> cells() const;
  size_t n_cells() const { return paired ? alpha.size() : mu.size() * alpha.size(); }
  std::vector<EnergyTable> tables;
  std::vector<ModelEnergy> models;
  double seconds = 0, build_seconds = 0;
  uint64_t samples = 0;
  double samples_per_second = 0;
  double max_se = 0;  // over E, A, B and E_avg of every table
  std::string max_se_at;
  size_t above_target = 0;  // quantities whose standard error stayed above the target
  size_t topped_up = 0;     // units whose fresh run ended above the target and were run again, fresh
  size_t reference_compared = 0;
  double reference_worst = 0, reference_bound = 5e-3;
  std::string reference_worst_at;
  std::string device;
  std::vector<std::string> shards;  // mfv energy --merge: one line per shard (index, file, variable, device)
};

std::vector<double> energy_mu_grid(int n);
// The width a table integrates at alpha: alpha itself, or D's smallest
// declared width where alpha is below it (alpha = 0, a mirror, has no
// microfacet integral; an engine layout's first roughness cells may lie below
// a D's range, e.g. charlie's 1e-3). Outputs list such cells.
double energy_min_alpha(const Term& d);
// The view cosine a cell integrates at: mu, or the grazing limit's stand-in
// kEnergyMuFloor where mu is below it (at mu = 0 exactly the view lies in the
// surface and the integrand is 0/0; engines' edge tables hold the limit
// mu -> 0+ there; docs/energy-layouts.md measures E's change below the floor).
constexpr double kEnergyMuFloor = 1e-6;
double energy_eval_mu(double mu);
double energy_eval_alpha(const Term& d, double alpha);
std::vector<double> energy_alpha_grid(int n);

void validate_energy_options(const EnergyOptions& opt);  // throws mfv::Error
// mfv energy --shard K/N (docs/scale.md): a part of the whole run, the units
// (energy_plan.hpp) [lo, hi) of the whole plan's list. Each unit keeps its
// streams and the pilots' stream offsets of the whole plan, and its point
// count is sized with the whole plan's family (Bonferroni over every unit),
// so it computes what the whole run computes for it.
struct EnergyUnitResult {
  std::vector<double> sum, b_sum;  // per replicate, of the reported run
  uint64_t done = 0;               // its points per replicate
};
struct EnergyPart {
  size_t lo = 0, hi = 0;
  // filled by run_energy: the units' results, and what the part measured
  std::vector<EnergyUnitResult> results;
  uint64_t samples = 0;
  size_t topped_up = 0, reference_compared = 0;
  double reference_worst = 0, seconds = 0, build_seconds = 0;
  std::string reference_worst_at;
};
// The whole run, or (part != nullptr) the part's units only: then the
// report's cells are those of the part's units and part->results is filled.
EnergyReport run_energy(Runtime& rt, const EnergyOptions& opt, EnergyPart* part = nullptr);
// The whole run's report from its parts' results (every unit once, parts in
// order): the same cells, verdicts and reference summary as run_energy.
// Throws mfv::Error where the parts do not cover the plan's units.
EnergyReport merge_energy(const EnergyOptions& opt, const std::string& device, const std::vector<EnergyPart>& parts);
// The whole plan's units' count and each unit's integrals (R, 2R for a glass
// cell: its estimated cost), and a digest of the plan (16 hex digits): every
// unit's integrals, streams and cells, and the options that change values.
using EnergyPlanSummary = UnitPlan;
EnergyPlanSummary energy_plan_summary(const EnergyOptions& opt);

// `baseline_json` is the text of an earlier energy.json; family-wise
// false-alarm rate `alpha_fw`. Throws mfv::Error on a malformed or
// incompatible baseline (different grid).
BaselineDiff compare_energy_baseline(const EnergyReport& now, const std::string& baseline_json, double alpha_fw);

}  // namespace mfv
