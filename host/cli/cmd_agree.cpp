// mfv agree: kernel vs reference on identical inputs, every term and BRDF.
#include "checks/agree.hpp"
#include "cli/commands.hpp"
#include "report/agree_report.hpp"

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
  auto* cmd = app.add_subcommand("agree",
                                 "evaluate every term and D x G x F BRDF on the device and in the "
                                 "double reference on identical inputs; fail beyond the ULP table");
  auto values = std::make_shared<AgreeCommandOptions>();  // the command's values
  g.command_values.push_back(values);
  cmd->add_option("--samples", values->opt.samples, "inputs per term or combination")
      ->check(CLI::Range(1ull, 1ull << 40));
  cmd->add_option("--seed", values->opt.seed, "Philox key");
  cmd->add_flag("--fp64", values->opt.fp64, "run the kernels in double (device needs cl_khr_fp64)");
  cmd->add_flag("--terms-only", values->terms_only, "skip the D x G x F combinations");
  cmd->add_option("--only", values->opt.only, "only cases whose name contains one of these (e.g. ggx, 'BRDF phong')");
  cmd->callback([&g, &rc, values] {
    values->opt.combinations = !values->terms_only;
    Runtime rt(g.device, g.kernel_dir);
    AgreeReport rep = run_agree(rt, values->opt);
    fmt::print("{}", agree_console(
                         rep, fmt::format("device: {} ({}), {}; kernels in {}", rt.device().name, rt.device().platform,
                                          rt.device().driver, values->opt.fp64 ? "float64" : "float32")));
    const int failed = agree_failures(rep);
    rc = failed ? 1 : 0;
  });
}

}  // namespace mfv::cli
