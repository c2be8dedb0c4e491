// mfv convergence: error against sample count and wall time for each
// estimator of the d_norm and albedo integrals, on the OpenCL device and in
// the double reference in one run, against a truth computed apart (closed
// form, or a peak-aware product Gauss-Legendre rule with its own error).
#pragma once

#include "runtime/opencl.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace mfv {

// One integrand: D (ggx or beckmann, with its Smith G and Schlick F0 = 0.04
// for albedo), width alpha, view cosine (albedo; d_norm ignores it).
struct ConvergenceCase {
  std::string d;
  double alpha = 0.01;
  double cos_o = 1.0;
  std::string name() const;  // e.g. ggx a=0.01 cos=0.05
};

struct ConvergenceOptions {
  std::vector<std::string> checks;      // d_norm, albedo, furnace (albedo with F = 1); empty: d_norm, albedo
  std::vector<std::string> estimators;  // uniform, cosine, mis, dsample, vndf, rqmc, quadrature; empty: all
  std::vector<ConvergenceCase> cases;   // empty: GGX, Beckmann x alpha 1e-3, 1e-2, 0.1, 0.5 x cos 1, 0.05
  int min_log2 = 7;                     // sample counts 2^min_log2 .. 2^max_log2 per run on the device
  int max_log2 = 17;
  int ref_max_log2 = 13;    // the reference stops here (it is slower)
  int replicates = 8;       // independent runs per sample count (RQMC: randomizations)
  int quad_max_order = 12;  // quadrature estimator: Gauss-Legendre orders 2..this
  uint64_t seed = 1;
  bool reference = true;
};

// Parses D:ALPHA:COS (e.g. ggx:0.01:0.05); throws mfv::Error on bad input.
ConvergenceCase parse_convergence_case(const std::string& text);
void validate_convergence_options(const ConvergenceOptions& opt);
std::vector<ConvergenceCase> default_convergence_cases();

struct ConvergenceLevel {
  uint64_t n = 0;      // samples (quadrature: integrand evaluations) of one run
  double mean = 0;     // mean of the replicates' estimates
  double rmse = 0;     // sqrt(mean over replicates of (estimate - truth)^2): the error of one run
  double est_se = 0;   // estimated standard error of one run (MC: from its samples; RQMC: replicate
                       // spread; quadrature: difference to the previous order)
  double seconds = 0;  // wall time of one run
};

struct ToleranceReach {
  double tol = 0;
  double n = 0, seconds = 0;  // NaN: not reached
  bool extrapolated = false;  // from the fitted slope and the last measured error
};

struct ConvergenceSeries {
  std::string check, estimator, engine;  // engine: "device" or "reference"
  size_t case_index = 0;
  std::vector<ConvergenceLevel> levels;
  double slope = 0;                   // least squares of log rmse on log n over the fit range; NaN if too few points
  size_t fit_from = 0;                // first level of the fit range
  double z = 0, p = 1;                // top level: (mean of replicates - truth) / its standard error, and its p-value
  bool consistent = true;             // p above the family-wise (Sidak) level
  std::vector<ToleranceReach> reach;  // 1e-3, 1e-4, 1e-5
};

struct ConvergenceTruth {
  double value = 0, error = 0;  // error: |fine - coarse rule| (0 for a closed form)
  std::string method;
  double quadrature_check = 0;  // d_norm: the fine rule's value of the closed form 1
};

struct ConvergenceTarget {
  bool measured = false;
  std::string best;  // estimator reaching 1e-4 in the fewest samples
  double best_n = 0;
  double uniform_variance = 0, uniform_n_variance = 0;  // exact, by quadrature: n = variance / tol²
  double uniform_n = 0, uniform_n_clt = 0;  // from the measured errors: extrapolated at n^-1/2, and by its est. se
  double ratio = 0;                         // uniform_n_variance / best_n
  bool best_extrapolated = false, uniform_extrapolated = false;
  std::string line() const;
};

struct ConvergenceReport {
  ConvergenceOptions opt;
  std::vector<ConvergenceCase> cases;
  std::vector<std::string> checks;
  std::vector<std::vector<ConvergenceTruth>> truth;  // [check][case]
  std::vector<ConvergenceSeries> series;
  double level = 0;  // per-series significance of the consistency test
  std::string device, platform, date;
  double seconds = 0;
  ConvergenceTarget target;  // GGX alpha = 0.01, cos 0.05, albedo, on the device
};

ConvergenceReport run_convergence(Runtime& rt, const ConvergenceOptions& opt);

// Which estimators a check uses; dsample and vndf are albedo-only.
bool estimator_applies(const std::string& estimator, const std::string& check);
// Kernel/reference id of an estimator for a case (dsample: by the case's D).
uint32_t estimator_id(const std::string& estimator, const ConvergenceCase& c);

// Two-sided p-value of Student's t with `dof` degrees of freedom (dof <= 0: normal).
double t_two_sided_p(double t, int dof);

void print_convergence(const ConvergenceReport& rep);
// convergence.json, convergence.md and plots/*.png (when gnuplot is there), under `dir`.
std::vector<std::pair<std::string, std::string>> convergence_outputs(const ConvergenceReport& rep,
                                                                     const std::string& dir);

}  // namespace mfv
