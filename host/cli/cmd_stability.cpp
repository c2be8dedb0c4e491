// mfv stability: where each term, each BRDF and each alternative formulation
// breaks on stiff and extreme inputs (issue 6); exit 1 when a term the
// catalog marks stable gives NaN or Inf on in-domain inputs. --shard K/N
// runs a part of the cases, --merge joins the parts (docs/scale.md).
#include "checks/stability.hpp"
#include "cli/run_shard.hpp"
#include "cli/shared_options.hpp"
#include "report/pointwise_shard_file.hpp"
#include "report/stability_report.hpp"
#include "runtime/provenance.hpp"
#include "scene/scene_filters.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

namespace mfv::cli {

namespace {

// mfv stability: its values, bound to its options, and its work.
struct StabilityCommand : SharedValues {
  StabilityOptions opt;

  void add_options(CLI::App* cmd) {
    cmd->description(
        "sweep every term, Smith G1, D x G x F BRDF, whole model and alternative form over extreme inputs; report "
        "NaN/Inf/negative and error per region");
    SharedOptions(cmd, *this)
        .out("stability.json, stability.md and plots (gnuplot)")
        .fp64(opt.fp64)
        .only(opt.only, "'D ggx', 'BRDF ggx/', 'MODEL', 'variant'")
        .scene("only the terms, BRDFs and models the materials of this scene use (.gltf, .glb, material .json)")
        .terms_only("the D x G x F combinations and the whole models")
        .shard("the cases", "stability_shard.json", "mfv stability --merge", "cases' results, evaluating nothing");
  }

  // mfv stability --shard K/N: the shard's cases into out_dir/stability_shard.json, no verdict.
  int stability_shard(const Globals& g, const ShardSpec& s) {
    const UnitPlan plan = stability_plan(opt);
    const UnitShard u = stability_unit_shard(plan);
    return run_unit_shard(g, u, s, out_dir, [&](Runtime& rt, std::pair<size_t, size_t> part) {
      return stability_shard_json(run_stability(rt, opt, part), u, s, part, provenance_json());
    });
  }

  int run(const Globals& g) {
    const Scene scene = load_scene_instead_of(!opt.only.empty(), "--only", "cases");
    if (!scene_path.empty()) scene_stability_options(scene, opt);
    opt.combinations = !terms_only;
    opt.models = !terms_only;
    if (std::optional<ShardSpec> s = shard_to_run("stability_shard.json", "mfv stability --merge"))
      return stability_shard(g, *s);
    StabilityReport rep;
    if (!merge.empty()) {
      const UnitPlan plan = stability_plan(opt);
      const StabilityShards shards = read_stability_shards(merge, stability_unit_shard(plan));  // before any output
      prepare_out();
      for (auto& l : shards.lines) fmt::print("{}\n", l);
      rep = merge_stability(shards.parts);
      rep.shards = shards.lines;
    } else {
      prepare_out();
      Runtime rt(g.device, g.kernel_dir);
      rep = run_stability(rt, opt);
    }
    fmt::print("{}", stability_console(rep));
    if (!scene_path.empty()) print_scene_stability(scene, rep);
    if (!out_dir.empty())
      for (auto& line : write_stability_outputs(rep, out_dir)) fmt::print("{}\n", line);
    return rep.gate_pass() ? 0 : 1;
  }
};

}  // namespace

void add_stability(CLI::App& app, Globals& g, int& rc) { add_command<StabilityCommand>(app, g, rc, "stability"); }

}  // namespace mfv::cli
