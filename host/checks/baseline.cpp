#include "checks/baseline.hpp"

#include "stats/normal.hpp"

#include <algorithm>
#include <cmath>

namespace mfv {

void judge_baseline(const std::vector<BaselineValue>& values, double alpha_fw, BaselineDiff& out) {
  out.compared = values.size();
  out.threshold_p = alpha_fw / double(std::max<size_t>(1, values.size()));
  out.moved.clear();
  for (auto& t : values) {
    const double v1 = t.before_se * t.before_se, v2 = t.after_se * t.after_se, se = std::sqrt(v1 + v2);
    double p;
    if (std::isnan(t.after) != std::isnan(t.before))
      p = 0;  // one side lost its value
    else if (std::isnan(t.after))
      continue;
    else if (se == 0)
      p = t.after == t.before ? 1 : 0;
    else {
      // Welch-Satterthwaite degrees of freedom of the combined standard error
      const double df = (v1 + v2) * (v1 + v2) / (v1 * v1 / t.before_df + v2 * v2 / t.after_df);
      p = stats::student_t_two_sided_p((t.after - t.before) / se,
                                       std::isfinite(df) ? df : std::min(t.before_df, t.after_df));
    }
    if (p < out.threshold_p) out.moved.push_back({t.where, t.before, t.after, se, p});
  }
  std::sort(out.moved.begin(), out.moved.end(), [](auto& x, auto& y) { return x.p < y.p; });
}

}  // namespace mfv
