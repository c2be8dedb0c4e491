// mfv bench --case D/G/F:ALPHA:MU: what one albedo integral costs with the
// suite's own estimator (IntegralKind::AlbedoMis, the furnace and energy
// checks of mfv run): samples/s, variance per sample and the seconds to a
// standard error of 1e-4, the numbers a user compares with another tool.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mfv {

struct BenchCase {
  std::string d, g, f;  // catalog ids; f may be "none"
  double alpha = 0.5, mu = 0.5;
  double f0 = 0, f1 = 0;  // the F's parameters (their catalog defaults)
};

// Parses "D/G/F:ALPHA:MU"; throws mfv::Error naming what is wrong.
BenchCase parse_bench_case(const std::string& text);

// One point count's timed calls.
struct BenchCaseCount {
  uint32_t points = 0;                                // per replicate
  uint64_t samples = 0;                               // per timed call: points x replicates
  double estimate = 0, stderr_ = 0;                   // of the first timed call
  double rms_stderr = 0;                              // root mean square of the timed calls' standard errors
  double median_seconds = 0, median_cpu_seconds = 0;  // wall and process CPU time of one call
  double samples_per_s = 0;
  double variance_per_sample = 0;  // samples x rms_stderr²: for RQMC the effective variance (it falls with N)
};

// The standard errors bench --case reports a call for.
inline constexpr double kBenchCaseTargets[] = {1e-4, 1e-5};

// One target standard error: the fewest points per replicate (5·2^(m-2),
// Integrator::mis_points) whose timed calls' rms SE reached it.
struct BenchCaseTarget : BenchCaseCount {
  double target_se = 1e-4;
  double seconds_to_se = 0;  // median_seconds, scaled by (rms_stderr / target)² only if the cap stopped the search
};

struct BenchCaseResult {
  BenchCase c;
  std::string device;
  uint32_t replicates = 0;               // RQMC replicates of the estimator
  std::vector<BenchCaseCount> grid;      // every count timed, ascending
  std::vector<BenchCaseTarget> targets;  // SE 1e-4, then 1e-5
  int repeats = 0;
};

// Times `repeats` calls at each whole-net point count per replicate, 20,
// 40, 80, ..., up to one count beyond the first whose rms SE is at most 1e-5
// (a RQMC error falls faster than N^-1/2, so the time to an error cannot be
// extrapolated down from a larger run); each target's call is the fewest
// points whose timed calls' rms SE is at most the target.
BenchCaseResult run_bench_case(const std::string& device_selector, const std::string& kernel_dir, const BenchCase& c,
                               int repeats, uint64_t seed);
std::string bench_case_text(const BenchCaseResult& r);
std::string bench_case_json(const BenchCaseResult& r, const std::string& load_average, const std::string& date);

}  // namespace mfv
