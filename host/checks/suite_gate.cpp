// SuiteReport::gate_failures: every reason a gate failed, one line each,
// naming the comparison, its worst case (inputs) and the bound it broke.
#include "checks/suite.hpp"

#include <fmt/format.h>

#include <cmath>

namespace mfv {
namespace {

std::string inputs(const PointResult& p) {
  std::string s;
  for (auto& [k, v] : p.params) s += fmt::format("{}{}={:g}", s.empty() ? "" : " ", k, v);
  return s.empty() ? "(no parameters)" : s;
}

// A NaN in a gate line says why (issue 28: no NaN without its reason).
std::string nan_reason(double x) {
  return std::isfinite(x) ? "" : " (some samples were NaN or infinite; the check 'finite' or mfv stability names them)";
}

// The statistical (or bounded) comparison of one point, with its bound.
std::string comparison(const PointResult& p) {
  if (p.bounded)
    return fmt::format("{} {:.3g} above bound {:.3g} at {}{}{}", p.measure.empty() ? "measure" : p.measure, p.estimate,
                       p.bound, inputs(p), p.detail.empty() ? "" : ": ", p.detail);
  if (p.upper_only)
    return fmt::format("estimate {:.6g} ± {:.2g} (SE) above {:g} + noise and tolerance: bound {:.6g}, at {}",
                       p.estimate, p.stderr_, p.expected, p.bound, inputs(p));
  return fmt::format("estimate {:.6g} ± {:.2g} (SE) off {:g} by {:.3g}, beyond the allowed {:.3g}, at {}{}", p.estimate,
                     p.stderr_, p.expected, p.deviation, p.bound, inputs(p), nan_reason(p.estimate + p.stderr_));
}

}  // namespace

std::vector<std::string> SuiteReport::gate_failures() const {
  std::vector<std::string> out;
  for (auto& g : groups) {
    if (g.verdict != Verdict::Fail && g.verdict != Verdict::XPass && g.verdict != Verdict::Inconclusive) continue;
    const std::string who = fmt::format("{} {} {}", verdict_name(g.verdict), g.check, g.model);
    if (g.verdict == Verdict::Inconclusive) {
      size_t n = 0;
      for (size_t i : g.points) n += points[i].inconclusive;
      for (size_t i : g.points)
        if (points[i].inconclusive) {
          out.push_back(fmt::format("{}: {} of {} points inconclusive; first at {}: {}", who, n, g.points.size(),
                                    inputs(points[i]), points[i].detail));
          break;
        }
      continue;
    }
    if (g.verdict == Verdict::XPass) {
      out.push_back(fmt::format("{}: expected to fail ({}) but every point held; closest: {}", who, g.reason,
                                comparison(points[g.worst])));
      continue;
    }
    // the worst statistical failure of a point that must hold, then each reference failure
    const PointResult* worst = nullptr;
    size_t failed = 0, ref_failed = 0;
    for (size_t i : g.points) {
      const PointResult& p = points[i];
      if (p.reference_failed) {
        ++ref_failed;
        if (ref_failed <= 3)
          out.push_back(fmt::format("{}: same-sample reference at {}: {}", who, inputs(p), p.reference_detail));
      }
      if (p.failed && p.expect == Expect::Hold) {
        ++failed;
        if (!worst ||
            std::fabs(p.deviation) / (p.bound + 1e-300) > std::fabs(worst->deviation) / (worst->bound + 1e-300))
          worst = &p;
      }
    }
    if (ref_failed > 3)
      out.push_back(fmt::format("{}: and {} more points disagree with the reference", who, ref_failed - 3));
    if (worst)
      out.push_back(
          fmt::format("{}: {} of {} points fail; worst: {}", who, failed, g.points.size(), comparison(*worst)));
    if (g.pooled.failed)
      out.push_back(
          fmt::format("{}: pooled over {} integrals, mean deviation {:+.3g} ± {:.2g} (bias bound {:.2g}) beyond "
                      "{} {:.2f}{}",
                      who, g.pooled.n, g.pooled.mean, g.pooled.se, g.pooled.bias,
                      g.pooled.upper_only ? "one-sided z" : "|z|", g.pooled.threshold,
                      nan_reason(g.pooled.mean + g.pooled.se)));
  }
  if (!reference_ok()) {
    if (reference_twin)
      out.push_back(fmt::format("reference: worst formula gap {:.3g} x its derived bound at {}", reference_worst,
                                reference_worst_at));
    else
      out.push_back(fmt::format("reference: worst disagreement {:.3g} above the fixed bound {:g} (no fp64 twin) at {}",
                                reference_worst, reference_bound, reference_worst_at));
  }
  return out;
}

}  // namespace mfv
