// mfv agree: kernel vs reference on identical inputs, every term and BRDF.
#include "checks/agree.hpp"
#include "cli/commands.hpp"
#include "report/agree_report.hpp"

#include <fmt/format.h>

namespace mfv::cli {

void add_agree(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand("agree", "evaluate every term and D x G x F BRDF on the device and in the "
                                          "double reference on identical inputs; fail beyond the ULP table");
  static AgreeOptions opt;
  static bool terms_only = false;
  cmd->add_option("--samples", opt.samples, "inputs per term or combination")->check(CLI::Range(1ull, 1ull << 40));
  cmd->add_option("--seed", opt.seed, "Philox key");
  cmd->add_flag("--fp64", opt.fp64, "run the kernels in double (device needs cl_khr_fp64)");
  cmd->add_flag("--terms-only", terms_only, "skip the D x G x F combinations");
  cmd->add_option("--only", opt.only, "only cases whose name contains one of these (e.g. ggx, 'BRDF phong')");
  cmd->callback([&g, &rc] {
    opt.combinations = !terms_only;
    Runtime rt(g.device, g.kernel_dir);
    AgreeReport rep = run_agree(rt, opt);
    fmt::print("{}", agree_console(rep, fmt::format("device: {} ({}), {}; kernels in {}", rt.device().name,
                                                     rt.device().platform, rt.device().driver,
                                                     opt.fp64 ? "float64" : "float32")));
    const int failed = agree_failures(rep);
    rc = failed ? 1 : 0;
  });
}

}  // namespace mfv::cli
