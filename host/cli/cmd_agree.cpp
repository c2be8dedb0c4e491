// mfv agree: kernel vs reference on identical inputs, every term and BRDF.
#include "checks/agree.hpp"
#include "cli/shared_options.hpp"
#include "report/agree_report.hpp"

#include <fmt/format.h>

namespace mfv::cli {

namespace {

// mfv agree: its values, bound to its options, and its work.
struct AgreeCommand : SharedValues {
  AgreeOptions opt;

  void add_options(CLI::App* cmd) {
    cmd->description(
        "evaluate every term and D x G x F BRDF on the device and in the double reference on identical inputs; fail "
        "beyond the ULP table");
    cmd->add_option("--samples", opt.samples, "inputs per term or combination")->check(CLI::Range(1ull, 1ull << 40));
    SharedOptions(cmd, *this)
        .seed(opt.seed)
        .fp64(opt.fp64)
        .terms_only("the D x G x F combinations")
        .only(opt.only, "ggx, 'BRDF phong'");
  }

  int run(const Globals& g) {
    opt.combinations = !terms_only;
    Runtime rt(g.device, g.kernel_dir);
    AgreeReport rep = run_agree(rt, opt);
    fmt::print("{}", agree_console(
                         rep, fmt::format("device: {} ({}), {}; kernels in {}", rt.device().name, rt.device().platform,
                                          rt.device().driver, opt.fp64 ? "float64" : "float32")));
    return agree_failures(rep) ? 1 : 0;
  }
};

}  // namespace

void add_agree(CLI::App& app, Globals& g, int& rc) { add_command<AgreeCommand>(app, g, rc, "agree"); }

}  // namespace mfv::cli
