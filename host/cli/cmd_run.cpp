// mfv run: the conformance suite and CI gate.
#include "checks/suite.hpp"
#include "cli/commands.hpp"
#include "report/energy_report.hpp"
#include "report/suite_baseline.hpp"
#include "report/suite_report.hpp"
#include "scene/scene_checks.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace mfv::cli {

namespace {

// mfv run's command-line values, bound to its options (Globals::command_values keeps them).
struct RunCommandOptions {
  SuiteOptions opt;
  std::string out_dir;
  int64_t samples = 0;
  std::string scene_path;
  bool compare_full = false;
  std::string baseline;
  double baseline_alpha = 1e-3;
};

}  // namespace

void add_run(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand("run",
                                 "run the conformance suite over the catalog; exit 0 exactly when every "
                                 "verdict matches expectation");
  auto values = std::make_shared<RunCommandOptions>();  // the command's values
  g.command_values.push_back(values);
  cmd->add_option("--seed", values->opt.seed, "Philox key");
  cmd->add_option("--scale", values->opt.scale,
                  "multiply every check's samples (budget); 1 = about a minute on 2 cores");
  auto* samples_opt =
      cmd->add_option("--samples", values->samples,
                      "samples per masking/furnace integral (default 4096); the other checks scale in proportion");
  cmd->add_option("--alpha-fw", values->opt.family_alpha, "family-wise false-alarm rate for the whole run")
      ->check(CLI::Range(1e-300, 0.5));
  cmd->add_option("--check", values->opt.checks,
                  "only these checks (d_norm, masking, furnace, energy, energy_diffuse, "
                  "reciprocity, closed_form)");
  cmd->add_option("--model", values->opt.models, "only models whose D/G/F or model[case] name contains one of these");
  cmd->add_option("--reference-samples", values->opt.reference_samples,
                  "samples compared with the reference per integral");
  cmd->add_option("--reference-every", values->opt.reference_every,
                  "compare every k-th integral with the reference (1 = all)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", values->out_dir, "write results.json, report.md and junit.xml here");
  cmd->add_option("--scene", values->scene_path,
                  "check only the materials this scene uses: glTF 2.0 (.gltf, .glb) or a "
                  "material file (.json naming D, G, F and parameters)");
  cmd->add_flag("--compare-full", values->compare_full,
                "with --scene: also run the full catalog and measure the time the "
                "scene saved");
  cmd->add_option("--baseline", values->baseline,
                  "earlier results.json: exit 1 if an estimate moved beyond its combined "
                  "standard errors (Welch t, Bonferroni over all integrals, as mfv energy)");
  cmd->add_option("--baseline-alpha-fw", values->baseline_alpha,
                  "family-wise false-alarm rate of the baseline comparison "
                  "(default 1e-3)")
      ->check(CLI::Range(1e-300, 0.5));
  auto* every_opt = cmd->get_option("--reference-every");
  cmd->callback([&g, &rc, samples_opt, every_opt, values] {
    if (samples_opt->count() > 0) {
      if (values->samples <= 0) throw Error(fmt::format("--samples must be a positive count, not {}", values->samples));
      values->opt.scale = double(values->samples) / double(kSuiteBaseSamples);
    }
    validate_suite_options(values->opt);
    if (values->compare_full && values->scene_path.empty()) throw Error("--compare-full needs --scene");
    const nlohmann::json base = values->baseline.empty()
                                    ? nlohmann::json()
                                    : parse_run_baseline(read_text_file(values->baseline, "--baseline"));
    // 0 when nothing moved (or no values->baseline), 1 otherwise
    auto compare = [&](const SuiteReport& rep) {
      if (values->baseline.empty()) return 0;
      BaselineDiff diff = compare_run_baseline(rep, base, values->baseline_alpha);
      print_baseline_console(diff);
      return diff.moved.empty() ? 0 : 1;
    };
    if (!values->scene_path.empty()) {
      if (!values->opt.models.empty())
        throw Error("--model and --scene cannot be combined: the scene chooses the models");
      Scene scene = load_scene(values->scene_path);  // every input error before any work
      // a scene has few integrals: compare every one with the reference
      if (every_opt->count() == 0) values->opt.reference_every = 1;
      if (!values->out_dir.empty()) prepare_output_dir(values->out_dir);
      Runtime rt(g.device, g.kernel_dir);
      SceneRun run = run_scene(rt, scene, values->opt, values->compare_full);
      print_suite_console(run.rep, rt, values->opt);
      print_scene_console(run);
      if (!values->out_dir.empty()) write_scene_outputs(run, rt, values->opt, values->out_dir);
      rc = std::max(run.rep.gate_ok() ? 0 : 1, compare(run.rep));
      return;
    }
    if (!values->out_dir.empty()) prepare_output_dir(values->out_dir);
    Runtime rt(g.device, g.kernel_dir);
    SuiteReport rep = run_suite(rt, values->opt);
    print_suite_console(rep, rt, values->opt);
    if (!values->out_dir.empty()) write_suite_outputs(rep, rt, values->opt, values->out_dir);
    rc = std::max(rep.gate_ok() ? 0 : 1, compare(rep));
  });
}

}  // namespace mfv::cli
