#include "report/pointwise_shard_file.hpp"

#include "report/agree_report.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

namespace mfv {

using nlohmann::json;

namespace {

json bit(double x) { return shard_bits({x}).at(0); }
double bit_of(const json& j) { return shard_doubles(json::array({j})).at(0); }

// Every field of a stability case and its regions.
json case_json(const StabilityCase& c) {
  json regions = json::array();
  for (auto& r : c.regions)
    regions.push_back(
        {{"region", r.region},
         {"what", r.what},
         {"in_domain", r.in_domain},
         {"expect", r.expect},
         {"counts", {r.points, r.nan, r.inf, r.negative, r.breaks, r.violations, r.ref_violations, r.out_of_domain}},
         {"first_out_of_domain", r.first_out_of_domain},
         {"max_rel", bit(r.max_rel)},
         {"max_ulps", bit(r.max_ulps)},
         {"first_break", r.first_break},
         {"worst", r.worst}});
  return {{"name", c.name},     {"group", c.group},        {"family", c.family}, {"formula", c.formula},
          {"stable", c.stable}, {"default", c.is_default}, {"regions", regions}};
}

StabilityCase case_of(const json& j) {
  StabilityCase c;
  c.name = j.at("name").get<std::string>();
  c.group = j.at("group").get<std::string>();
  c.family = j.at("family").get<std::string>();
  c.formula = j.at("formula").get<std::string>();
  c.stable = j.at("stable").get<bool>();
  c.is_default = j.at("default").get<bool>();
  for (auto& jr : j.at("regions")) {
    RegionResult r;
    r.region = jr.at("region").get<std::string>();
    r.what = jr.at("what").get<std::string>();
    r.in_domain = jr.at("in_domain").get<bool>();
    r.expect = jr.at("expect").get<std::string>();
    const json& n = jr.at("counts");
    uint64_t* counts[] = {&r.points,         &r.nan,          &r.inf, &r.negative, &r.breaks, &r.violations,
                          &r.ref_violations, &r.out_of_domain};
    if (n.size() != std::size(counts)) throw Error(fmt::format("case {}: {} counts", c.name, n.size()));
    for (size_t k = 0; k < n.size(); ++k) *counts[k] = n[k].get<uint64_t>();
    r.first_out_of_domain = jr.at("first_out_of_domain").get<std::string>();
    r.max_rel = bit_of(jr.at("max_rel"));
    r.max_ulps = bit_of(jr.at("max_ulps"));
    r.first_break = jr.at("first_break").get<std::string>();
    r.worst = jr.at("worst").get<std::string>();
    c.regions.push_back(std::move(r));
  }
  return c;
}

}  // namespace

UnitShard agree_unit_shard(const UnitPlan& plan, uint64_t seed) {
  return {{"agree_shard.json", "mfv-agree-shard/1", "mfv agree --shard K/N"}, plan, seed, "cases"};
}

std::string agree_shard_json(const AgreeReport& part, const UnitShard& u, const ShardSpec& s,
                             std::pair<size_t, size_t> cases, const std::string& device, const json& provenance) {
  json j = plan_shard_json(u, s, cases, device, provenance);
  j["seconds"] = {
      {"build", part.build_seconds}, {"kernel", part.kernel_seconds}, {"reference", part.reference_seconds}};
  j["units"] = json::array();
  for (auto& r : part.results) j["units"].push_back(agree_result_json(r));
  j["complete"] = true;  // a file cut short fails to parse or lacks this
  return j.dump();
}

AgreeShards read_agree_shards(const std::vector<std::string>& inputs, const UnitShard& u) {
  AgreeShards m;
  const UnitShards read = read_unit_shards(inputs, u, [&](const ShardDoc& s, const json& units) {
    for (auto& r : units) {
      m.rep.results.push_back(agree_result_of(r));
      m.rep.samples += m.rep.results.back().samples;
    }
    const json& t = s.doc.at("seconds");
    m.rep.build_seconds += t.at("build").get<double>();
    m.rep.kernel_seconds += t.at("kernel").get<double>();
    m.rep.reference_seconds += t.at("reference").get<double>();
  });
  m.device = read.device;
  m.lines = read.lines;
  return m;
}

UnitShard stability_unit_shard(const UnitPlan& plan) {
  return {{"stability_shard.json", "mfv-stability-shard/1", "mfv stability --shard K/N"}, plan, json(), "cases"};
}

std::string stability_shard_json(const StabilityReport& part, const UnitShard& u, const ShardSpec& s,
                                 std::pair<size_t, size_t> cases, const json& provenance) {
  json j = plan_shard_json(u, s, cases, part.device, provenance);
  j["report"] = {{"platform", part.platform},
                 {"driver", part.driver},
                 {"precision", part.precision},
                 {"build_options", part.build_options},
                 {"points", part.points},
                 {"seconds", {part.build_seconds, part.kernel_seconds, part.reference_seconds, part.total_seconds}}};
  // one unit per case, with its scan (run_case keeps a case's non-empty scan, in case order)
  j["units"] = json::array();
  size_t next_scan = 0;
  for (auto& c : part.cases) {
    json unit{{"case", case_json(c)}};
    if (next_scan < part.scans.size() && part.scans[next_scan].name == c.name) {
      std::vector<double> flat;
      for (auto& p : part.scans[next_scan].points) flat.insert(flat.end(), {p.theta, p.alpha, p.ulps});
      unit["scan"] = shard_bits(flat);
      ++next_scan;
    }
    j["units"].push_back(unit);
  }
  if (next_scan != part.scans.size()) throw Error("internal: a stability scan without its case");
  j["complete"] = true;  // a file cut short fails to parse or lacks this
  return j.dump();
}

StabilityShards read_stability_shards(const std::vector<std::string>& inputs, const UnitShard& u) {
  StabilityShards m;
  const UnitShards read = read_unit_shards(inputs, u, [&](const ShardDoc& s, const json& units) {
    StabilityReport p;
    p.device = s.doc.at("device").at("name").get<std::string>();
    const json& r = s.doc.at("report");
    p.platform = r.at("platform").get<std::string>();
    p.driver = r.at("driver").get<std::string>();
    p.precision = r.at("precision").get<std::string>();
    p.build_options = r.at("build_options").get<std::string>();
    p.points = r.at("points").get<uint64_t>();
    const auto t = r.at("seconds").get<std::vector<double>>();
    if (t.size() != 4) throw Error("seconds: not build, kernel, reference and total");
    p.build_seconds = t[0], p.kernel_seconds = t[1], p.reference_seconds = t[2], p.total_seconds = t[3];
    for (auto& unit : units) {
      p.cases.push_back(case_of(unit.at("case")));
      if (!unit.contains("scan")) continue;
      const std::vector<double> flat = shard_doubles(unit.at("scan"));
      if (flat.size() % 3) throw Error(fmt::format("case {}: a scan of {} numbers", p.cases.back().name, flat.size()));
      ScanSeries scan{p.cases.back().name, {}};
      for (size_t k = 0; k < flat.size(); k += 3) scan.points.push_back({flat[k], flat[k + 1], flat[k + 2]});
      p.scans.push_back(std::move(scan));
    }
    m.parts.push_back(std::move(p));
  });
  m.lines = read.lines;
  return m;
}

}  // namespace mfv
