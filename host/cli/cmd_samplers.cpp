// mfv samplers: quadrature and chi-square tests of every sampling routine.
#include "checks/samplers.hpp"
#include "cli/commands.hpp"
#include "report/sampler_plots.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <memory>

namespace mfv::cli {

namespace {

// mfv samplers's command-line values, bound to its options (Globals::command_values keeps them).
struct SamplersCommandOptions {
  SamplersOptions opt;
  std::string out_dir;
  std::string bins;
  bool device_only = false;
  bool plots = false;
};

}  // namespace

void add_samplers(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand("samplers",
                                 "verify the sampling routines: pdf integrates to 1, chi-square "
                                 "histogram test (Sidak-corrected), device and reference draws");
  auto values = std::make_shared<SamplersCommandOptions>();  // the command's values
  g.command_values.push_back(values);
  cmd->add_option("--samples", values->opt.samples, "draws per test (default 2^20)");
  cmd->add_option("--seed", values->opt.seed, "Philox key");
  cmd->add_option("--significance", values->opt.significance, "family-wise false-alarm rate (default 0.01)");
  cmd->add_option("--bins", values->bins, "COSxPHI histogram cells (default 64x128)");
  cmd->add_flag("--device-only", values->device_only, "skip the reference twin's draws");
  cmd->add_option("--out", values->out_dir,
                  "write samplers.json here, and an observed/expected/difference image of every "
                  "failed chi-square test into plots/");
  cmd->add_flag("--plots", values->plots, "with --out: images of every chi-square test, not only the failed ones");
  cmd->callback([&g, &rc, values] {
    if (!values->bins.empty()) {
      char x = 0, extra = 0;
      if (std::sscanf(values->bins.c_str(), "%d%c%d%c", &values->opt.cos_bins, &x, &values->opt.phi_bins, &extra) !=
              3 ||
          (x != 'x' && x != 'X'))
        throw Error(fmt::format("--bins '{}': expected COSxPHI, e.g. 64x128", values->bins));
    }
    if (values->plots && values->out_dir.empty()) throw Error("--plots needs --out DIR (the images go to DIR/plots)");
    values->opt.reference = !values->device_only;
    if (!values->out_dir.empty()) prepare_output_dir(values->out_dir);
    Runtime rt(g.device, g.kernel_dir);
    fmt::print("device: {} ({})\n", rt.device().name, rt.device().platform);
    auto rs = run_samplers(rt, values->opt);
    print_samplers(rs);
    int failed = 0;
    for (auto& r : rs) failed += !r.pass();
    fmt::print("{} of {} sampler tests pass (family-wise significance {:g}, Sidak)\n", rs.size() - failed, rs.size(),
               values->opt.significance);
    if (!values->out_dir.empty()) {
      std::vector<std::pair<std::string, std::string>> files;
      for (auto& [name, bytes] : sampler_plots(rs, values->plots))
        files.push_back({values->out_dir + "/plots/" + name, bytes});
      files.push_back({values->out_dir + "/samplers.json", samplers_json(rs, rt, values->opt)});
      write_files_atomically(files);
      fmt::print("wrote {}/samplers.json{}\n", values->out_dir,
                 files.size() > 1 ? fmt::format(" and {} images in plots/", files.size() - 1) : "");
    } else if (failed) {
      fmt::print("rerun with --out DIR for an observed/expected/difference image of each failed test\n");
    }
    rc = failed ? 1 : 0;
  });
}

}  // namespace mfv::cli
