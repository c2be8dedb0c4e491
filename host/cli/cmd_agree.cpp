// mfv agree: kernel vs reference on identical inputs, every term and BRDF.
#include "checks/agree.hpp"
#include "cli/commands.hpp"

#include <fmt/format.h>

#include <memory>

namespace mfv::cli {

namespace {

// mfv agree's command-line values, bound to its options (Globals::command_values keeps them).
struct AgreeCommandOptions {
  AgreeOptions opt;
  bool terms_only = false;
};

}  // namespace

void add_agree(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand("agree", "evaluate every term and D x G x F BRDF on the device and in the "
                                          "double reference on identical inputs; fail beyond the ULP table");
  auto values = std::make_shared<AgreeCommandOptions>();  // the command's values
  g.command_values.push_back(values);
  cmd->add_option("--samples", values->opt.samples, "inputs per term or combination")->check(CLI::Range(1ull, 1ull << 40));
  cmd->add_option("--seed", values->opt.seed, "Philox key");
  cmd->add_flag("--fp64", values->opt.fp64, "run the kernels in double (device needs cl_khr_fp64)");
  cmd->add_flag("--terms-only", values->terms_only, "skip the D x G x F combinations");
  cmd->add_option("--only", values->opt.only, "only cases whose name contains one of these (e.g. ggx, 'BRDF phong')");
  cmd->callback([&g, &rc, values] {
    values->opt.combinations = !values->terms_only;
    Runtime rt(g.device, g.kernel_dir);
    AgreeReport rep = run_agree(rt, values->opt);
    fmt::print("device: {} ({}), {}; kernels in {}\n", rt.device().name, rt.device().platform, rt.device().driver,
               values->opt.fp64 ? "float64" : "float32");
    int failed = 0;
    fmt::print("{:<44} {:>10} {:>10} {:>10} {:>7} {:>9}  {}\n", "case", "max rel", "median rel", "max ulps",
               "budget", "failures", "verdict");
    bool conditioned = false;
    for (auto& r : rep.results) {
      // above the budget yet passing: every such input was within its conditioning (below)
      const bool by_conditioning = r.pass() && r.max_ulps > r.ulp_budget;
      conditioned = conditioned || by_conditioning;
      fmt::print("{:<44} {:>10.3g} {:>10.3g} {:>10.3g} {:>7g} {:>9}  {}\n", r.name, r.max_rel, r.median_rel,
                 r.max_ulps, r.ulp_budget, r.failures, r.pass() ? (by_conditioning ? "pass*" : "pass") : "FAIL");
      if (!r.pass()) {
        fmt::print("    worst: {}\n", r.worst);
        ++failed;
      }
    }
    if (conditioned)
      fmt::print("* max ulps above the budget, yet no failure: an input also passes when its error is within twice "
                 "what the exact function moves when any one input moves by two units of rounding (an "
                 "ill-conditioned input, e.g. near a zero of the function, cannot be computed closer)\n");
    fmt::print("{} cases, {} inputs; build {:.2f} s, kernel {:.2f} s, reference {:.2f} s; {} failed\n",
               rep.results.size(), rep.samples, rep.build_seconds, rep.kernel_seconds, rep.reference_seconds, failed);
    rc = failed ? 1 : 0;
  });
}

}  // namespace mfv::cli
