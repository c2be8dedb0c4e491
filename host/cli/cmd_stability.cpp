// mfv stability: where each term, each BRDF and each alternative formulation
// breaks on stiff and extreme inputs (issue 6); exit 1 when a term the
// catalog marks stable gives NaN or Inf on in-domain inputs.
#include "checks/stability.hpp"
#include "report/stability_report.hpp"
#include "cli/commands.hpp"
#include "report/files.hpp"
#include "runtime/error.hpp"
#include "scene/scene_filters.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace mfv::cli {

void add_stability(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand("stability", "sweep every term, Smith G1, D x G x F BRDF, whole model and alternative "
                                              "form over extreme inputs; report NaN/Inf/negative and error per region");
  static StabilityOptions opt;
  static std::string out;
  static bool terms_only = false;
  cmd->add_option("--out", out, "write stability.json, stability.md and plots (gnuplot) into this folder");
  cmd->add_flag("--fp64", opt.fp64, "run the kernels in double (device needs cl_khr_fp64)");
  cmd->add_flag("--terms-only", terms_only, "skip the D x G x F combinations and the whole models");
  cmd->add_option("--only", opt.only,
                  "only cases whose name contains one of these (e.g. 'D ggx', 'BRDF ggx/', 'MODEL', 'variant')");
  static std::string scene_path;
  cmd->add_option("--scene", scene_path, "only the terms, BRDFs and models the materials of this scene use (.gltf, "
                                         ".glb, material .json)");
  cmd->callback([&g, &rc] {
    Scene scene;
    if (!scene_path.empty()) {
      if (!opt.only.empty()) throw Error("--only and --scene cannot be combined: the scene chooses the cases");
      scene = load_scene(scene_path);
      scene_stability_options(scene, opt);
    }
    opt.combinations = !terms_only;
    opt.models = !terms_only;
    if (!out.empty()) prepare_output_dir(out);  // checked before the sweep, not after it
    Runtime rt(g.device, g.kernel_dir);
    StabilityReport rep = run_stability(rt, opt);
    fmt::print("{}", stability_console(rep));
    if (!scene_path.empty()) print_scene_stability(scene, rep);
    if (!out.empty())
      for (auto& line : write_stability_outputs(rep, out)) fmt::print("{}\n", line);
    rc = rep.gate_pass() ? 0 : 1;
  });
}

}  // namespace mfv::cli
