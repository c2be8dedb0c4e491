#include "cli/app.hpp"

#include "cli/strict_numbers.hpp"
#include "util/error.hpp"

#include <string>

namespace mfv::cli {

void build_app(CLI::App& app, Globals& g, int& rc) {
  app.require_subcommand(1);
  app.add_option("--device", g.device,
                 "OpenCL device: index, exact name, or a name substring that matches one "
                 "device (default: first GPU, else CPU); bench and run: all, run: a comma list (docs/scale.md)");
  app.add_option("--kernel-dir", g.kernel_dir, "read kernels from this folder instead of the embedded copies")
      ->check(CLI::ExistingDirectory);
  add_devices(app, g, rc);
  add_list(app, g, rc);
  add_agree(app, g, rc);
  add_eval(app, g, rc);
  add_run(app, g, rc);
  add_stability(app, g, rc);
  add_energy(app, g, rc);
  add_check(app, g, rc);
  add_samplers(app, g, rc);
  add_bench(app, g, rc);
  add_convergence(app, g, rc);
  add_merge(app, g, rc);
  make_options_strict(app);
}

void parse_command_line(CLI::App& app, int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--device" || a == "--kernel-dir") {
      ++i;
      continue;
    }
    if (a.rfind("-", 0) == 0) continue;
    bool known = false;
    std::string names;
    for (auto* sub : app.get_subcommands({})) {
      known = known || sub->get_name() == a;
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) throw Error("unknown command '" + a + "' (commands: " + names + "; see 'mfv --help')");
    break;
  }
  app.parse(argc, argv);
}

}  // namespace mfv::cli
