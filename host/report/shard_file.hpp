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

#include <string>
#include <vector>

namespace mfv {

// The run's records of shard `s`: `cut` is the plan as run_suite_plans ran
// it (cut_to_shard), `positions` what cut_to_shard returned.
std::string shard_json(const SuiteReport& rep, const SuitePlans& cut, const std::vector<size_t>& positions,
                       const SuiteOptions& opt, const ShardSpec& s, const std::string& hash, size_t integrals,
                       const OutputContext& ctx);

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
