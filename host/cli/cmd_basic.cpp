// mfv devices, mfv list.
#include "catalog/catalog.hpp"
#include "cli/commands.hpp"
#include "runtime/opencl.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <iostream>

namespace mfv::cli {

void add_devices(CLI::App& app, Globals&, int& rc) {
  auto* cmd = app.add_subcommand("devices", "list OpenCL platforms and devices");
  cmd->callback([&rc] {
    fmt::print("{:>3}  {:<28} {:<40} {:<5} {:>3}  {:<4}  {}\n", "#", "platform", "device", "type", "CUs", "fp64",
               "driver");
    for (auto& d : list_devices())
      fmt::print("{:>3}  {:<28} {:<40} {:<5} {:>3}  {:<4}  {}\n", d.index, d.platform, d.name, d.type,
                 d.compute_units, d.fp64 ? "yes" : "no", d.driver);
    rc = 0;
  });
}

void add_list(CLI::App& app, Globals&, int& rc) {
  auto* cmd = app.add_subcommand("list", "print the catalog of terms with sources and parameters");
  static bool json = false;
  cmd->add_flag("--json", json, "machine-readable output");
  cmd->callback([&rc] {
    if (json) {
      nlohmann::json out = nlohmann::json::array();
      for (auto& t : catalog()) {
        nlohmann::json j{{"id", t.id},       {"kind", kind_name(t.kind)}, {"source", t.source},
                         {"formula", t.formula}, {"kernel", t.kernel_fn},   {"ulp_budget", t.ulp_budget}};
        j["params"] = nlohmann::json::array();
        for (auto& p : t.params)
          j["params"].push_back({{"name", p.name}, {"min", p.lo}, {"max", p.hi}, {"default", p.fallback}, {"doc", p.doc}});
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
      std::cout << out.dump(2) << "\n";
    } else {
      for (auto& t : catalog()) {
        std::string ps;
        for (auto& p : t.params) ps += fmt::format("{}{} in [{:g}, {:g}]", ps.empty() ? "" : ", ", p.name, p.lo, p.hi);
        fmt::print("{} {:<22} {:<40} {}\n", kind_name(t.kind), t.id, t.formula, ps.empty() ? "-" : ps);
        fmt::print("  {:<22} source: {}{}\n", "", t.source, t.known_bad.empty() ? "" : "  [known bad: " + t.known_bad + "]");
      }
    }
    rc = 0;
  });
}

}  // namespace mfv::cli
