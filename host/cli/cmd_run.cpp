// mfv run: the conformance suite and CI gate.
#include "checks/compile_ahead.hpp"
#include "checks/profile.hpp"
#include "checks/suite.hpp"
#include "cli/run_shard.hpp"
#include "cli/shared_options.hpp"
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
#include <utility>

namespace mfv::cli {

namespace {

// mfv run: its values, bound to its options, and its work.
struct RunCommand : SharedValues {
  SuiteOptions opt;
  bool compare_full = false;
  double baseline_alpha = 1e-3;
  CLI::Option* every_opt = nullptr;
  std::string profile = "default";
  bool dry = false;

  void add_options(CLI::App* cmd) {
    cmd->description(
        "run the conformance suite over the catalog; exit 0 exactly when every verdict matches expectation");
    SharedOptions(cmd, *this)
        .seed(opt.seed)
        .budget(opt.scale, opt.family_alpha)
        .out("results.json, report.md and junit.xml")
        .scene(
            "check only the materials this scene uses: glTF 2.0 (.gltf, .glb) or a material file (.json naming D, G, "
            "F and parameters)")
        .baseline(
            "earlier results.json: exit 1 if an estimate moved beyond its combined standard errors (Welch t, "
            "Bonferroni over all integrals, as mfv energy)",
            "--baseline-alpha-fw", baseline_alpha)
        .shard("the plan", "shard.json", "mfv merge");
    cmd->add_option("--check", opt.checks, "only these checks (" + suite_check_list() + ")");
    cmd->add_option("--model", opt.models, "only models whose D/G/F or model[case] name contains one of these");
    cmd->add_option("--reference-samples", opt.reference_samples, "samples compared with the reference per integral");
    every_opt = cmd->add_option("--reference-every", opt.reference_every,
                                "compare every k-th integral with the reference (1 = all)")
                    ->check(CLI::PositiveNumber);
    cmd->add_option("--profile", profile,
                    "default: the CI-sized run; deep: denser widths, views, lights and F parameters (over 10^6 "
                    "integrals, docs/scale.md)");
    cmd->add_flag("--dry-run", dry, "print the plan's integrals, samples and estimated time on this device; run nothing");
    cmd->add_flag("--compare-full", compare_full,
                  "with --scene: also run the full catalog and measure the time the scene saved");
  }

  int run(const Globals& g) {
    apply_samples(opt.scale);
    opt.density = profile_density(profile);
    validate_suite_options(opt);
    if (compare_full && scene_path.empty()) throw Error("--compare-full needs --scene");
    const nlohmann::json base =
        baseline.empty() ? nlohmann::json() : parse_run_baseline(read_text_file(baseline, "--baseline"));
    // 0 when nothing moved (or no baseline), 1 otherwise
    auto compare = [&](const SuiteReport& rep) {
      if (baseline.empty()) return 0;
      BaselineDiff diff = compare_run_baseline(rep, base, baseline_alpha);
      print_baseline_console(diff);
      return diff.moved.empty() ? 0 : 1;
    };
    if (dry && !scene_path.empty()) throw Error("--dry-run does not apply to --scene");
    if (opt.density > 1 && !scene_path.empty()) throw Error("--profile does not apply to --scene");
    if (is_device_set(g.device) && (dry || !scene_path.empty() || (!shard.empty() && shard != "off")))
      throw Error(fmt::format("--device {} (several devices) does not apply to {} yet: give one device", g.device,
                              dry ? "--dry-run" : !scene_path.empty() ? "--scene" : "--shard"));
    if (dry) return dry_run(g, opt, shard_of(shard, shard_count));
    if (std::optional<ShardSpec> s = shard_of(scene_path.empty() ? shard : "off", shard_count)) {
      if (is_device_set(g.device))
        throw Error(fmt::format("--device {} (several devices) does not apply to a shard ({}) yet", g.device,
                                s->source));
      if (!baseline.empty()) throw Error("--baseline applies to the merged run (mfv merge), not to a shard");
      return run_shard(g, opt, *s, out_dir);
    }
    if (!shard.empty() && !scene_path.empty() && shard != "off") throw Error("--shard does not apply to --scene");
    if (!scene_path.empty()) {
      // every input error before any work
      const Scene scene = load_scene_instead_of(!opt.models.empty(), "--model", "models");
      // a scene has few integrals: compare every one with the reference
      if (every_opt->count() == 0) opt.reference_every = 1;
      prepare_out();
      Runtime rt(g.device, g.kernel_dir);
      SceneRun scene_run = run_scene(rt, scene, opt, compare_full);
      print_suite_console(scene_run.rep, rt, opt);
      print_scene_console(scene_run);
      if (!out_dir.empty()) write_scene_outputs(scene_run, rt, opt, out_dir);
      return std::max(scene_run.rep.gate_ok() ? 0 : 1, compare(scene_run.rep));
    }
    prepare_out();
    if (is_device_set(g.device)) return run_on_devices(g, opt, compare);
    SuitePlans plans = make_suite_plans(opt);
    // where a core is free (MFV_COMPILE_AHEAD unset or auto) or MFV_COMPILE_AHEAD=1:
    // a child process compiles the run's kernels from its end meanwhile
    // (checks/compile_ahead.hpp), forked before this process's first OpenCL call
    CompileAhead ahead(plans, opt, g.device, g.kernel_dir);
    if (ahead.only()) return ahead.wait() == 0 ? 0 : 1;
    Runtime rt(g.device, g.kernel_dir);
    // the child builds the integration program and the float sample_values; the run waits for them (bounded)
    if (ahead.started()) rt.set_hand_over([&ahead](HandOver what) { return ahead.await(what); });
    SuiteReport rep = run_suite(rt, opt, std::move(plans));
    ahead.end();  // every kernel of the run has been launched
    print_suite_console(rep, rt, opt);
    if (!out_dir.empty()) write_suite_outputs(rep, rt, opt, out_dir);
    return std::max(rep.gate_ok() ? 0 : 1, compare(rep));
  }

  // --device all or a list: every plan's integration shared by the devices
  // (checks/device_share.hpp), the rest on the first.
  template <class Compare>
  int run_on_devices(const Globals& g, const SuiteOptions& o, Compare& compare) {
    const std::vector<DeviceInfo> devices = select_devices(g.device);
    std::vector<std::unique_ptr<Runtime>> more;  // built before the first, whose device the provenance records
    for (size_t d = 1; d < devices.size(); ++d) more.push_back(std::make_unique<Runtime>(devices[d], g.kernel_dir));
    Runtime rt(devices[0], g.kernel_dir);
    std::vector<Runtime*> others;
    for (auto& m : more) others.push_back(m.get());
    SuiteReport rep = run_suite(rt, o, others);
    print_suite_console(rep, rt, o);
    if (!out_dir.empty()) write_suite_outputs(rep, rt, o, out_dir);
    return std::max(rep.gate_ok() ? 0 : 1, compare(rep));
  }
};

}  // namespace

void add_run(CLI::App& app, Globals& g, int& rc) { add_command<RunCommand>(app, g, rc, "run"); }

}  // namespace mfv::cli
