// mfv stability: where each term, each BRDF and each alternative formulation
// breaks on stiff and extreme inputs (issue 6); exit 1 when a term the
// catalog marks stable gives NaN or Inf on in-domain inputs.
#include "checks/stability.hpp"
#include "cli/commands.hpp"
#include "report/stability_report.hpp"
#include "scene/scene_filters.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <memory>

namespace mfv::cli {

namespace {

// mfv stability's command-line values, bound to its options (Globals::command_values keeps them).
struct StabilityCommandOptions {
  StabilityOptions opt;
  std::string out;
  bool terms_only = false;
  std::string scene_path;
};

}  // namespace

void add_stability(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand("stability",
                                 "sweep every term, Smith G1, D x G x F BRDF, whole model and alternative "
                                 "form over extreme inputs; report NaN/Inf/negative and error per region");
  auto values = std::make_shared<StabilityCommandOptions>();  // the command's values
  g.command_values.push_back(values);
  cmd->add_option("--out", values->out, "write stability.json, stability.md and plots (gnuplot) into this folder");
  cmd->add_flag("--fp64", values->opt.fp64, "run the kernels in double (device needs cl_khr_fp64)");
  cmd->add_flag("--terms-only", values->terms_only, "skip the D x G x F combinations and the whole models");
  cmd->add_option("--only", values->opt.only,
                  "only cases whose name contains one of these (e.g. 'D ggx', 'BRDF ggx/', 'MODEL', 'variant')");
  cmd->add_option("--scene", values->scene_path,
                  "only the terms, BRDFs and models the materials of this scene use (.gltf, "
                  ".glb, material .json)");
  cmd->callback([&g, &rc, values] {
    Scene scene;
    if (!values->scene_path.empty()) {
      if (!values->opt.only.empty()) throw Error("--only and --scene cannot be combined: the scene chooses the cases");
      scene = load_scene(values->scene_path);
      scene_stability_options(scene, values->opt);
    }
    values->opt.combinations = !values->terms_only;
    values->opt.models = !values->terms_only;
    if (!values->out.empty()) prepare_output_dir(values->out);  // checked before the sweep, not after it
    Runtime rt(g.device, g.kernel_dir);
    StabilityReport rep = run_stability(rt, values->opt);
    fmt::print("{}", stability_console(rep));
    if (!values->scene_path.empty()) print_scene_stability(scene, rep);
    if (!values->out.empty())
      for (auto& line : write_stability_outputs(rep, values->out)) fmt::print("{}\n", line);
    rc = rep.gate_pass() ? 0 : 1;
  });
}

}  // namespace mfv::cli
