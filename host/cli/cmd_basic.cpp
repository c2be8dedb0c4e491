// mfv devices, mfv list.
#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "cli/commands.hpp"
#include "runtime/opencl.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>

namespace mfv::cli {

void add_devices(CLI::App& app, Globals&, int& rc) {
  auto* cmd = app.add_subcommand("devices", "list OpenCL platforms and devices");
  cmd->callback([&rc] {
    // denorm: float subnormals kept (CL_FP_DENORM); "ftz" flushes them to zero
    fmt::print("{:>3}  {:<28} {:<40} {:<5} {:>3}  {:<4}  {:<6}  {}\n", "#", "platform", "device", "type", "CUs", "fp64",
               "fp32", "driver");
    for (auto& d : list_devices())
      fmt::print("{:>3}  {:<28} {:<40} {:<5} {:>3}  {:<4}  {:<6}  {}\n", d.index, d.platform, d.name, d.type,
                 d.compute_units, d.fp64 ? "yes" : "no", d.fp32_denorms ? "denorm" : "ftz", d.driver);
    rc = 0;
  });
}

namespace {

// mfv list's command-line values, bound to its options (Globals::command_values keeps them).
struct ListCommandOptions {
  bool json = false;
};

}  // namespace

void add_list(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand(
      "list", "print the catalog of terms and whole models with sources, parameters and expected verdicts");
  auto values = std::make_shared<ListCommandOptions>();  // the command's values
  g.command_values.push_back(values);
  cmd->add_flag("--json", values->json, "machine-readable output");
  cmd->callback([&rc, values] {
    if (values->json) {
      nlohmann::json out = nlohmann::json::array();
      for (auto& t : catalog()) {
        nlohmann::json j{{"id", t.id},           {"kind", kind_name(t.kind)}, {"source", t.source},
                         {"formula", t.formula}, {"kernel", t.kernel_fn},     {"ulp_budget", t.ulp_budget}};
        j["params"] = nlohmann::json::array();
        for (auto& p : t.params)
          j["params"].push_back(
              {{"name", p.name}, {"min", p.lo}, {"max", p.hi}, {"default", p.fallback}, {"doc", p.doc}});
        if (!t.known_bad.empty()) j["known_bad"] = t.known_bad;
        for (auto& f : t.smith_for) {
          nlohmann::json fj{{"d", f.d}, {"tol", f.tol}, {"why", f.why}};
          if (f.alpha_max < 1e300) fj["alpha_max"] = f.alpha_max;
          j["smith_for"].push_back(fj);
        }
        if (!t.under_masks.empty()) j["under_masks"] = t.under_masks;
        if (!t.masking_exact.empty()) j["masking_exact"] = t.masking_exact;
        j["stable"] = t.stable;
        out.push_back(j);
      }
      for (auto& m : models()) {
        nlohmann::json j{{"id", m.id},           {"kind", "model"},       {"source", m.source},
                         {"formula", m.formula}, {"kernel", m.kernel_fn}, {"ulp_budget", m.ulp_budget}};
        j["params"] = nlohmann::json::array();
        for (auto& p : m.params)
          j["params"].push_back(
              {{"name", p.name}, {"min", p.lo}, {"max", p.hi}, {"default", p.fallback}, {"doc", p.doc}});
        if (!m.radiance.empty()) j["radiance"] = m.radiance;
        if (m.ref_albedo) j["closed_form_albedo"] = m.albedo_doc;
        j["cases"] = nlohmann::json::array();
        for (auto& c : m.cases)
          j["cases"].push_back({{"case", m.id + "[" + c.label + "]"},
                                {"energy", expect_name(c.energy)},
                                {"energy_why", c.energy_why},
                                {"reciprocity", expect_name(c.reciprocity)},
                                {"reciprocity_why", c.reciprocity_why}});
        out.push_back(j);
      }
      std::cout << out.dump(2) << "\n";
    } else {
      for (auto& t : catalog()) {
        std::string ps;
        for (auto& p : t.params) ps += fmt::format("{}{} in [{:g}, {:g}]", ps.empty() ? "" : ", ", p.name, p.lo, p.hi);
        fmt::print("{} {:<22} {:<40} {}\n", kind_name(t.kind), t.id, t.formula, ps.empty() ? "-" : ps);
        fmt::print("  {:<22} source: {}{}\n", "", t.source,
                   t.known_bad.empty() ? "" : "  [known bad: " + t.known_bad + "]");
      }
      for (auto& m : models()) {
        std::string ps;
        for (auto& p : m.params) ps += fmt::format("{}{} in [{:g}, {:g}]", ps.empty() ? "" : ", ", p.name, p.lo, p.hi);
        fmt::print("M {:<22} {}\n  {:<22} params: {}\n  {:<22} source: {}\n", m.id, m.formula, "", ps, "", m.source);
        if (!m.radiance.empty()) fmt::print("  {:<22} radiance form: {}\n", "", m.radiance);
        for (auto& c : m.cases)
          fmt::print("  {:<22} [{}] energy {}{}; reciprocity {}{}\n", "", c.label, expect_name(c.energy),
                     c.energy_why.empty() ? "" : " (" + c.energy_why + ")", expect_name(c.reciprocity),
                     c.reciprocity_why.empty() ? "" : " (" + c.reciprocity_why + ")");
      }
    }
    rc = 0;
  });
}

}  // namespace mfv::cli
