// mfv agree --shard K/N and mfv stability --shard K/N (docs/scale.md): DIR/
// agree_shard.json (schema mfv-agree-shard/1) and DIR/stability_shard.json
// (mfv-stability-shard/1), one unit per case of the shard, every number
// exact, with report/shard_file.hpp's header (plan hash, seed, tool
// version, shard index); read back and checked by the command's --merge.
#pragma once

#include "checks/agree.hpp"
#include "checks/stability.hpp"
#include "report/shard_file.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace mfv {

UnitShard agree_unit_shard(const UnitPlan& plan, uint64_t seed);
// `part`: the shard's cases [lo, hi) of the plan, run_agree's report of them.
std::string agree_shard_json(const AgreeReport& part, const UnitShard& u, const ShardSpec& s,
                             std::pair<size_t, size_t> cases, const std::string& device,
                             const nlohmann::json& provenance);
struct AgreeShards {
  AgreeReport rep;                 // the whole run's cases, in plan order
  std::string device;              // the shards' devices
  std::vector<std::string> lines;  // one per shard, for the console
};
// Throws mfv::Error naming the shard for a missing, duplicated, truncated or foreign one.
AgreeShards read_agree_shards(const std::vector<std::string>& inputs, const UnitShard& u);

UnitShard stability_unit_shard(const UnitPlan& plan);
std::string stability_shard_json(const StabilityReport& part, const UnitShard& u, const ShardSpec& s,
                                 std::pair<size_t, size_t> cases, const nlohmann::json& provenance);
struct StabilityShards {
  std::vector<StabilityReport> parts;  // by index (merge_stability joins them)
  std::vector<std::string> lines;
};
StabilityShards read_stability_shards(const std::vector<std::string>& inputs, const UnitShard& u);

}  // namespace mfv
