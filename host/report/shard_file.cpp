#include "report/shard_file.hpp"
#include "mfv_git_commit.h"

#include "runtime/provenance.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>

namespace mfv {

using nlohmann::json;

json shard_number(double x) {
  if (std::isfinite(x)) return x;
  return std::isnan(x) ? "nan" : x > 0 ? "inf" : "-inf";
}

double shard_number_of(const json& j) {
  if (j.is_number()) return j.get<double>();
  const std::string s = j.get<std::string>();
  if (s == "nan") return std::nan("");
  if (s == "inf") return std::numeric_limits<double>::infinity();
  if (s == "-inf") return -std::numeric_limits<double>::infinity();
  throw Error("not a number: " + s);
}

std::string ShardDoc::name() const { return fmt::format("shard {}/{} ({})", index + 1, count, path); }

namespace {

constexpr const char* kSchema = "mfv-shard/1";

// Every field of a point, defaults left out.
json point_json(const PointResult& p, size_t position) {
  json r{{"i", position}, {"check", p.check}, {"estimate", shard_number(p.estimate)}, {"samples", p.samples}};
  auto put = [&](const char* k, double v) {
    if (v != 0 || std::isnan(v)) r[k] = shard_number(v);
  };
  auto text = [&](const char* k, const std::string& v) {
    if (!v.empty()) r[k] = v;
  };
  text("D", p.d ? p.d->id : "");
  text("G", p.g ? p.g->id : "");
  text("F", p.f ? p.f->id : "");
  text("model", p.model);
  json params = json::object();
  for (auto& [k, v] : p.params) params[k] = shard_number(v);
  r["params"] = params;
  put("stderr", p.stderr_);
  put("rounding_bound", p.rounding_bound);
  if (p.dof) r["dof"] = p.dof;
  put("expected", p.expected);
  if (p.known) r["known"] = {shard_number(p.known_value), shard_number(p.known_error)};
  put("bound", p.bound);
  if (p.upper_only) r["upper_only"] = true;
  if (p.expect != Expect::Hold) r["expect"] = int(p.expect);
  put("tolerance", p.tolerance);
  text("reason", p.reason);
  if (p.bounded) r["bounded"] = true;
  text("measure", p.measure);
  text("detail", p.detail);
  if (p.reference_compared) r["reference_compared"] = true;
  if (p.reference_failed) r["reference_failed"] = true;
  text("reference_detail", p.reference_detail);
  return r;
}

const Term* term_of(const json& r, const char* key, Kind kind) {
  if (!r.contains(key)) return nullptr;
  const Term* t = try_find_term(r.at(key).get<std::string>(), kind);
  if (!t) throw Error(fmt::format("unknown {} term '{}'", key, r.at(key).get<std::string>()));
  return t;
}

PointResult point_of(const json& r) {
  PointResult p;
  auto get = [&](const char* k) { return r.contains(k) ? shard_number_of(r.at(k)) : 0.0; };
  auto text = [&](const char* k) { return r.contains(k) ? r.at(k).get<std::string>() : std::string(); };
  p.check = r.at("check").get<std::string>();
  p.d = term_of(r, "D", Kind::D);
  p.g = term_of(r, "G", Kind::G);
  p.f = term_of(r, "F", Kind::F);
  p.model = text("model");
  for (auto& [k, v] : r.at("params").items()) p.params[k] = shard_number_of(v);
  p.estimate = shard_number_of(r.at("estimate"));
  p.samples = r.at("samples").get<uint64_t>();
  p.stderr_ = get("stderr");
  p.rounding_bound = get("rounding_bound");
  p.dof = r.value("dof", 0u);
  p.expected = get("expected");
  if (r.contains("known")) {
    p.known = true;
    p.known_value = shard_number_of(r.at("known").at(0));
    p.known_error = shard_number_of(r.at("known").at(1));
  }
  p.bound = get("bound");
  p.upper_only = r.value("upper_only", false);
  const int e = r.value("expect", int(Expect::Hold));
  if (e != int(Expect::Hold) && e != int(Expect::Fail) && e != int(Expect::May)) throw Error("bad expect");
  p.expect = Expect(e);
  p.tolerance = get("tolerance");
  p.reason = text("reason");
  p.bounded = r.value("bounded", false);
  p.measure = text("measure");
  p.detail = text("detail");
  p.reference_compared = r.value("reference_compared", false);
  p.reference_failed = r.value("reference_failed", false);
  p.reference_detail = text("reference_detail");
  return p;
}

json options_json(const SuiteOptions& opt) {
  return {{"seed", opt.seed},
          {"scale", opt.scale},
          {"family_alpha", opt.family_alpha},
          {"checks", opt.checks},
          {"models", opt.models},
          {"reference_samples", opt.reference_samples},
          {"reference_every", opt.reference_every},
          {"density", opt.density}};
}

SuiteOptions options_of(const json& j) {
  SuiteOptions o;
  o.seed = j.at("seed").get<uint64_t>();
  o.scale = j.at("scale").get<double>();
  o.family_alpha = j.at("family_alpha").get<double>();
  o.checks = j.at("checks").get<std::vector<std::string>>();
  o.models = j.at("models").get<std::vector<std::string>>();
  o.reference_samples = j.at("reference_samples").get<uint32_t>();
  o.reference_every = j.at("reference_every").get<uint32_t>();
  o.density = j.value("density", 1);
  return o;
}

json tool_json() { return {{"version", MFV_VERSION}, {"commit", MFV_GIT_COMMIT}, {"describe", MFV_GIT_DESCRIBE}}; }

// One shard's file, read and checked on its own.
using Shard = ShardDoc;

Shard read_shard(const std::string& input, const ShardKind& kind) {
  Shard s;
  s.path = std::filesystem::is_directory(input) ? (std::filesystem::path(input) / kind.file).string() : input;
  if (!std::filesystem::is_regular_file(s.path))
    throw Error(fmt::format("{}: no shard file ({} --out DIR writes DIR/{})", s.path, kind.writer, kind.file));
  const std::string text = read_text_file(s.path, "mfv merge");
  try {
    s.doc = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(fmt::format("{}: truncated or not JSON ({}); rerun that shard", s.path, e.what()));
  }
  try {
    if (s.doc.value("schema", "") != kind.schema) throw Error(fmt::format("schema is not {}", kind.schema));
    if (!s.doc.value("complete", false)) throw Error("the shard's run did not complete");
    s.index = s.doc.at("shard").at("index").get<uint32_t>() - 1;
    s.count = s.doc.at("shard").at("count").get<uint32_t>();
    if (s.count == 0 || s.index >= s.count) throw Error("bad shard index or count");
  } catch (const json::exception& e) {
    throw Error(fmt::format("{}: not an mfv shard file ({})", s.path, e.what()));
  } catch (const Error& e) {
    throw Error(fmt::format("{}: not a complete mfv shard file ({})", s.path, e.what()));
  }
  return s;
}

// The same plan, seed, count and tool as the first shard and this mfv.
void check_alike(const Shard& s, const Shard& first) {
  const json& t = s.doc.at("tool");
  if (t != tool_json())
    throw Error(fmt::format("{} was written by mfv {} (commit {}), this is mfv {} (commit {}): merge with the "
                            "version that ran the shards",
                            s.name(), t.value("version", "?"), t.value("commit", "?"), MFV_VERSION, MFV_GIT_COMMIT));
  if (s.count != first.count)
    throw Error(fmt::format("{} is one of {} shards, {} of {}", s.name(), s.count, first.name(), first.count));
  const json &a = s.doc.at("plan"), &b = first.doc.at("plan");
  if (a.at("options").at("seed") != b.at("options").at("seed"))
    throw Error(fmt::format("{} ran seed {}, {} seed {}", s.name(), a.at("options").at("seed").dump(), first.name(),
                            b.at("options").at("seed").dump()));
  if (a.at("hash") != b.at("hash") || a.at("options") != b.at("options"))
    throw Error(fmt::format("{} ran another plan (hash {}, options {}) than {} (hash {}, options {})", s.name(),
                            a.at("hash").get<std::string>(), a.at("options").dump(), first.name(),
                            b.at("hash").get<std::string>(), b.at("options").dump()));
}

}  // namespace

std::string shard_json(const SuiteReport& rep, const SuitePlans& cut, const std::vector<size_t>& positions,
                       const SuiteOptions& opt, const ShardSpec& s, const std::string& hash, size_t integrals,
                       const OutputContext& ctx) {
  if (positions.size() != rep.points.size())
    throw Error(fmt::format("internal: shard ran {} records for {} integrals", rep.points.size(), positions.size()));
  json j;
  j["schema"] = kSchema;
  j["tool"] = tool_json();
  j["plan"] = {{"hash", hash}, {"integrals", integrals}, {"options", options_json(opt)}};
  j["shard"] = {{"index", s.index + 1}, {"count", s.count}, {"source", s.source}, {"date", utc_timestamp()}};
  j["device"] = {{"name", ctx.device.name},
                 {"platform", ctx.device.platform},
                 {"driver", ctx.device.driver},
                 {"version", ctx.device.version},
                 {"fp64", ctx.device.fp64}};
  j["build"] = {{"options", ctx.build_options}, {"builds", ctx.builds}, {"seconds", rep.build_seconds}};
  j["provenance"] = ctx.provenance;
  // one row per non-empty plan, as run_plan and record_reciprocity push them
  std::vector<size_t> plan_of;
  for (size_t i = 0; i < cut.plans.size(); ++i)
    if (!cut.plans[i].specs.empty()) plan_of.push_back(i);
  if (!cut.reciprocity.specs.empty()) plan_of.push_back(cut.plans.size());
  j["timings"] = json::array();
  for (size_t k = 0; k < rep.stats.size(); ++k) {
    const CheckStats& c = rep.stats[k];
    j["timings"].push_back({{"plan", k < plan_of.size() ? plan_of[k] : k},
                            {"check", c.check},
                            {"integrals", c.integrals},
                            {"samples", c.samples},
                            {"seconds", c.seconds}});
  }
  j["double_accumulation"] = rep.double_accumulation;
  j["reference"] = {{"compared", rep.reference_compared}, {"twin", rep.reference_twin},
                    {"bound", shard_number(rep.reference_bound)},  {"builds", rep.reference_builds},
                    {"worst", shard_number(rep.reference_worst)},  {"worst_at", rep.reference_worst_at},
                    {"worst_point", rep.reference_compared ? json(positions.at(rep.reference_worst_point)) : json()}};
  std::string records = "[";
  for (size_t k = 0; k < rep.points.size(); ++k) records += (k ? "," : "") + point_json(rep.points[k], positions[k]).dump();
  records += "]";
  j["results"] = json::array();  // its text is `records`
  j["complete"] = true;           // a file cut short fails to parse or lacks this
  return dump_with_results(j, records);
}

nlohmann::json shard_tool_json() { return tool_json(); }

json shard_bits(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) {
    uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    a.push_back(b);
  }
  return a;
}

