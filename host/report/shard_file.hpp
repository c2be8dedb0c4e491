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

#include <string>
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
