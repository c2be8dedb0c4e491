// mfv run --shard K/N (a deterministic part of the run, into DIR/shard.json)
// and mfv merge DIR... --out DIR (the shards into one run's results,
// judged once over the whole run). docs/scale.md.
#include "cli/run_shard.hpp"

#include "report/shard_file.hpp"
#include "report/suite_report.hpp"
#include "runtime/opencl.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace mfv::cli {

std::optional<ShardSpec> shard_of(const std::string& option, uint32_t count) {
  if (option == "off") return std::nullopt;
  if (!option.empty()) return parse_shard_option(option);
  std::optional<ShardSpec> s = shard_from_environment(count);
  if (!s) return s;
  fmt::print(stderr, "mfv: shard {}/{} from {}\n", s->index + 1, s->count, s->source);
  // Bazel asks a test that shards to touch this file.
  if (const char* status = std::getenv("TEST_SHARD_STATUS_FILE"); status && *status) {
    std::ofstream touch(status, std::ios::app);
    if (!touch) throw Error(fmt::format("cannot touch TEST_SHARD_STATUS_FILE '{}'", status));
  }
  return s;
}

int run_unit_shard(const Globals& g, const UnitShard& u, const ShardSpec& s, const std::string& out_dir,
                   const std::function<std::string(Runtime&, std::pair<size_t, size_t>)>& run) {
  const std::pair<size_t, size_t> part = cut_by_cost(u.plan.cost, s);
  fmt::print("{}\n", plan_shard_line(u, s, part));
  prepare_output_dir(out_dir);
  Runtime rt(g.device, g.kernel_dir);
  write_files_atomically({{out_dir + "/" + u.kind.file, run(rt, part)}});
  const std::string command = u.kind.writer.substr(0, u.kind.writer.find(" --shard"));
  fmt::print("wrote {}/{}: no verdict yet; {} --merge the {} shards' folders (same options) --out DIR writes the "
             "whole run's outputs\n",
             out_dir, u.kind.file, command, s.count);
  return 0;
}

int run_shard(const Globals& g, const SuiteOptions& opt, const ShardSpec& shard, const std::string& out_dir) {
  if (out_dir.empty()) throw Error("a shard's records go to DIR/shard.json: give --out DIR (then mfv merge the DIRs)");
  SuitePlans sp = make_suite_plans(opt);
  const std::string hash = plan_hash(sp, opt);
  const size_t integrals = plan_integrals(sp);
  const std::vector<size_t> positions = cut_to_shard(sp, opt, shard);
  fmt::print("shard {}/{} (from {}): {} of {} integrals; plan {}, seed {}\n", shard.index + 1, shard.count,
             shard.source, positions.size(), integrals, hash, opt.seed);
  prepare_output_dir(out_dir);
  Runtime rt(g.device, g.kernel_dir);
  SuiteReport rep;
  if (!positions.empty()) run_suite_plans(rt, sp, opt, rep);
  write_files_atomically(
      {{out_dir + "/shard.json", shard_json(rep, sp, positions, opt, shard, hash, integrals, output_context(rt))}});
  double seconds = 0;
  uint64_t samples = 0;
  for (auto& c : rep.stats) seconds += c.seconds, samples += c.samples;
  fmt::print("device: {}; {} samples, {:.1f} s of integration, kernel builds {:.2f} s\n", rt.device().name, samples,
             seconds, rep.build_seconds);
  fmt::print("wrote {}/shard.json: no verdict yet; mfv merge the {} shards' folders --out DIR judges the whole run\n",
             out_dir, shard.count);
  return 0;
}

namespace {

struct MergeCommand : SharedValues {
  std::vector<std::string> inputs;

  void add_options(CLI::App* cmd) {
    cmd->description(
        "merge the folders of mfv run --shard K/N into one run's results.json, report.md and junit.xml, judged once "
        "over the whole run; exit 0 exactly when every verdict matches expectation, 2 for a missing, duplicated, "
        "truncated or foreign shard");
    cmd->add_option("shards", inputs, "the shards' --out folders (or their shard.json files)")->required();
    SharedOptions(cmd, *this).out("results.json, report.md and junit.xml");
  }

  int run(const Globals&) {
    MergedRun m = merge_shards(inputs);  // every check before any output
    prepare_out();
    for (auto& line : m.lines) fmt::print("{}\n", line);
    print_suite_console(m.rep, m.ctx.device, m.opt);
    if (!out_dir.empty()) write_files_atomically(suite_output_files(m.rep, m.ctx, m.opt, out_dir));
    return m.rep.gate_ok() ? 0 : 1;
  }
};

}  // namespace

void add_merge(CLI::App& app, Globals& g, int& rc) { add_command<MergeCommand>(app, g, rc, "merge"); }

}  // namespace mfv::cli
