// mfv devices, mfv list.
#include "catalog/bsdfs.hpp"
#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "checks/suite_bsdf.hpp"
#include "cli/shared_options.hpp"
#include "runtime/opencl.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <iostream>

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

// What `mfv list --json` says of a term and of a whole model alike.
template <class Entry>
nlohmann::json entry_json(const Entry& e, const std::string& kind) {
  nlohmann::json j{{"id", e.id},           {"kind", kind},          {"source", e.source},
                   {"formula", e.formula}, {"kernel", e.kernel_fn}, {"ulp_budget", e.ulp_budget}};
  j["params"] = nlohmann::json::array();
  for (auto& p : e.params)
    j["params"].push_back({{"name", p.name}, {"min", p.lo}, {"max", p.hi}, {"default", p.fallback}, {"doc", p.doc}});
  return j;
}

// "alpha in [0.001, 1], f0 in [0, 1]": a term's or a model's parameters.
template <class Entry>
std::string params_text(const Entry& e) {
  std::string ps;
  for (auto& p : e.params) ps += fmt::format("{}{} in [{:g}, {:g}]", ps.empty() ? "" : ", ", p.name, p.lo, p.hi);
  return ps;
}

// mfv list: its option and its work.
struct ListCommand : SharedValues {
  bool json = false;

  void add_options(CLI::App* cmd) {
    cmd->description("print the catalog of terms and whole models with sources, parameters and expected verdicts");
    cmd->add_flag("--json", json, "machine-readable output");
  }

  int run(const Globals&) {
    if (json)
      print_json();
    else
      print_text();
    return 0;
  }

  static void print_json() {
    nlohmann::json out = nlohmann::json::array();
    for (auto& t : catalog()) {
      nlohmann::json j = entry_json(t, kind_name(t.kind));
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
      nlohmann::json j = entry_json(m, "model");
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
    for (auto& b : bsdfs()) out.push_back(bsdf_json(b));
    std::cout << out.dump(2) << "\n";
  }

  // A rough dielectric BTDF (catalog/bsdfs.hpp): its D, G and G2 form, the
  // parameters it takes (D's, G's, eta) and the radiance/flux convention.
  static nlohmann::json bsdf_json(const Bsdf& b) {
    nlohmann::json j{{"id", b.id},
                     {"kind", "bsdf"},
                     {"source", b.source},
                     {"formula", b.formula},
                     {"kernel", "btdf_eval"},
                     {"ulp_budget", b.ulp_budget},
                     {"d", b.d->id},
                     {"g", b.g->id},
                     {"g2", btdf_form_name(b.form)},
                     {"convention", kBtdfConvention}};
    j["params"] = nlohmann::json::array();
    for (const Param* p : {&b.d->params[0], &b.g->params[0], &b.eta})
      j["params"].push_back({{"name", p->name}, {"min", p->lo}, {"max", p->hi}, {"default", p->fallback}, {"doc", p->doc}});
    if (!b.known_bad.empty()) j["known_bad"] = b.known_bad;
    if (!b.g1_fit.empty()) j["g1_fit"] = b.g1_fit;
    // the registry's kinds that take it (mfv run --check), each with the form
    // it tests in its summary and the verdict the catalog expects
    j["checks"] = nlohmann::json::array();
    for (const BsdfCheck& c : bsdf_checks(b)) {
      nlohmann::json cj{{"check", c.kind->check}, {"expect", expect_name(c.expect)}, {"summary", c.kind->summary}};
      if (!c.reason.empty()) cj["why"] = c.reason;
      j["checks"].push_back(cj);
    }
    return j;
  }

  static void print_text() {
    for (auto& t : catalog()) {
      const std::string ps = params_text(t);
      fmt::print("{} {:<22} {:<40} {}\n", kind_name(t.kind), t.id, t.formula, ps.empty() ? "-" : ps);
      fmt::print("  {:<22} source: {}{}\n", "", t.source,
                 t.known_bad.empty() ? "" : "  [known bad: " + t.known_bad + "]");
    }
    for (auto& m : models()) {
      const std::string ps = params_text(m);
      fmt::print("M {:<22} {}\n  {:<22} params: {}\n  {:<22} source: {}\n", m.id, m.formula, "", ps, "", m.source);
      if (!m.radiance.empty()) fmt::print("  {:<22} radiance form: {}\n", "", m.radiance);
      for (auto& c : m.cases)
        fmt::print("  {:<22} [{}] energy {}{}; reciprocity {}{}\n", "", c.label, expect_name(c.energy),
                   c.energy_why.empty() ? "" : " (" + c.energy_why + ")", expect_name(c.reciprocity),
                   c.reciprocity_why.empty() ? "" : " (" + c.reciprocity_why + ")");
    }
    for (auto& b : bsdfs()) {
      fmt::print("T {:<22} D {} x G1 of {}, G2 {}; params {}, {}, eta in [{:g}, {:g}]\n", b.id, b.d->id, b.g->id,
                 btdf_form_name(b.form), b.d->params[0].name, b.g->params[0].name, b.eta.lo, b.eta.hi);
      fmt::print("  {:<22} source: {}{}\n", "", b.source, b.known_bad.empty() ? "" : "  [known bad: " + b.known_bad + "]");
      std::string checks;
      for (const BsdfCheck& c : bsdf_checks(b))
        checks += fmt::format("{}{} {}", checks.empty() ? "" : "; ", c.kind->check, expect_name(c.expect));
      fmt::print("  {:<22} checks: {}\n", "", checks);
    }
    if (!bsdfs().empty()) fmt::print("T: rough dielectric BTDFs; {}\n", kBtdfConvention);
  }
};

}  // namespace

void add_list(CLI::App& app, Globals& g, int& rc) { add_command<ListCommand>(app, g, rc, "list"); }

}  // namespace mfv::cli
