#include "report/agree_report.hpp"

#include "mfv_git_commit.h"

#include "report/shard_file.hpp"
#include "runtime/provenance.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

namespace mfv {

int agree_failures(const AgreeReport& rep) {
  int failed = 0;
  for (auto& r : rep.results) failed += !r.pass();
  return failed;
}

using nlohmann::json;

json agree_result_json(const AgreeResult& r) {
  return {{"name", r.name},
          {"samples", r.samples},
          {"max_rel", shard_number(r.max_rel)},
          {"median_rel", shard_number(r.median_rel)},
          {"max_ulps", shard_number(r.max_ulps)},
          {"ulp_budget", shard_number(r.ulp_budget)},
          {"failures", r.failures},
          {"worst", r.worst},
          {"pass", r.pass()}};
}

AgreeResult agree_result_of(const json& j) {
  AgreeResult r;
  r.name = j.at("name").get<std::string>();
  r.samples = j.at("samples").get<uint64_t>();
  r.max_rel = shard_number_of(j.at("max_rel"));
  r.median_rel = shard_number_of(j.at("median_rel"));
  r.max_ulps = shard_number_of(j.at("max_ulps"));
  r.ulp_budget = shard_number_of(j.at("ulp_budget"));
  r.failures = j.at("failures").get<uint64_t>();
  r.worst = j.at("worst").get<std::string>();
  return r;
}

std::string agree_json(const AgreeReport& rep, const AgreeOptions& opt, const std::string& device) {
  json j;
  j["schema"] = "mfv-agree/1";
  j["tool"] = {{"version", MFV_VERSION}, {"commit", MFV_GIT_COMMIT}};
  j["provenance"] = provenance_json();
  if (!rep.shards.empty()) j["provenance"]["shards"] = rep.shards;  // mfv agree --merge
  j["created"] = utc_timestamp();
  j["device"] = device;
  j["options"] = {{"seed", opt.seed}, {"samples", opt.samples}, {"fp64", opt.fp64}};
  j["seconds"] = {{"build", rep.build_seconds}, {"kernel", rep.kernel_seconds}, {"reference", rep.reference_seconds}};
  j["samples"] = rep.samples;
  j["failed"] = agree_failures(rep);
  j["results"] = json::array();
  for (auto& r : rep.results) j["results"].push_back(agree_result_json(r));
  return j.dump(1) + "\n";
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
