// mfv bench: samples/s and integrals/s on each OpenCL device and in the reference.
#include "checks/bench.hpp"
#include "checks/bench_case.hpp"
#include "cli/shared_options.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

namespace mfv::cli {

namespace {

// mfv bench: its values, bound to its options, and its work.
struct BenchCommand : SharedValues {
  BenchOptions opt;
  std::string case_text;

  void add_options(CLI::App* cmd) {
    cmd->description(
        "throughput of d_norm, albedo (GGX + smith_ggx_correlated + Schlick) and reciprocity on every OpenCL device "
        "(or --device) and the double reference with 1 and all threads; medians, ratios, flops/sample");
    cmd->add_option("--integrals", opt.integrals, "integrals per launch and per reference pass (default 64)");
    cmd->add_option("--samples", opt.samples, "samples per integral on a device (default 65536)");
    cmd->add_option("--ref-samples", opt.ref_samples, "samples per integral in the reference (default 4096)");
    cmd->add_option("--repeats", opt.repeats, "timed repetitions, medians reported (default 5)");
    cmd->add_option("--threads", opt.threads, "reference threads of the all-threads row (default: hardware threads)");
    cmd->add_option("--integrand", opt.integrands, "only these: d_norm, albedo, reciprocity");
    SharedOptions(cmd, *this).seed(opt.seed).out("bench.json and bench.md");
    cmd->add_option("--case", case_text,
                    "D/G/F:ALPHA:MU: one albedo integral with the suite's estimator: samples/s, variance per sample, "
                    "seconds to a standard error of 1e-4 (e.g. ggx/smith_ggx_correlated/none:0.5:0.5)");
  }

  int run(const Globals& g) {
    validate_bench_options(opt);
    if (!case_text.empty()) return run_case(g);
    prepare_out();
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
    return 0;
  }

  // --case: one albedo integral
  int run_case(const Globals& g) {
    const BenchCase c = parse_bench_case(case_text);
    prepare_out();
    const BenchCaseResult r = run_bench_case(g.device, g.kernel_dir, c, opt.repeats, opt.seed);
    fmt::print("{}", bench_case_text(r));
    if (!out_dir.empty()) {
      const std::string json = bench_case_json(r, bench_load_average(), utc_timestamp());
      write_files_atomically(
          {{out_dir + "/bench.json", json}, {out_dir + "/bench.md", "# mfv bench --case\n\n" + bench_case_text(r)}});
      fmt::print("wrote {}/bench.json, bench.md\n", out_dir);
    }
    return 0;
  }
};

}  // namespace

void add_bench(CLI::App& app, Globals& g, int& rc) { add_command<BenchCommand>(app, g, rc, "bench"); }

}  // namespace mfv::cli
