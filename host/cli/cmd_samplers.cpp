// mfv samplers: quadrature and chi-square tests of every sampling routine.
#include "checks/samplers.hpp"
#include "cli/commands.hpp"
#include "report/files.hpp"
#include "report/sampler_plots.hpp"
#include "runtime/error.hpp"

#include <fmt/format.h>

namespace mfv::cli {

void add_samplers(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand("samplers", "verify the sampling routines: pdf integrates to 1, chi-square "
                                             "histogram test (Sidak-corrected), device and reference draws");
  static SamplersOptions opt;
  static std::string out_dir, bins;
  static bool device_only = false;
  cmd->add_option("--samples", opt.samples, "draws per test (default 2^20)");
  cmd->add_option("--seed", opt.seed, "Philox key");
  cmd->add_option("--significance", opt.significance, "family-wise false-alarm rate (default 0.01)");
  cmd->add_option("--bins", bins, "COSxPHI histogram cells (default 64x128)");
  cmd->add_flag("--device-only", device_only, "skip the reference twin's draws");
  cmd->add_option("--out", out_dir, "write samplers.json here, and an observed/expected/difference image of every "
                                    "failed chi-square test into plots/");
  static bool plots = false;
  cmd->add_flag("--plots", plots, "with --out: images of every chi-square test, not only the failed ones");
  cmd->callback([&g, &rc] {
    if (!bins.empty()) {
      char x = 0, extra = 0;
      if (std::sscanf(bins.c_str(), "%d%c%d%c", &opt.cos_bins, &x, &opt.phi_bins, &extra) != 3 || (x != 'x' && x != 'X'))
        throw Error(fmt::format("--bins '{}': expected COSxPHI, e.g. 64x128", bins));
    }
    if (plots && out_dir.empty()) throw Error("--plots needs --out DIR (the images go to DIR/plots)");
    opt.reference = !device_only;
    if (!out_dir.empty()) prepare_output_dir(out_dir);
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
    rc = failed ? 1 : 0;
  });
}

}  // namespace mfv::cli
