// mfv bench: samples/s and integrals/s on each OpenCL device and in the reference.
#include "checks/bench.hpp"
#include "cli/commands.hpp"
#include "report/files.hpp"

#include <fmt/format.h>

namespace mfv::cli {

void add_bench(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand("bench", "throughput of d_norm, albedo (GGX + smith_ggx_correlated + Schlick) and "
                                          "reciprocity on every OpenCL device (or --device) and the double reference "
                                          "with 1 and all threads; medians, ratios, flops/sample");
  static BenchOptions opt;
  static std::string out_dir;
  cmd->add_option("--integrals", opt.integrals, "integrals per launch and per reference pass (default 64)");
  cmd->add_option("--samples", opt.samples, "samples per integral on a device (default 65536)");
  cmd->add_option("--ref-samples", opt.ref_samples, "samples per integral in the reference (default 4096)");
  cmd->add_option("--repeats", opt.repeats, "timed repetitions, medians reported (default 5)");
  cmd->add_option("--threads", opt.threads, "reference threads of the all-threads row (default: hardware threads)");
  cmd->add_option("--integrand", opt.integrands, "only these: d_norm, albedo, reciprocity");
  cmd->add_option("--seed", opt.seed, "Philox key");
  cmd->add_option("--out", out_dir, "write bench.json and bench.md here");
  cmd->callback([&g, &rc] {
    validate_bench_options(opt);
    if (!out_dir.empty()) prepare_output_dir(out_dir);
    BenchReport rep = run_bench(g.device, g.kernel_dir, opt);
    const std::string table = bench_table(rep);
    const std::string host = fmt::format("cpu: {} ({} hardware threads), load average {} at the start, {}\n", rep.cpu,
                                         rep.hardware_threads, rep.load_average, rep.date);
    fmt::print("{}{}", table, host);
    if (!out_dir.empty()) {
      write_files_atomically({{out_dir + "/bench.json", bench_json(rep)},
                              {out_dir + "/bench.md", fmt::format("# mfv bench\n\n{}\n{}", host, table)}});
      fmt::print("wrote {}/bench.json, bench.md\n", out_dir);
    }
    rc = 0;
  });
}

}  // namespace mfv::cli
