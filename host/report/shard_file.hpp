// A shard's file (mfv run --shard K/N --out DIR writes DIR/shard.json, schema
// mfv-shard/1) and mfv merge's reading of them: the shard's records before
// any verdict, at full precision, with the plan's hash, seed, tool version
// and the whole-run position of each record. Merging rebuilds the plan from
// the recorded options, checks every shard against it (docs/scale.md) and
// judges the merged records once: the family-wise correction counts the
// whole run.
#pragma once

#include "checks/shard.hpp"
#include "report/suite_report.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace mfv {

// The run's records of shard `s`: `cut` is the plan as run_suite_plans ran
// it (cut_to_shard), `positions` what cut_to_shard returned.
std::string shard_json(const SuiteReport& rep, const SuitePlans& cut, const std::vector<size_t>& positions,
                       const SuiteOptions& opt, const ShardSpec& s, const std::string& hash, size_t integrals,
                       const OutputContext& ctx);

// One shard's file as read: its path, its JSON, its 0-based index and count.
struct ShardDoc {
  std::string path;
  nlohmann::json doc;
  uint32_t index = 0, count = 0;
  std::string name() const;  // "shard 2/3 (PATH)"
};
// Which shard files: DIR/`file` of schema `schema`, written by `writer`.
struct ShardKind {
  std::string file, schema, writer;
};
// The checks every merge makes before reading any record (docs/scale.md):
// each input's file parses, has the schema and its closing `complete`, was
// written by this mfv (version and commit), has the first's count, seed,
// plan hash and options; none given twice, none missing. Returns the shards
// by index; throws mfv::Error naming the shard.
std::vector<ShardDoc> read_shard_set(const std::vector<std::string>& inputs, const ShardKind& kind);
// {"version", "commit", "describe"} of this mfv, as a shard file records it.
nlohmann::json shard_tool_json();

// A double at full precision (JSON has no NaN or infinity: those as text), and back.
nlohmann::json shard_number(double x);
double shard_number_of(const nlohmann::json& j);
// Doubles as their bit patterns: exact, NaN and infinities included.
nlohmann::json shard_bits(const std::vector<double>& v);
std::vector<double> shard_doubles(const nlohmann::json& a);

// The shard files of a command whose plan is cut into whole units
// (checks/unit_plan.hpp: mfv energy's cells, mfv agree's and mfv stability's
// cases), given the plan by the command's own options. Each file is
// plan_shard_json's header, the command's fields, and "units": one entry per
// unit [lo, hi) of the shard, in plan order.
struct UnitShard {
  ShardKind kind;
  const UnitPlan& plan;
  nlohmann::json seed;  // the plan's seed (null where a command has none)
  std::string noun;     // what a unit is, for the console ("units", "cases")
};
// The header: schema, tool, plan {hash, units, options {seed}}, shard
// {index, count, source, date, lo, hi}, device {name}, provenance; the
// caller adds its fields and "units", then "complete": true last.
nlohmann::json plan_shard_json(const UnitShard& u, const ShardSpec& s, std::pair<size_t, size_t> part,
                               const std::string& device, const nlohmann::json& provenance);
// "shard 2/3 (from --shard): cases 5..9 of 14; plan HASH, seed 5", as a shard prints it first.
std::string plan_shard_line(const UnitShard& u, const ShardSpec& s, std::pair<size_t, size_t> part);
struct UnitShards {
  std::string device;              // the shards' devices, " + " between different ones
  std::vector<std::string> lines;  // one per shard, for the console
};
// read_shard_set, then each shard against the merge's plan: its seed, its
// hash and its units [lo, hi) as cut_by_cost gives them; `read` takes the
// shard's own fields and its units (in index order). Throws mfv::Error
// naming the shard ("...; nothing merged").
UnitShards read_unit_shards(const std::vector<std::string>& inputs, const UnitShard& u,
                            const std::function<void(const ShardDoc&, const nlohmann::json& units)>& read);

struct MergedRun {
  SuiteReport rep;  // judged
  SuiteOptions opt;
  OutputContext ctx;
  std::vector<std::string> lines;  // one per shard, for the console
};

// Reads DIR/shard.json of each input (a folder, or the file itself) and
// merges them; throws mfv::Error naming the shard for a missing, duplicated,
// truncated or foreign shard (another plan, seed, count or tool version).
MergedRun merge_shards(const std::vector<std::string>& inputs);

}  // namespace mfv
