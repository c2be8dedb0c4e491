// mfv run's pointwise kinds (checks/registry.hpp, Runner::Pointwise): an agree
// pass (kernel and double reference on identical inputs, checks/agree.hpp),
// a stability pass (the deterministic sweep of extreme inputs,
// checks/stability.hpp) at a CI-sized budget and the BTDF's generalized
// reciprocity (checks/bsdf_reciprocity.cpp), each case one bounded point of
// the report, so that their verdicts share the report, the JUnit file and the
// exit code with the integrals. `mfv agree` and `mfv stability` run the same
// checks at their full budgets.
#include "checks/agree.hpp"
#include "checks/stability.hpp"
#include "checks/suite.hpp"
#include "checks/suite_bsdf.hpp"

#include <fmt/format.h>

#include <chrono>

namespace mfv {

namespace {

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// mfv run's agree pass: its options.
AgreeOptions agree_pass_options(const SuiteOptions& opt) {
  AgreeOptions ao;
  ao.seed = opt.seed;
  ao.samples = scaled_samples(check_kind("agree").base_samples, opt.scale);
  ao.only = opt.models;
  ao.only_may_match_none = true;
  return ao;
}

void run_agree_pass(Runtime& rt, const SuiteOptions& opt, SuiteReport& rep) {
  const auto t0 = std::chrono::steady_clock::now();
  const AgreeOptions ao = agree_pass_options(opt);
  const double b0 = rt.build_stats().seconds;
  const AgreeReport ar = run_agree(rt, ao);
  rep.build_seconds += rt.build_stats().seconds - b0;
  for (const AgreeResult& r : ar.results) {
    PointResult p;
    p.check = "agree";
    p.model = r.name;
    p.bounded = true;
    p.estimate = double(r.failures);
    p.bound = 0;
    p.samples = r.samples;
    p.measure = "inputs beyond the ULP budget and their conditioning";
    p.detail = fmt::format("max {:.3g} ulps (budget {:g}); worst input {}", r.max_ulps, r.ulp_budget, r.worst);
    p.params["max_ulps"] = r.max_ulps;
    rep.points.push_back(p);
  }
  rep.stats.push_back({"agree", ar.results.size(), ar.samples, since(t0)});
}

void run_stability_pass(Runtime& rt, const SuiteOptions& opt, SuiteReport& rep) {
  const auto t0 = std::chrono::steady_clock::now();
  StabilityOptions so;
  so.only = opt.models;
  so.only_may_match_none = true;
  const double b0 = rt.build_stats().seconds;
  const StabilityReport sr = run_stability(rt, so);
  rep.build_seconds += rt.build_stats().seconds - b0;
  size_t n = 0;
  for (const StabilityCase& c : sr.cases) {
    if (!c.stable) continue;  // the catalog's unstable forms and the variants are reported by mfv stability, not gated
    PointResult p;
    p.check = "stability";
    p.model = c.name;
    p.bounded = true;
    const uint64_t bad = c.count(&RegionResult::nan, true) + c.count(&RegionResult::inf, true) +
                         c.count(&RegionResult::out_of_domain, true);
    p.estimate = double(bad);
    p.bound = 0;
    p.measure = "in-domain NaN, Inf or out-of-domain values";
    for (const RegionResult& r : c.regions)
      if (r.in_domain && (r.nan + r.inf + r.out_of_domain) > 0 && p.detail.empty())
        p.detail = fmt::format("region {}: {} NaN, {} Inf, {} out of domain; first at {}", r.region, r.nan, r.inf,
                               r.out_of_domain, r.first_out_of_domain.empty() ? r.first_break : r.first_out_of_domain);
    p.samples = 0;
    for (const RegionResult& r : c.regions) p.samples += r.points;
    rep.points.push_back(p);
    ++n;
  }
  rep.stats.push_back({"stability", n, sr.points, since(t0)});
}

}  // namespace

void run_pointwise_kinds(Runtime& rt, const SuiteOptions& opt, SuiteReport& rep) {
  if (suite_check_wanted(opt, "agree")) run_agree_pass(rt, opt, rep);
  if (suite_check_wanted(opt, "stability")) run_stability_pass(rt, opt, rep);
  if (suite_check_wanted(opt, "bsdf_reciprocity")) run_bsdf_reciprocity_pass(rt, opt, rep);
}

void compile_pointwise_kinds(Runtime& rt, const SuiteOptions& opt) {
  SuiteReport scratch;
  // agree's first case only: every case launches agree_eval over the same
  // chunk of records (the same work-group size, so the same compile); the
  // other 252 cases' host reference (~1 s of CPU) compiles nothing
  if (suite_check_wanted(opt, "agree")) run_agree(rt, agree_pass_options(opt), {0, 1});
  if (suite_check_wanted(opt, "stability")) run_stability_pass(rt, opt, scratch);
  if (suite_check_wanted(opt, "bsdf_reciprocity")) run_bsdf_reciprocity_pass(rt, opt, scratch);
}

}  // namespace mfv
