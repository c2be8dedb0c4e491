// mfv samplers: quadrature and chi-square tests of every sampling routine.
#include "checks/samplers.hpp"
#include "cli/commands.hpp"
#include "report/files.hpp"
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
  cmd->add_option("--out", out_dir, "write samplers.json here");
  cmd->callback([&g, &rc] {
    if (!bins.empty()) {
      char x = 0, extra = 0;
      if (std::sscanf(bins.c_str(), "%d%c%d%c", &opt.cos_bins, &x, &opt.phi_bins, &extra) != 3 || (x != 'x' && x != 'X'))
        throw Error(fmt::format("--bins '{}': expected COSxPHI, e.g. 64x128", bins));
    }
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
      write_files_atomically({{out_dir + "/samplers.json", samplers_json(rs, rt, opt)}});
      fmt::print("wrote {}/samplers.json\n", out_dir);
    }
    rc = failed ? 1 : 0;
  });
}

}  // namespace mfv::cli
