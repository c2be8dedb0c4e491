#include "report/agree_report.hpp"

#include <fmt/format.h>

namespace mfv {

int agree_failures(const AgreeReport& rep) {
  int failed = 0;
  for (auto& r : rep.results) failed += !r.pass();
  return failed;
}

std::string agree_console(const AgreeReport& rep, const std::string& device) {
  std::string out = device + "\n";
  out += fmt::format("{:<44} {:>10} {:>10} {:>10} {:>7} {:>9}  {}\n", "case", "max rel", "median rel", "max ulps",
                     "budget", "failures", "verdict");
  bool conditioned = false;
  for (auto& r : rep.results) {
    // above the budget yet passing: every such input was within its conditioning (below)
    const bool by_conditioning = r.pass() && r.max_ulps > r.ulp_budget;
    conditioned = conditioned || by_conditioning;
    out += fmt::format("{:<44} {:>10.3g} {:>10.3g} {:>10.3g} {:>7g} {:>9}  {}\n", r.name, r.max_rel, r.median_rel,
                       r.max_ulps, r.ulp_budget, r.failures, r.pass() ? (by_conditioning ? "pass*" : "pass") : "FAIL");
    if (!r.pass()) out += fmt::format("    worst: {}\n", r.worst);
  }
  if (conditioned)
    out +=
        "* max ulps above the budget, yet no failure: an input also passes when its error is within twice what the "
        "exact function moves when any one input moves by two units of rounding (an ill-conditioned input, e.g. "
        "near a zero of the function, cannot be computed closer)\n";
  out += fmt::format("{} cases, {} inputs; build {:.2f} s, kernel {:.2f} s, reference {:.2f} s; {} failed\n",
                     rep.results.size(), rep.samples, rep.build_seconds, rep.kernel_seconds, rep.reference_seconds,
                     agree_failures(rep));
  return out;
}

}  // namespace mfv
