// mfv samplers: quadrature and chi-square tests of every sampling routine.
#include "checks/samplers.hpp"
#include "cli/shared_options.hpp"
#include "report/sampler_plots.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <tuple>

namespace mfv::cli {

namespace {

// mfv samplers: its values, bound to its options, and its work.
struct SamplersCommand : SharedValues {
  SamplersOptions opt;
  std::string bins;
  bool device_only = false;
  bool plots = false;

  void add_options(CLI::App* cmd) {
    cmd->description(
        "verify the sampling routines: pdf integrates to 1, chi-square histogram test (Sidak-corrected), device and "
        "reference draws");
    SharedOptions(cmd, *this)
        .seed(opt.seed)
        .out("samplers.json",
             ", and an observed/expected/difference image of every failed chi-square test into plots/");
    cmd->add_option("--samples", opt.samples, "draws per test (default 2^20)");
    cmd->add_option("--significance", opt.significance, "family-wise false-alarm rate (default 0.01)");
    cmd->add_option("--bins", bins, "COSxPHI histogram cells (default 64x128)");
    cmd->add_flag("--device-only", device_only, "skip the reference twin's draws");
    cmd->add_flag("--plots", plots, "with --out: images of every chi-square test, not only the failed ones");
  }

  int run(const Globals& g) {
    if (!bins.empty()) std::tie(opt.cos_bins, opt.phi_bins) = parse_cells("--bins", bins, "COSxPHI", "64x128");
    if (plots && out_dir.empty()) throw Error("--plots needs --out DIR (the images go to DIR/plots)");
    opt.reference = !device_only;
    prepare_out();
    Runtime rt(g.device, g.kernel_dir);
    fmt::print("device: {} ({})\n", rt.device().name, rt.device().platform);
    auto rs = run_samplers(rt, opt);
    print_samplers(rs);
    int failed = 0;
    for (auto& r : rs) failed += !r.pass();
    fmt::print("{} of {} sampler tests pass (family-wise significance {:g}, Sidak)\n", rs.size() - failed, rs.size(),
               opt.significance);
    if (!out_dir.empty()) {
      std::vector<std::pair<std::string, std::string>> files;
      for (auto& [name, bytes] : sampler_plots(rs, plots)) files.push_back({out_dir + "/plots/" + name, bytes});
      files.push_back({out_dir + "/samplers.json", samplers_json(rs, rt, opt)});
      write_files_atomically(files);
      fmt::print("wrote {}/samplers.json{}\n", out_dir,
                 files.size() > 1 ? fmt::format(" and {} images in plots/", files.size() - 1) : "");
    } else if (failed) {
      fmt::print("rerun with --out DIR for an observed/expected/difference image of each failed test\n");
    }
    return failed ? 1 : 0;
  }
};

}  // namespace

void add_samplers(CLI::App& app, Globals& g, int& rc) { add_command<SamplersCommand>(app, g, rc, "samplers"); }

}  // namespace mfv::cli