std::vector<double> shard_doubles(const json& a) {
  std::vector<double> v;
  for (auto& e : a) {
    const uint64_t b = e.get<uint64_t>();
    double x;
    std::memcpy(&x, &b, sizeof x);
    v.push_back(x);
  }
  return v;
}

json plan_shard_json(const UnitShard& u, const ShardSpec& s, std::pair<size_t, size_t> part, const std::string& device,
                     const json& provenance) {
  json j;
  j["schema"] = u.kind.schema;
  j["tool"] = tool_json();
  j["plan"] = {{"hash", u.plan.hash}, {"units", u.plan.cost.size()}, {"options", {{"seed", u.seed}}}};
  j["shard"] = {{"index", s.index + 1}, {"count", s.count},        {"source", s.source},
                {"date", utc_timestamp()}, {"lo", part.first}, {"hi", part.second}};
  j["device"] = {{"name", device}};
  j["provenance"] = provenance;
  return j;
}

std::string plan_shard_line(const UnitShard& u, const ShardSpec& s, std::pair<size_t, size_t> part) {
  return fmt::format("shard {}/{} (from {}): {} {}..{} of {}; plan {}{}", s.index + 1, s.count, s.source, u.noun,
                     part.first + 1, part.second, u.plan.cost.size(), u.plan.hash,
                     u.seed.is_null() ? "" : ", seed " + u.seed.dump());
}

