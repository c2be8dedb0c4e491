#include "report/suite_baseline.hpp"

#include "report/suite_report.hpp"
#include "util/error.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <limits>
#include <map>

namespace mfv {
namespace {

using nlohmann::json;

// An integral's identity across runs: check, terms or model, parameters as
// results.json rounds them, and the input a measured maximum names.
std::string key_of(const json& r) {
  const std::string d = r.at("D").get<std::string>(), model = r.at("model").get<std::string>();
  const std::string terms =
      d.empty() ? "" : d + "/" + r.at("G").get<std::string>() + "/" + r.at("F").get<std::string>();
  return fmt::format("{} {}{}{} {}", r.at("check").get<std::string>(), terms, terms.empty() || model.empty() ? "" : " ",
                     model, r.at("params").dump());
}

double number(const json& v) { return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN(); }

// Degrees of freedom of an integral's standard error. iid: samples - 1;
// stratified d_norm pairs neighbouring strata: samples / 2 - 1. The smaller
// is taken for every integral (at thousands of samples either is normal).
double dof(const json& r) { return std::max(1.0, number(r.at("samples")) / 2 - 1); }

}  // namespace

json parse_run_baseline(const std::string& text) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(fmt::format("--baseline is not JSON: {}", e.what()));
  }
  // results.json before the "schema" key said "schema_version": 1
  const bool run_schema = !j.is_object()         ? false
                          : j.contains("schema") ? j["schema"] == "mfv-run/1"
                                                 : j.contains("schema_version") && j["schema_version"] == 1;
  if (!run_schema || !j.contains("results") || !j["results"].is_array())
    throw Error("--baseline is not an mfv run results.json (schema mfv-run/1)");
  return j;
}

BaselineDiff compare_run_baseline(const SuiteReport& now, const json& j, double alpha_fw) {
  BaselineDiff out;
  try {
    std::map<std::string, const json*> old;
    for (auto& r : j.at("results"))
      if (!r.contains("measure")) old[key_of(r)] = &r;
    std::vector<BaselineValue> values;
    size_t missing = 0;
    for (auto& p : now.points) {
      if (p.bounded) continue;  // a measured maximum has no standard error to test against
      const json r = point_record(p);
      auto it = old.find(key_of(r));
      if (it == old.end()) {
        ++missing;
        continue;
      }
      const json& b = *it->second;
      values.push_back({key_of(r), number(b.at("estimate")), number(b.at("stderr")), dof(b), number(r.at("estimate")),
                        number(r.at("stderr")), dof(r)});
    }
    if (missing > 0) out.notes.push_back(fmt::format("{} integrals of this run are not in the baseline", missing));
    if (values.empty()) throw Error("--baseline shares no integral with this run (other checks, models or options?)");
    judge_baseline(values, alpha_fw, out);
  } catch (const json::exception& e) {
    throw Error(fmt::format("--baseline is malformed: {}", e.what()));
  }
  return out;
}

}  // namespace mfv
