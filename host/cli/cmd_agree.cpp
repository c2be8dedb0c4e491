// mfv agree: kernel vs reference on identical inputs, every term and BRDF;
// --shard K/N runs a part of the cases, --merge joins the parts (docs/scale.md).
#include "checks/agree.hpp"
#include "cli/run_shard.hpp"
#include "cli/shared_options.hpp"
#include "report/agree_report.hpp"
#include "report/pointwise_shard_file.hpp"
#include "runtime/provenance.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

namespace mfv::cli {

namespace {

// mfv agree: its values, bound to its options, and its work.
struct AgreeCommand : SharedValues {
  AgreeOptions opt;

  void add_options(CLI::App* cmd) {
    cmd->description(
        "evaluate every term and D x G x F BRDF on the device and in the double reference on identical inputs; fail "
        "beyond the ULP table");
    cmd->add_option("--samples", opt.samples, "inputs per term or combination")->check(CLI::Range(1ull, 1ull << 40));
    SharedOptions(cmd, *this)
        .seed(opt.seed)
        .fp64(opt.fp64)
        .terms_only("the D x G x F combinations")
        .only(opt.only, "ggx, 'BRDF phong'")
        .out("agree.json")
        .shard("the cases", "agree_shard.json", "mfv agree --merge", "cases' results, evaluating nothing");
  }

  // mfv agree --shard K/N: the shard's cases into out_dir/agree_shard.json, no verdict.
  int agree_shard(const Globals& g, const ShardSpec& s) {
    const UnitPlan plan = agree_plan(opt);
    const UnitShard u = agree_unit_shard(plan, opt.seed);
    return run_unit_shard(g, u, s, out_dir, [&](Runtime& rt, std::pair<size_t, size_t> part) {
      return agree_shard_json(run_agree(rt, opt, part), u, s, part, rt.device().name, provenance_json());
    });
  }

  int run(const Globals& g) {
    opt.combinations = !terms_only;
    if (std::optional<ShardSpec> s = shard_to_run("agree_shard.json", "mfv agree --merge")) return agree_shard(g, *s);
    AgreeReport rep;
    std::string device, line;
    if (!merge.empty()) {
      const UnitPlan plan = agree_plan(opt);
      AgreeShards shards = read_agree_shards(merge, agree_unit_shard(plan, opt.seed));  // every check before output
      prepare_out();
      for (auto& l : shards.lines) fmt::print("{}\n", l);
      rep = std::move(shards.rep);
      rep.shards = shards.lines;
      device = shards.device;
      line = fmt::format("device: {} ({} shards merged); kernels in {}", device, shards.lines.size(),
                         opt.fp64 ? "float64" : "float32");
    } else {
      prepare_out();
      Runtime rt(g.device, g.kernel_dir);
      rep = run_agree(rt, opt);
      device = rt.device().name;
      line = fmt::format("device: {} ({}), {}; kernels in {}", device, rt.device().platform, rt.device().driver,
                         opt.fp64 ? "float64" : "float32");
    }
    fmt::print("{}", agree_console(rep, line));
    if (!out_dir.empty()) {
      write_files_atomically({{out_dir + "/agree.json", agree_json(rep, opt, device)}});
      fmt::print("wrote {}/agree.json\n", out_dir);
    }
    return agree_failures(rep) ? 1 : 0;
  }
};

}  // namespace

void add_agree(CLI::App& app, Globals& g, int& rc) { add_command<AgreeCommand>(app, g, rc, "agree"); }

}  // namespace mfv::cli
