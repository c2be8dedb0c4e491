#include "user/user_power.hpp"

#include "stats/normal.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

namespace mfv {

double effective_samples(double mean, double se, uint64_t n) {
  if (!(se > 0)) return double(n);
  const double m2 = mean * mean;
  return double(n) * m2 / (m2 + double(n) * se * se);
}

void mark_inconclusive(SuiteReport& rep, size_t first) {
  for (size_t i = first; i < rep.points.size(); ++i) {
    PointResult& p = rep.points[i];
    // a NaN fails by itself; an exact zero (every sample 0) is conclusive
    if (p.bounded || !std::isfinite(p.estimate) || !std::isfinite(p.stderr_) || p.samples == 0) continue;
    // a difference expected 0 (bsdf_avg_reciprocity: T_avg(1/eta) - T_avg(eta)/eta^2) has no lobe scale of its
    // own; its estimator's reach is that of bsdf_furnace's E_T, where the same proposal is judged
    if (!p.upper_only && p.expected == 0) continue;
    const double ess = effective_samples(p.estimate, p.stderr_, p.samples);
    if (ess >= kMinEffectiveSamples) continue;
    if (std::fabs(p.estimate) + p.stderr_ < kNegligible * std::fabs(p.expected)) continue;
    p.inconclusive = true;
    p.detail = fmt::format(
        "inconclusive: the estimator did not reach the lobe (effective sample size {:.3g} of {}, below {:g}: "
        "{:.3g} ± {:.2g}); give the lobe's width as the roughness parameter, or more samples (--scale)",
        ess, p.samples, kMinEffectiveSamples, p.estimate, p.stderr_);
  }
}

uint64_t samples_for_power(const PointResult& p, double z) {
  constexpr double kGain = 0.05, kPowerZ = 1.6448536269514722;  // one-sided 0.95
  const uint64_t n = p.samples;
  if (p.bounded || !p.upper_only || n == 0 || !std::isfinite(p.stderr_) || !std::isfinite(p.estimate)) return n;
  const double room = kGain * std::fabs(p.expected) - p.rounding_bound;  // what noise may take of the gain
  const double need_se = (z + kPowerZ) * p.stderr_;
  if (need_se <= room) return n;
  if (!(room > 0)) return n;  // the bias alone hides the gain: no sample count helps
  const double factor = (need_se / room) * (need_se / room);
  uint64_t m = 2;
  while (m < kMaxSizing && double(m) < factor) m *= 2;
  return n * m;
}

std::string power_statement(const SuiteReport& rep) {
  constexpr double kGain = 0.05, kPowerZ = 1.6448536269514722;  // one-sided 0.95
  struct Power {
    size_t n = 0, detects = 0;
    double worst = -1;
    const PointResult* at = nullptr;
  };
  std::map<std::string, Power> by;
  for (auto& p : rep.points) {
    if (p.bounded || !p.upper_only || !std::isfinite(p.stderr_)) continue;
    Power& w = by[p.check];
    const double gain = (rep.z_threshold + kPowerZ) * p.stderr_ + p.bias;  // detected with probability 0.95
    ++w.n;
    w.detects += gain <= kGain * std::fabs(p.expected);
    if (gain > w.worst) {
      w.worst = gain;
      w.at = &p;
    }
  }
  std::string out;
  for (auto& [check, w] : by) {
    std::string at;
    for (auto& [k, v] : w.at->params) at += fmt::format("{}{}={:g}", at.empty() ? "" : " ", k, v);
    out += fmt::format("{}power: {} detects a 5 % gain with probability 0.95 at {} of {} points; its least powerful "
                       "point detects {:.3g} (at {})",
                       out.empty() ? "" : "\n", check, w.detects, w.n, w.worst, at);
  }
  return out;
}

}  // namespace mfv
