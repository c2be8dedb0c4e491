// mfv energy --shard K/N --out DIR writes DIR/energy_shard.json (schema
// mfv-energy-shard/1): its units' reported runs (per-replicate sums, bit
// exact) with the plan's hash, seed, tool version and shard index, read and
// checked by mfv energy --merge with report/shard_file.hpp's rules
// (docs/scale.md).
#pragma once

#include "checks/energy.hpp"
#include "checks/shard.hpp"
#include "report/shard_file.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace mfv {

// mfv energy's shard files (report/shard_file.hpp's units: the cells).
UnitShard energy_unit_shard(const EnergyPlanSummary& plan, uint64_t seed);

std::string energy_shard_json(const EnergyPart& part, const EnergyOptions& opt, const ShardSpec& s,
                              const EnergyPlanSummary& plan, const std::string& device, const nlohmann::json& provenance);

struct EnergyShards {
  std::vector<EnergyPart> parts;   // by index
  std::string device;              // the shards' devices, " + " between different ones
  std::vector<std::string> lines;  // one per shard, for the console
};

// Reads DIR/energy_shard.json of each input (a folder or the file) and checks
// them against the plan `opt` gives (hash, seed, each shard's units); throws
// mfv::Error naming the shard for a missing, duplicated, truncated or foreign one.
EnergyShards read_energy_shards(const std::vector<std::string>& inputs, const EnergyOptions& opt);

}  // namespace mfv
