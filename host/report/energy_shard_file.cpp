#include "report/energy_shard_file.hpp"

#include "report/shard_file.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

namespace mfv {
namespace {

using nlohmann::json;

const ShardKind kKind{"energy_shard.json", "mfv-energy-shard/1", "mfv energy --shard K/N"};

// Doubles as their bit patterns: exact, NaN and infinities included.
json bits(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) {
    uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    a.push_back(b);
  }
  return a;
}
std::vector<double> doubles(const json& a) {
  std::vector<double> v;
  for (auto& e : a) {
    const uint64_t b = e.get<uint64_t>();
    double x;
    std::memcpy(&x, &b, sizeof x);
    v.push_back(x);
  }
  return v;
}

}  // namespace

std::string energy_shard_json(const EnergyPart& part, const EnergyOptions& opt, const ShardSpec& s,
                              const EnergyPlanSummary& plan, const std::string& device, const json& provenance) {
  json j;
  j["schema"] = kKind.schema;
  j["tool"] = shard_tool_json();
  j["plan"] = {{"hash", plan.hash}, {"units", plan.cost.size()}, {"options", {{"seed", opt.seed}}}};
  j["shard"] = {{"index", s.index + 1}, {"count", s.count}, {"source", s.source}, {"date", utc_timestamp()},
                {"lo", part.lo},        {"hi", part.hi}};
  j["device"] = {{"name", device}};
  j["provenance"] = provenance;
  j["measured"] = {{"samples", part.samples}, {"topped_up", part.topped_up}, {"seconds", part.seconds},
                   {"build_seconds", part.build_seconds}};
  j["reference"] = {{"compared", part.reference_compared},
                    {"worst", bits({part.reference_worst})},
                    {"worst_at", part.reference_worst_at}};
  json units = json::array();
  for (auto& r : part.results) units.push_back({{"done", r.done}, {"sum", bits(r.sum)}, {"b_sum", bits(r.b_sum)}});
  j["units"] = units;
  j["complete"] = true;  // a file cut short fails to parse or lacks this
  return j.dump();
}

EnergyShards read_energy_shards(const std::vector<std::string>& inputs, const EnergyOptions& opt) {
  const std::vector<ShardDoc> shards = read_shard_set(inputs, kKind);
  const EnergyPlanSummary plan = energy_plan_summary(opt);
  EnergyShards m;
  std::vector<std::string> devices;
  for (const ShardDoc& s : shards) {
    // read_shard_set checked plan, hash and options alike in every shard
    const json& p = s.doc.at("plan");
    if (p.at("options").at("seed") != json(opt.seed))
      throw Error(fmt::format("{} ran seed {}, this merge --seed {}: nothing merged", s.name(),
                              p.at("options").at("seed").dump(), opt.seed));
    if (p.at("hash") != json(plan.hash))
      throw Error(fmt::format("{} ran another plan (hash {}) than these options give (hash {}): merge with the "
                              "shards' options; nothing merged",
                              s.name(), p.at("hash").dump(), plan.hash));
    try {
      const auto [lo, hi] = cut_by_cost(plan.cost, {s.index, s.count, ""});
      EnergyPart part;
      part.lo = s.doc.at("shard").at("lo").get<size_t>();
      part.hi = s.doc.at("shard").at("hi").get<size_t>();
      const json& units = s.doc.at("units");
      if (part.lo != lo || part.hi != hi || units.size() != hi - lo)
        throw Error(fmt::format("{} units [{}, {}) but the plan gives this shard {} [{}, {})", units.size(), part.lo,
                                part.hi, hi - lo, lo, hi));
      for (auto& u : units) {
        EnergyUnitResult r{doubles(u.at("sum")), doubles(u.at("b_sum")), u.at("done").get<uint64_t>()};
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
      part.reference_worst = doubles(ref.at("worst")).at(0);
      part.reference_worst_at = ref.at("worst_at").get<std::string>();
      const std::string dev = s.doc.at("device").at("name").get<std::string>();
      if (std::find(devices.begin(), devices.end(), dev) == devices.end()) devices.push_back(dev);
      m.lines.push_back(fmt::format("{}: units {}..{} of {} from {} on {}", s.name(), lo + 1, hi, plan.cost.size(),
                                    s.doc.at("shard").at("source").get<std::string>(), dev));
      m.parts.push_back(std::move(part));
    } catch (const json::exception& e) {
      throw Error(fmt::format("{}: malformed ({}); nothing merged", s.name(), e.what()));
    } catch (const Error& e) {
      throw Error(fmt::format("{}: {}; nothing merged", s.name(), e.what()));
    }
  }
  for (size_t k = 0; k < devices.size(); ++k) m.device += (k ? " + " : "") + devices[k];
  return m;
}

}  // namespace mfv