UnitShards read_unit_shards(const std::vector<std::string>& inputs, const UnitShard& u,
                            const std::function<void(const ShardDoc&, const json& units)>& read) {
  const std::vector<ShardDoc> shards = read_shard_set(inputs, u.kind);
  UnitShards m;
  std::vector<std::string> devices;
  for (const ShardDoc& s : shards) {
    // read_shard_set checked plan, hash and options alike in every shard
    const json& p = s.doc.at("plan");
    if (p.at("options").at("seed") != u.seed)
      throw Error(fmt::format("{} ran seed {}, this merge --seed {}: nothing merged", s.name(),
                              p.at("options").at("seed").dump(), u.seed.dump()));
    if (p.at("hash") != json(u.plan.hash))
      throw Error(fmt::format("{} ran another plan (hash {}) than these options give (hash {}): merge with the "
                              "shards' options; nothing merged",
                              s.name(), p.at("hash").dump(), u.plan.hash));
    try {
      const auto [lo, hi] = cut_by_cost(u.plan.cost, {s.index, s.count, ""});
      const size_t slo = s.doc.at("shard").at("lo").get<size_t>(), shi = s.doc.at("shard").at("hi").get<size_t>();
      const json& units = s.doc.at("units");
      if (slo != lo || shi != hi || units.size() != hi - lo)
        throw Error(fmt::format("{} {} [{}, {}) but the plan gives this shard {} [{}, {})", units.size(), u.noun, slo,
                                shi, hi - lo, lo, hi));
      read(s, units);
      const std::string dev = s.doc.at("device").at("name").get<std::string>();
      if (std::find(devices.begin(), devices.end(), dev) == devices.end()) devices.push_back(dev);
      m.lines.push_back(fmt::format("{}: {} {}..{} of {} from {} on {}", s.name(), u.noun, lo + 1, hi,
                                    u.plan.cost.size(), s.doc.at("shard").at("source").get<std::string>(), dev));
    } catch (const json::exception& e) {
      throw Error(fmt::format("{}: malformed ({}); nothing merged", s.name(), e.what()));
    } catch (const Error& e) {
      throw Error(fmt::format("{}: {}; nothing merged", s.name(), e.what()));
    }
  }
  for (size_t k = 0; k < devices.size(); ++k) m.device += (k ? " + " : "") + devices[k];
  return m;
}

