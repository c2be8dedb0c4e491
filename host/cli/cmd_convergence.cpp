// mfv convergence: error against samples and wall time per estimator, device and reference.
#include "checks/convergence.hpp"
#include "cli/shared_options.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace mfv::cli {

namespace {

// mfv convergence: its values, bound to its options, and its work.
struct ConvergenceCommand : SharedValues {
  ConvergenceOptions opt;
  std::vector<std::string> cases;
  bool no_reference = false;
  CLI::Option* out_opt = nullptr;

  void add_options(CLI::App* cmd) {
    cmd->description(
        "error against samples and wall time for each estimator of d_norm and albedo (uniform, cosine, mis, dsample, "
        "vndf, rqmc, quadrature) on the OpenCL device and in the reference: slopes, time to tolerance, log-log plots");
    cmd->add_option("--check", opt.checks, "d_norm, albedo, furnace (albedo with F = 1) (default: d_norm albedo)");
    cmd->add_option("--estimator", opt.estimators,
                    "uniform, cosine, mis, dsample, vndf, rqmc, quadrature (default: all; dsample and vndf are "
                    "albedo only)");
    cmd->add_option("--case", cases,
                    "D:ALPHA:COS, e.g. ggx:0.01:0.05 (default: ggx, beckmann x alpha 1e-3, 1e-2, 0.1, 0.5 x cos 1, "
                    "0.05)");
    cmd->add_option("--min-log2", opt.min_log2, "smallest sample count 2^k per run (default 7)");
    cmd->add_option("--max-log2", opt.max_log2, "largest sample count 2^k per run on the device (default 17)");
    cmd->add_option("--ref-max-log2", opt.ref_max_log2, "largest sample count 2^k in the reference (default 13)");
    cmd->add_option("--replicates", opt.replicates, "independent runs per count (RQMC: random shifts) (default 8)");
    cmd->add_option("--quad-max-order", opt.quad_max_order,
                    "quadrature estimator: Gauss-Legendre orders up to this (default 12)");
    SharedOptions(cmd, *this)
        .seed(opt.seed)
        .out("convergence.json, convergence.md and plots/", " (without a folder: results/convergence)");
    out_opt = cmd->get_option("--out")->expected(0, 1);
    cmd->add_flag("--no-reference", no_reference, "device only (no reference timings, no quadrature estimator)");
  }

  int run(const Globals& g) {
    for (auto& c : cases) opt.cases.push_back(parse_convergence_case(c));
    opt.reference = !no_reference;
    if (no_reference)
      opt.estimators.erase(std::remove(opt.estimators.begin(), opt.estimators.end(), "quadrature"),
                           opt.estimators.end());
    validate_convergence_options(opt);
    if (out_opt->count() > 0 && out_dir.empty()) out_dir = "results/convergence";
    prepare_out();
    Runtime rt(g.device, g.kernel_dir);
    ConvergenceReport rep = run_convergence(rt, opt);
    print_convergence(rep);
    if (!out_dir.empty()) {
      write_files_atomically(convergence_outputs(rep, out_dir));
      fmt::print("wrote {}/convergence.json, convergence.md, plots/\n", out_dir);
    }
    return 0;
  }
};

}  // namespace

void add_convergence(CLI::App& app, Globals& g, int& rc) { add_command<ConvergenceCommand>(app, g, rc, "convergence"); }

}  // namespace mfv::cli
