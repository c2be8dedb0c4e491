// mfv bench: samples/s and integrals/s on each OpenCL device and in the reference.
#include "checks/bench.hpp"
#include "checks/bench_case.hpp"
#include "cli/commands.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <memory>

namespace mfv::cli {

namespace {

// mfv bench's command-line values, bound to its options (Globals::command_values keeps them).
struct BenchCommandOptions {
  BenchOptions opt;
  std::string out_dir;
  std::string case_text;
};

}  // namespace

void add_bench(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand("bench",
                                 "throughput of d_norm, albedo (GGX + smith_ggx_correlated + Schlick) and "
                                 "reciprocity on every OpenCL device (or --device) and the double reference "
                                 "with 1 and all threads; medians, ratios, flops/sample");
  auto values = std::make_shared<BenchCommandOptions>();  // the command's values
  g.command_values.push_back(values);
  cmd->add_option("--integrals", values->opt.integrals, "integrals per launch and per reference pass (default 64)");
  cmd->add_option("--samples", values->opt.samples, "samples per integral on a device (default 65536)");
  cmd->add_option("--ref-samples", values->opt.ref_samples, "samples per integral in the reference (default 4096)");
  cmd->add_option("--repeats", values->opt.repeats, "timed repetitions, medians reported (default 5)");
  cmd->add_option("--threads", values->opt.threads,
                  "reference threads of the all-threads row (default: hardware threads)");
  cmd->add_option("--integrand", values->opt.integrands, "only these: d_norm, albedo, reciprocity");
  cmd->add_option("--seed", values->opt.seed, "Philox key");
  cmd->add_option("--out", values->out_dir, "write bench.json and bench.md here");
  cmd->add_option("--case", values->case_text,
                  "D/G/F:ALPHA:MU: one albedo integral with the suite's estimator: samples/s, variance per sample, "
                  "seconds to a standard error of 1e-4 (e.g. ggx/smith_ggx_correlated/none:0.5:0.5)");
  cmd->callback([&g, &rc, values] {
    validate_bench_options(values->opt);
    if (!values->case_text.empty()) {
      const BenchCase c = parse_bench_case(values->case_text);
      if (!values->out_dir.empty()) prepare_output_dir(values->out_dir);
      const BenchCaseResult r = run_bench_case(g.device, g.kernel_dir, c, values->opt.repeats, values->opt.seed);
      fmt::print("{}", bench_case_text(r));
      if (!values->out_dir.empty()) {
        const std::string json = bench_case_json(r, bench_load_average(), utc_timestamp());
        write_files_atomically({{values->out_dir + "/bench.json", json},
                                {values->out_dir + "/bench.md", "# mfv bench --case\n\n" + bench_case_text(r)}});
        fmt::print("wrote {}/bench.json, bench.md\n", values->out_dir);
      }
      rc = 0;
      return;
    }
    if (!values->out_dir.empty()) prepare_output_dir(values->out_dir);
    BenchReport rep = run_bench(g.device, g.kernel_dir, values->opt);
    const std::string table = bench_table(rep);
    const std::string host = fmt::format("cpu: {} ({} hardware threads), load average {} at the start, {}\n", rep.cpu,
                                         rep.hardware_threads, rep.load_average, rep.date);
    fmt::print("{}{}", table, host);
    if (!values->out_dir.empty()) {
      write_files_atomically({{values->out_dir + "/bench.json", bench_json(rep)},
                              {values->out_dir + "/bench.md", fmt::format("# mfv bench\n\n{}\n{}", host, table)}});
      fmt::print("wrote {}/bench.json, bench.md\n", values->out_dir);
    }
    rc = 0;
  });
}

}  // namespace mfv::cli
