// mfv energy --baseline: this run's cells against an earlier energy.json, by
// Welch's t on the two estimates and their replicate standard errors.
#include "checks/energy.hpp"

#include "util/error.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace mfv {

BaselineDiff compare_energy_baseline(const EnergyReport& now, const std::string& text, double alpha_fw) {
  using nlohmann::json;
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(fmt::format("--baseline is not JSON: {}", e.what()));
  }
  auto num = [](const json& v) { return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN(); };
  BaselineDiff out;
  try {
    if (j.at("schema").get<std::string>() != "mfv-energy/1")
      throw Error("--baseline is not an mfv energy report (schema mfv-energy/1)");
    const auto& grid = j.at("grid");
    auto same = [](const json& a, const std::vector<double>& b) {
      if (a.size() != b.size()) return false;
      for (size_t i = 0; i < b.size(); ++i)
        if (std::fabs(a[i].get<double>() - b[i]) > 1e-9 * std::max(1.0, std::fabs(b[i]))) return false;
      return true;
    };
    const bool paired = grid.contains("points") && grid.at("points").get<bool>();
    if (paired != now.paired || !same(grid.at("mu"), now.mu) || !same(grid.at("alpha"), now.alpha))
      throw Error(fmt::format("--baseline has {}x{} (mu x alpha) values; this run has {}x{}: rerun on the same axes",
                              grid.at("mu").size(), grid.at("alpha").size(), now.mu.size(), now.alpha.size()));
    const double df_old = j.at("options").at("replicates").get<double>() - 1, df_new = now.opt.replicates - 1;
    std::vector<BaselineValue> tests;
    std::map<std::string, const json*> old;
    for (auto& c : j.at("combinations")) old[c.at("d").get<std::string>() + "/" + c.at("g").get<std::string>()] = &c;
    const size_t nm = now.mu.size();
    for (auto& t : now.tables) {
      auto it = old.find(t.name());
      if (it == old.end()) {
        out.notes.push_back(t.name() + " is not in the baseline");
        continue;
      }
      const json& c = *it->second;
      for (const CellAt& cell : now.cells()) {
        const std::string w = fmt::format("{} alpha={:.4g} mu={:.4g}", t.name(), now.alpha[cell.a], now.mu[cell.m]);
        // a grid's arrays are [alpha][mu]; paired points' are flat
        auto at = [&](const char* key) { return num(now.paired ? c.at(key)[cell.c] : c.at(key)[cell.a][cell.m]); };
        const size_t ci = cell.c;
        tests.push_back({"E " + w, at("E"), at("E_se"), df_old, t.E[ci].mean, t.E[ci].se, df_new});
        tests.push_back({"A " + w, at("A"), at("A_se"), df_old, t.A[ci].mean, t.A[ci].se, df_new});
      }
      for (size_t a = 0; a < now.alpha.size(); ++a)
        tests.push_back({fmt::format("E_avg {} alpha={:.4g}", t.name(), now.alpha[a]), num(c.at("E_avg")[a]),
                         num(c.at("E_avg_se")[a]), df_old, t.eavg[a].mean, t.eavg[a].se, df_new});
    }
    for (auto& [name, c] : old)
      if (std::none_of(now.tables.begin(), now.tables.end(), [&](const EnergyTable& t) { return t.name() == name; }))
        out.notes.push_back(name + " is in the baseline but not in this run");
    // whole models, by point name (a baseline from before they existed has none)
    std::map<std::string, const json*> old_models;
    if (j.contains("models"))
      for (auto& m : j.at("models")) old_models[m.at("name").get<std::string>()] = &m;
    for (auto& me : now.models) {
      auto it = old_models.find(me.point.name);
      if (it == old_models.end()) {
        out.notes.push_back(me.point.name + " is not in the baseline");
        continue;
      }
      const json& c = *it->second;
      for (size_t m = 0; m < nm; ++m)
        tests.push_back({fmt::format("E {} mu_l={:.4g}", me.point.name, now.mu[m]), num(c.at("E")[m]),
                         num(c.at("E_se")[m]), df_old, me.E[m].mean, me.E[m].se, df_new});
      tests.push_back({"E_avg " + me.point.name, num(c.at("E_avg")), num(c.at("E_avg_se")), df_old, me.eavg.mean,
                       me.eavg.se, df_new});
    }
    // the standard errors come from R-1 degrees of freedom each (replicates)
    judge_baseline(tests, alpha_fw, out);
  } catch (const json::exception& e) {
    throw Error(fmt::format("--baseline is malformed: {}", e.what()));
  }
  return out;
}

}  // namespace mfv
