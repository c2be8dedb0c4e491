// mfv convergence: error against samples and wall time per estimator, device and reference.
#include "checks/convergence.hpp"
#include "cli/commands.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <memory>

namespace mfv::cli {

namespace {

// mfv convergence's command-line values, bound to its options (Globals::command_values keeps them).
struct ConvergenceCommandOptions {
  ConvergenceOptions opt;
  std::vector<std::string> cases;
  std::string out_dir;
  bool no_reference = false;
};

}  // namespace

void add_convergence(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand("convergence",
                                 "error against samples and wall time for each estimator of d_norm "
                                 "and albedo (uniform, cosine, mis, dsample, vndf, rqmc, quadrature) "
                                 "on the OpenCL device and in the reference: slopes, time to "
                                 "tolerance, log-log plots");
  auto values = std::make_shared<ConvergenceCommandOptions>();  // the command's values
  g.command_values.push_back(values);
  cmd->add_option("--check", values->opt.checks,
                  "d_norm, albedo, furnace (albedo with F = 1) (default: d_norm albedo)");
  cmd->add_option("--estimator", values->opt.estimators,
                  "uniform, cosine, mis, dsample, vndf, rqmc, quadrature (default: all; "
                  "dsample and vndf are albedo only)");
  cmd->add_option("--case", values->cases,
                  "D:ALPHA:COS, e.g. ggx:0.01:0.05 (default: ggx, beckmann x alpha 1e-3, 1e-2, "
                  "0.1, 0.5 x cos 1, 0.05)");
  cmd->add_option("--min-log2", values->opt.min_log2, "smallest sample count 2^k per run (default 7)");
  cmd->add_option("--max-log2", values->opt.max_log2, "largest sample count 2^k per run on the device (default 17)");
  cmd->add_option("--ref-max-log2", values->opt.ref_max_log2, "largest sample count 2^k in the reference (default 13)");
  cmd->add_option("--replicates", values->opt.replicates,
                  "independent runs per count (RQMC: random shifts) (default 8)");
  cmd->add_option("--quad-max-order", values->opt.quad_max_order,
                  "quadrature estimator: Gauss-Legendre orders up to this "
                  "(default 12)");
  cmd->add_option("--seed", values->opt.seed, "Philox key");
  cmd->add_flag("--no-reference", values->no_reference, "device only (no reference timings, no quadrature estimator)");
  cmd->add_option("--out", values->out_dir,
                  "write convergence.json, convergence.md and plots/ here "
                  "(without a folder: results/convergence)")
      ->expected(0, 1);
  cmd->callback([&g, &rc, cmd, values] {
    for (auto& c : values->cases) values->opt.cases.push_back(parse_convergence_case(c));
    values->opt.reference = !values->no_reference;
    if (values->no_reference)
      values->opt.estimators.erase(
          std::remove(values->opt.estimators.begin(), values->opt.estimators.end(), "quadrature"),
          values->opt.estimators.end());
    validate_convergence_options(values->opt);
    if (cmd->count("--out") > 0 && values->out_dir.empty()) values->out_dir = "results/convergence";
    if (!values->out_dir.empty()) prepare_output_dir(values->out_dir);
    Runtime rt(g.device, g.kernel_dir);
    ConvergenceReport rep = run_convergence(rt, values->opt);
    print_convergence(rep);
    if (!values->out_dir.empty()) {
      write_files_atomically(convergence_outputs(rep, values->out_dir));
      fmt::print("wrote {}/convergence.json, convergence.md, plots/\n", values->out_dir);
    }
    rc = 0;
  });
}

}  // namespace mfv::cli
