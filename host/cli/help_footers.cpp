// The end of every `mfv COMMAND --help`: the global options (CLI11 lists only
// the command's own) and examples to start from (docs/cli/ has the rest).
#include "cli/commands.hpp"

#include <map>
#include <string>

namespace mfv::cli {

void add_help_footers(CLI::App& app) {
  static const std::map<std::string, std::string> examples = {
      {"run",
       "  mfv run\n  mfv run --out results --scale 4\n  mfv run --check masking --model ggx/smith\n"
       "  mfv run --scene scene.gltf --out results/scene\n  mfv run --out new --baseline old/results.json"},
      {"check",
       "  mfv check --brdf examples/brdf/ggx.cl --as ggx/smith_ggx_correlated/schlick\n"
       "  mfv check --brdf my_brdf.cl --param f0=0.04 --check furnace reciprocity finite --out check"},
      {"energy",
       "  mfv energy --out results/energy\n  mfv energy --models ggx/smith_ggx_correlated --grid 16x16\n"
       "  mfv energy --models ggx/ --baseline results/energy/energy.json"},
      {"stability", "  mfv stability\n  mfv stability --fp64 --out results/stability\n  mfv stability --only ggx"},
      {"agree", "  mfv agree\n  mfv agree --samples 100000 --only ggx --fp64"},
      {"samplers", "  mfv samplers\n  mfv samplers --samples 262144 --device-only --out results/samplers --plots"},
      {"bench", "  mfv bench --out results/bench\n  mfv bench --integrand albedo --repeats 9"},
      {"convergence",
       "  mfv convergence --out\n  mfv convergence --case ggx:0.01:0.05 --check albedo --estimator vndf"},
      {"eval",
       "  mfv eval ggx/smith_ggx_correlated/schlick --alpha 0.3 --param f0=0.04 --wi 0.3,0,0.953939 "
       "--wo -0.2,0.1,0.974679\n  mfv eval ggx --param alpha=0.01 --NoH 1"},
      {"list", "  mfv list\n  mfv list --json"},
      {"devices", "  mfv devices\n  mfv --device 1 run"},
  };
  const std::string globals =
      "Global options (before or after the command): --device N|NAME, --kernel-dir DIR, --quiet, --version; "
      "see 'mfv --help'.";
  for (auto* sub : app.get_subcommands({})) {
    auto it = examples.find(sub->get_name());
    sub->footer(globals + (it == examples.end() ? "" : "\n\nExamples:\n" + it->second));
  }
}

}  // namespace mfv::cli
