// --baseline (mfv energy, mfv run): did an estimate move between an earlier
// run and this one beyond what the two runs' uncertainties explain?
#pragma once

#include <string>
#include <vector>

namespace mfv {

struct BaselineDiff {
  size_t compared = 0;     // values tested
  double threshold_p = 0;  // per-test p-value threshold (Bonferroni)
  struct Moved {
    std::string where;
    double before, after, se, p;
  };
  std::vector<Moved> moved;  // sorted by p, ascending
  std::vector<std::string> notes;
};

// One value in both runs: estimate and standard error, each with the degrees
// of freedom its standard error was estimated from.
struct BaselineValue {
  std::string where;
  double before, before_se, before_df;
  double after, after_se, after_df;
};

// Welch's t-test per value, Bonferroni over all of them at family-wise
// false-alarm rate alpha_fw: `moved` holds the values whose two-sided p is
// below alpha_fw / count. A value NaN on one side only has moved (p = 0); NaN
// on both is skipped. Fills compared, threshold_p and moved; keeps notes.
void judge_baseline(const std::vector<BaselineValue>& values, double alpha_fw, BaselineDiff& out);

}  // namespace mfv
