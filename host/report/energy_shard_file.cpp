#include "report/energy_shard_file.hpp"

#include "util/error.hpp"

#include <fmt/format.h>

namespace mfv {
using nlohmann::json;

UnitShard energy_unit_shard(const EnergyPlanSummary& plan, uint64_t seed) {
  return {{"energy_shard.json", "mfv-energy-shard/1", "mfv energy --shard K/N"}, plan, seed, "units"};
}

std::string energy_shard_json(const EnergyPart& part, const EnergyOptions& opt, const ShardSpec& s,
                              const EnergyPlanSummary& plan, const std::string& device, const json& provenance) {
  json j = plan_shard_json(energy_unit_shard(plan, opt.seed), s, {part.lo, part.hi}, device, provenance);
  j["measured"] = {{"samples", part.samples},
                   {"topped_up", part.topped_up},
                   {"seconds", part.seconds},
                   {"build_seconds", part.build_seconds}};
  j["reference"] = {{"compared", part.reference_compared},
                    {"worst", shard_bits({part.reference_worst})},
                    {"worst_at", part.reference_worst_at}};
  json units = json::array();
  for (auto& r : part.results)
    units.push_back({{"done", r.done}, {"sum", shard_bits(r.sum)}, {"b_sum", shard_bits(r.b_sum)}});
  j["units"] = units;
  j["complete"] = true;  // a file cut short fails to parse or lacks this
  return j.dump();
}

EnergyShards read_energy_shards(const std::vector<std::string>& inputs, const EnergyOptions& opt) {
  const EnergyPlanSummary plan = energy_plan_summary(opt);
  EnergyShards m;
  const UnitShards read =
      read_unit_shards(inputs, energy_unit_shard(plan, opt.seed), [&](const ShardDoc& s, const json& units) {
        EnergyPart part;
        part.lo = s.doc.at("shard").at("lo").get<size_t>();
        part.hi = s.doc.at("shard").at("hi").get<size_t>();
        for (auto& u : units) {
          EnergyUnitResult r{shard_doubles(u.at("sum")), shard_doubles(u.at("b_sum")), u.at("done").get<uint64_t>()};
          if (r.sum.size() != size_t(opt.replicates) || r.b_sum.size() != r.sum.size())
            throw Error(fmt::format("a unit has {} replicates, the plan {}", r.sum.size(), opt.replicates));
          part.results.push_back(std::move(r));
        }
        const json& me = s.doc.at("measured");
        part.samples = me.at("samples").get<uint64_t>();
        part.topped_up = me.at("topped_up").get<size_t>();
        part.seconds = me.at("seconds").get<double>();
        part.build_seconds = me.at("build_seconds").get<double>();
        const json& ref = s.doc.at("reference");
        part.reference_compared = ref.at("compared").get<size_t>();
        part.reference_worst = shard_doubles(ref.at("worst")).at(0);
        part.reference_worst_at = ref.at("worst_at").get<std::string>();
        m.parts.push_back(std::move(part));
      });
  m.device = read.device;
  m.lines = read.lines;
  return m;
}

}  // namespace mfv
