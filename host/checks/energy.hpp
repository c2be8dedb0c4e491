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
// independently shifted Kronecker point sets per quantity; the standard error
// is the spread of the R replicate means / sqrt(R). Adaptive: cells whose
// standard error is above the target get 4x the points, up to a cap.
#pragma once

#include "catalog/catalog.hpp"
#include "runtime/opencl.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace mfv {

struct EnergyOptions {
  std::vector<std::string> models;  // substrings of "d/g"; empty = every D x G
  int n_mu = 32, n_alpha = 32;
  double target = 1e-4;             // standard error per cell
  uint64_t seed = 1;
  int replicates = 8;               // randomizations per quantity (stderr has R-1 degrees of freedom)
  uint64_t min_points = 1024;       // points per replicate on the first pass
  uint64_t max_points = 1u << 14;   // cap on points per replicate
  uint32_t reference_samples = 32;  // kernel vs double reference on identical samples
  int reference_every = 97;         // ... for every k-th integral
};

struct Cell {
  double mean = 0, se = 0;
};

struct EnergyTable {
  const Term* d = nullptr;
  const Term* g = nullptr;
  std::vector<double> pd, pg;   // native parameters per alpha
  std::vector<Cell> E, A, B;    // index a * n_mu + m
  std::vector<uint64_t> points;  // points per replicate used, per cell
  std::vector<Cell> eavg;       // per alpha, its own integral (mu drawn with density 2mu)
  std::vector<Cell> eavg_quad;  // per alpha, midpoint rule over the mu grid (cross-check)
  std::string name() const { return d->id + "/" + g->id; }
};

struct EnergyReport {
  EnergyOptions opt;
  std::vector<double> mu, alpha;  // mu: midpoints (m + 1/2)/n; alpha: log-spaced 1e-3..1
  std::vector<EnergyTable> tables;
  double seconds = 0, build_seconds = 0;
  uint64_t samples = 0;
  double samples_per_second = 0;
  double max_se = 0;              // over E, A, B and E_avg of every table
  std::string max_se_at;
  size_t above_target = 0;        // quantities whose standard error stayed above the target
  size_t reference_compared = 0;
  double reference_worst = 0, reference_bound = 5e-3;
  std::string reference_worst_at;
  std::string device;
};

std::vector<double> energy_mu_grid(int n);
std::vector<double> energy_alpha_grid(int n);

void validate_energy_options(const EnergyOptions& opt);  // throws mfv::Error
EnergyReport run_energy(Runtime& rt, const EnergyOptions& opt);

// --baseline: cells that moved beyond their combined standard errors.
struct BaselineDiff {
  size_t compared = 0;  // values tested (E, A per cell and E_avg per alpha)
  double threshold_p = 0;  // per-test p-value threshold (Bonferroni)
  struct Moved {
    std::string where;
    double before, after, se, p;
  };
  std::vector<Moved> moved;  // sorted by p, ascending
  std::vector<std::string> notes;
};

// `baseline_json` is the text of an earlier energy.json; family-wise
// false-alarm rate `alpha_fw`. Throws mfv::Error on a malformed or
// incompatible baseline (different grid).
BaselineDiff compare_energy_baseline(const EnergyReport& now, const std::string& baseline_json, double alpha_fw);

// Two-sided p-value of Student's t with `df` degrees of freedom.
double student_t_two_sided_p(double t, double df);

}  // namespace mfv