std::vector<ShardDoc> read_shard_set(const std::vector<std::string>& inputs, const ShardKind& kind) {
  if (inputs.empty()) throw Error("mfv merge needs the shards' folders");
  std::vector<Shard> shards;
  for (auto& in : inputs) shards.push_back(read_shard(in, kind));
  const Shard& first = shards.front();
  std::vector<const Shard*> by_index(first.count, nullptr);
  for (const Shard& s : shards) {
    check_alike(s, first);
    if (by_index[s.index]) throw Error(fmt::format("{} is given twice: {} and {}", s.name(), by_index[s.index]->path, s.path));
    by_index[s.index] = &s;
  }
  std::string missing;
  for (uint32_t k = 0; k < first.count; ++k)
    if (!by_index[k]) missing += fmt::format("{}{}/{}", missing.empty() ? "" : ", ", k + 1, first.count);
  if (!missing.empty()) throw Error(fmt::format("shard {} missing: nothing merged (have {} of {})", missing, shards.size(), first.count));
  std::vector<ShardDoc> ordered;
  for (const Shard* s : by_index) ordered.push_back(*s);
  return ordered;
}

MergedRun merge_shards(const std::vector<std::string>& inputs) {
  const std::vector<Shard> ordered = read_shard_set(inputs, {"shard.json", kSchema, "mfv run --shard K/N"});
  const Shard& first = ordered.front();
  std::vector<const Shard*> by_index;
  for (const Shard& s : ordered) by_index.push_back(&s);

  MergedRun m;
  try {
    m.opt = options_of(first.doc.at("plan").at("options"));
  } catch (const json::exception& e) {
    throw Error(fmt::format("{}: bad plan options ({})", first.name(), e.what()));
  }
  validate_suite_options(m.opt);
  const SuitePlans whole = make_suite_plans(m.opt);
  const std::string hash = plan_hash(whole, m.opt);
  if (hash != first.doc.at("plan").at("hash").get<std::string>())
    throw Error(fmt::format("{}: plan hash {} but this mfv builds {} from its options", first.name(),
                            first.doc.at("plan").at("hash").get<std::string>(), hash));
  std::vector<const PointResult*> planned;  // the whole run's points, by position
  for (auto& p : whole.plans)
    for (auto& q : p.points) planned.push_back(&q);
  for (auto& q : whole.reciprocity.points) planned.push_back(&q);

  SuiteReport& rep = m.rep;
  rep.points.resize(planned.size());
  std::map<size_t, CheckStats> stats;  // by plan
  bool have_worst = false;
  size_t worst_pos = 0;
  std::vector<std::string> devices;
  for (uint32_t k = 0; k < first.count; ++k) {
    const Shard& s = *by_index[k];
    const std::vector<size_t> want = shard_positions(whole, {k, first.count, ""});
    try {
      const json& recs = s.doc.at("results");
      if (recs.size() != want.size())
        throw Error(fmt::format("{} records but the plan gives this shard {}", recs.size(), want.size()));
      for (size_t r = 0; r < recs.size(); ++r) {
        const size_t pos = recs[r].at("i").get<size_t>();
        if (pos != want[r]) throw Error(fmt::format("record {} is integral {}, the plan's is {}", r, pos, want[r]));
        PointResult p = point_of(recs[r]);
        if (p.check != planned[pos]->check || model_name(p) != model_name(*planned[pos]))
          throw Error(fmt::format("record {} is {} {}, the plan's is {} {}", r, p.check, model_name(p),
                                  planned[pos]->check, model_name(*planned[pos])));
        rep.points[pos] = std::move(p);
      }
      for (auto& t : s.doc.at("timings")) {
        CheckStats& c = stats[t.at("plan").get<size_t>()];
        c.check = t.at("check").get<std::string>();
        c.integrals += t.at("integrals").get<uint64_t>();
        c.samples += t.at("samples").get<uint64_t>();
        c.seconds += t.at("seconds").get<double>();
      }
      const json& ref = s.doc.at("reference");
      rep.reference_compared += ref.at("compared").get<uint64_t>();
      rep.reference_twin = rep.reference_twin || ref.at("twin").get<bool>();
      rep.reference_builds += ref.at("builds").get<int>();
      if (ref.at("twin").get<bool>()) rep.reference_bound = shard_number_of(ref.at("bound"));
      if (!ref.at("worst_point").is_null()) {
        // run_suite keeps the first integral of the largest disagreement
        const double w = shard_number_of(ref.at("worst"));
        const size_t pos = ref.at("worst_point").get<size_t>();
        if (!have_worst || w > rep.reference_worst || (w == rep.reference_worst && pos < worst_pos)) {
          rep.reference_worst = w;
          rep.reference_worst_at = ref.at("worst_at").get<std::string>();
          worst_pos = pos;
          have_worst = true;
        }
      }
      rep.double_accumulation = rep.double_accumulation && s.doc.at("double_accumulation").get<bool>();
      rep.build_seconds += s.doc.at("build").at("seconds").get<double>();
      m.ctx.builds += s.doc.at("build").at("builds").get<int>();
      const std::string dev = s.doc.at("device").at("name").get<std::string>();
      if (std::find(devices.begin(), devices.end(), dev) == devices.end()) devices.push_back(dev);
      m.lines.push_back(fmt::format("{}: {} records from {} on {}", s.name(), recs.size(),
                                    s.doc.at("shard").at("source").get<std::string>(), dev));
    } catch (const json::exception& e) {
      throw Error(fmt::format("{}: malformed ({})", s.name(), e.what()));
    } catch (const Error& e) {
      throw Error(fmt::format("{}: {}; nothing merged", s.name(), e.what()));
    }
  }
  rep.reference_worst_point = worst_pos;
  for (auto& [plan, c] : stats) rep.stats.push_back(c);
  if (rep.points.empty()) throw Error("the merged plan has no integrals");
  judge(rep, m.opt);

  const json& d = first.doc.at("device");
  m.ctx.device.name = devices.size() == 1 ? devices.front() : fmt::format("{}", fmt::join(devices, " + "));
  m.ctx.device.platform = d.value("platform", "");
  m.ctx.device.driver = d.value("driver", "");
  m.ctx.device.version = d.value("version", "");
  m.ctx.device.fp64 = d.value("fp64", false);
  m.ctx.build_options = first.doc.at("build").value("options", "");
  m.ctx.provenance = first.doc.value("provenance", json::object());
  json list = json::array();
  for (uint32_t k = 0; k < first.count; ++k) {
    const Shard& s = *by_index[k];
    list.push_back({{"index", k + 1},
                    {"count", first.count},
                    {"file", s.path},
                    {"source", s.doc.at("shard").at("source")},
                    {"date", s.doc.at("shard").value("date", "")},
                    {"device", s.doc.at("device").at("name")},
                    {"command", s.doc.at("provenance").value("command", json())}});
  }
  m.ctx.provenance["shards"] = {{"count", first.count}, {"plan_hash", hash}, {"shards", list}};
  m.ctx.provenance["merged_by"] = provenance_json().value("command", json());
  return m;
}

}  // namespace mfv
