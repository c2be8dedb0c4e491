#include "report/energy_report.hpp"
#include "mfv_git_commit.h"
#include "report/sheen_table.hpp"

#include "catalog/roughness.hpp"
#include "report/energy_plots.hpp"
#include "runtime/provenance.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace mfv {

const char* const kEnergyParam =
    "alpha = microfacet width (GGX/Beckmann slope scale); perceptual roughness r = sqrt(alpha), i.e. alpha = r^2; "
    "a D or G with another native parameter gets it from alpha (Phong: alpha_p = 2/alpha^2 - 2; blinn_rho: rho = "
    "alpha; beckmann_ct82: m = alpha)";

std::string energy_grid_text(const EnergyReport& rep) {
  if (rep.opt.mu_axis.empty())
    return "mu = cos(theta_view) at cell midpoints (m + 1/2)/N_MU, m = 0..N_MU-1; alpha = 10^(-3 + 3a/(N_ALPHA-1)), "
           "a = 0..N_ALPHA-1 (log spacing, 1e-3..1)";
  std::string s = rep.paired ? "points given one by one: value i at (mu[i], alpha[i])"
                             : "the caller's axes: mu[m] and alpha[a] as given, in the given order";
  if (!rep.opt.roughness.empty()) s += "; alpha = r^2 of the given perceptual roughness r";
  if (!rep.opt.layout.empty()) s += "; engine layout " + rep.opt.layout + " (docs/energy-layouts.md)";
  if (std::find(rep.alpha.begin(), rep.alpha.end(), 0.0) != rep.alpha.end())
    s += "; alpha = 0 (a mirror) is evaluated at the D's smallest declared width";
  return s;
}

namespace {

const char* kMethod =
    "E = directional albedo with F = 1; A, B: Schlick split sum E_F = F0*A + F90*B (B = albedo with F = (1-o.h)^5, "
    "A = E - B on the same points); E_avg = 2*int E(mu) mu dmu as its own integral (mu^2 stratified). "
    "Estimator: the view reflected about visible normals of a GGX-shaped proposal of width alpha (its own code, "
    "never the D under test; Heitz 2018, sampled by spherical caps, Dupuy & Benyoub 2023) on randomized QMC "
    "(2D Kronecker sequence of the plastic number, R random shifts); standard error = spread of the R replicate "
    "means / sqrt(R)";

}  // namespace

void print_energy_console(const EnergyReport& rep) {
  const auto& o = rep.opt;
  const size_t nm = rep.mu.size(), na = rep.alpha.size();
  fmt::print("mfv energy: {} D x G combinations, {} F = none; {}; {} whole-model points{}\n", rep.tables.size(),
             rep.paired ? fmt::format("{} points,", na) : fmt::format("{}x{} (mu x alpha) grid,", nm, na),
             o.mu_axis.empty() ? "alpha log-spaced 1e-3..1, perceptual r = sqrt(alpha)" : energy_grid_text(rep),
             rep.models.size(), o.fp64 ? "; kernels in double (--fp64)" : "");
  if (!o.mu_axis.empty()) print_energy_cells(rep);
  const std::vector<double> show = {0.01, 0.1, 0.3, 1.0};
  std::vector<size_t> cols;
  for (double s : show) {
    size_t best = 0;
    for (size_t a = 0; a < na; ++a)
      if (std::fabs(std::log(rep.alpha[a] / s)) < std::fabs(std::log(rep.alpha[best] / s))) best = a;
    cols.push_back(best);
  }
  std::string head = fmt::format("{:<40}", "E_avg(alpha)");
  for (size_t c : cols) head += fmt::format(" {:>18}", fmt::format("alpha={:.3g}", rep.alpha[c]));
  if (!rep.tables.empty() && o.mu_axis.empty()) fmt::print("{}\n", head);
  for (auto& t : o.mu_axis.empty() ? rep.tables : std::vector<EnergyTable>{}) {
    std::string line = fmt::format("{:<40}", t.name());
    for (size_t c : cols) line += fmt::format(" {:>18}", fmt::format("{:.5f}±{:.1e}", t.eavg[c].mean, t.eavg[c].se));
    fmt::print("{}\n", line);
  }
  if (!rep.models.empty()) {
    fmt::print(
        "whole models: E(mu_l) with mu_l = the light's cosine, F as the model has it; gains = E > 1 beyond "
        "noise (one-sided t, Bonferroni over {} cells, family-wise {:g})\n",
        rep.models.size() * nm, o.gain_alpha);
    fmt::print("{:<36} {:>16} {:>22} {:>16} {:>10} {:>6} {:>9}\n", "model[case]",
               "E(mu_l=" + fmt::format("{:.3g}", rep.mu.back()) + ")", "max E (at mu_l)", "E_avg", "1 - E_avg", "gains",
               "catalog");
    for (auto& me : rep.models) {
      const Cell& mx = me.E[me.max_at];
      fmt::print("{:<36} {:>16} {:>22} {:>16} {:>10.5f} {:>6} {:>9}\n", me.point.name,
                 fmt::format("{:.5f}±{:.1e}", me.E.back().mean, me.E.back().se),
                 fmt::format("{:.4f}±{:.1e} ({:.3g})", mx.mean, mx.se, rep.mu[me.max_at]),
                 fmt::format("{:.5f}±{:.1e}", me.eavg.mean, me.eavg.se), me.loss(),
                 me.gains        ? "GAINS"
                 : me.unresolved ? "UNRES"
                                 : "no",
                 expect_name(me.point.expect));
    }
  }
  fmt::print(
      "accuracy: target standard error {:.1e} per value (R = {} replicates, {}..{} points each); achieved max "
      "{:.2e} at {}; {} values above target; {} run again, fresh, after ending above it\n",
      o.target, o.replicates, o.min_points, o.max_points, rep.max_se, rep.max_se_at, rep.above_target,
      rep.topped_up);
  fmt::print(
      "reference (double, identical samples): {} integrals x {} samples, worst relative difference {:.2e} "
      "(bound {:.0e}){}\n",
      rep.reference_compared, o.reference_samples, rep.reference_worst, rep.reference_bound,
      rep.reference_worst <= rep.reference_bound ? "" : " FAILED at " + rep.reference_worst_at);
  fmt::print(
      "{:.3g} QMC points (one BRDF evaluation each, E and B together) in {:.2f} s ({:.2f} s kernel build): "
      "{:.3g} points/s on {}\n",
      double(rep.samples), rep.seconds, rep.build_seconds, rep.samples_per_second, rep.device);
}

void print_baseline_console(const BaselineDiff& d) {
  for (auto& n : d.notes) fmt::print("baseline: {}\n", n);
  fmt::print("baseline: {} values compared (Welch t-test, Bonferroni p < {:.2e}): {} moved\n", d.compared,
             d.threshold_p, d.moved.size());
  for (size_t i = 0; i < d.moved.size() && i < 20; ++i) {
    auto& m = d.moved[i];
    fmt::print("  MOVED {}: {:.6f} -> {:.6f} (combined se {:.1e}, p = {:.1e})\n", m.where, m.before, m.after, m.se,
               m.p);
  }
  if (d.moved.size() > 20) fmt::print("  ... and {} more\n", d.moved.size() - 20);
}

namespace {

// One D/G table: [alpha index][mu index] arrays of E, A, B and their errors
// (paired points: flat arrays, one value per point), E_avg per alpha.
nlohmann::json table_json(const EnergyReport& rep, const EnergyTable& t) {
  using nlohmann::json;
  const size_t nm = rep.mu.size(), na = t.eavg.size();
  auto grid = [&](const std::vector<Cell>& v, bool se) {
    json rows = json::array();
    if (rep.paired) {
      for (auto& c : v) rows.push_back(se ? c.se : c.mean);
      return rows;
    }
    for (size_t a = 0; a < na; ++a) {
      json row = json::array();
      for (size_t m = 0; m < nm; ++m) row.push_back(se ? v[a * nm + m].se : v[a * nm + m].mean);
      rows.push_back(row);
    }
    return rows;
  };
  auto line = [&](const std::vector<Cell>& v, bool se) {
    json row = json::array();
    for (auto& c : v) row.push_back(se ? c.se : c.mean);
    return row;
  };
  json pts = json::array();
  if (rep.paired)
    pts = t.points;
  else
    for (size_t a = 0; a < na; ++a)
      pts.push_back(std::vector<uint64_t>(t.points.begin() + long(a * nm), t.points.begin() + long((a + 1) * nm)));
  json j{{"d", t.d->id},
         {"g", t.g->id},
         {"f", "none"},
         {"d_param", {{"name", t.d->params[0].name}, {"values", t.pd}}},
         {"g_param", t.g->params.empty() ? json(nullptr) : json{{"name", t.g->params[0].name}, {"values", t.pg}}},
         {"E", grid(t.E, false)},
         {"E_se", grid(t.E, true)},
         {t.bsdf ? "E_R" : "A", grid(t.A, false)},
         {t.bsdf ? "E_R_se" : "A_se", grid(t.A, true)},
         {t.bsdf ? "E_T" : "B", grid(t.B, false)},
         {t.bsdf ? "E_T_se" : "B_se", grid(t.B, true)},
         {"points_per_replicate", pts},
         {"E_avg", line(t.eavg, false)},
         {"E_avg_se", line(t.eavg, true)}};
  if (t.bsdf) j["bsdf"] = t.bsdf->id;  // a glass table: E_avg is the midpoint rule (E_avg_quadrature)
  if (rep.midpoint_mu) {  // the midpoint rule over mu applies to the midpoint grid only
    j["E_avg_quadrature"] = line(t.eavg_quad, false);
    j["E_avg_quadrature_se"] = line(t.eavg_quad, true);
  }
  return j;
}

// One whole-model point: E over the light cosines mu, E_avg, its gains and the catalog's expectation.
nlohmann::json model_json(const ModelEnergy& me, const std::vector<double>& mu) {
  using nlohmann::json;
  json params = json::object(), E = json::array(), se = json::array();
  for (size_t i = 0; i < me.point.model->params.size(); ++i) params[me.point.model->params[i].name] = me.point.p[i];
  for (auto& c : me.E) E.push_back(c.mean), se.push_back(c.se);
  return json{{"name", me.point.name},
              {"model", me.point.model->id},
              {"source", me.point.model->source},
              {"params", params},
              {"mu_is", "cosine of the light (E(l) = int f(l, v) (n.v) dv)"},
              {"E", E},
              {"E_se", se},
              {"points_per_replicate", me.points},
              {"E_avg", me.eavg.mean},
              {"E_avg_se", me.eavg.se},
              {"E_avg_quadrature", me.eavg_quad.mean},  // NaN (null) where mu is not the midpoint grid
              {"E_avg_quadrature_se", me.eavg_quad.se},
              {"energy_loss", me.loss()},
              {"max_E", me.E[me.max_at].mean},
              {"max_E_se", me.E[me.max_at].se},
              {"max_E_mu", mu[me.max_at]},
              {"excess_p", me.excess_p},
              {"gains", me.gains},
              {"unresolved", me.unresolved},
              {"catalog_expect", expect_name(me.point.expect)},
              {"catalog_why", me.point.why}};
}

}  // namespace

std::string energy_json(const EnergyReport& rep, const Runtime& rt) {
  using nlohmann::json;
  json j;
  j["schema"] = "mfv-energy/1";
  j["tool"] = {{"name", "mfv"}, {"version", MFV_VERSION}, {"commit", MFV_GIT_COMMIT}};
  j["provenance"] = provenance_json();  // command line, --kernel-dir, kernel hashes, device (runtime/provenance.hpp)
  if (!rep.shards.empty()) j["provenance"]["shards"] = rep.shards;  // mfv energy --merge
  j["device"] = {{"name", rt.device().name},
                 {"platform", rt.device().platform},
                 {"driver", rt.device().driver},
                 {"fp64", rt.device().fp64}};
  j["build_options"] = rt.base_options();
  j["date"] = utc_timestamp();
  j["parameterization"] = kEnergyParam;
  j["method"] = kMethod;
  std::vector<double> r;
  for (double a : rep.alpha) r.push_back(perceptual_from_alpha(a));
  j["grid"] = {{"definition", rep.opt.mu_axis.empty() ? energy_grid_text(rep) : "the caller's axes (mfv energy --mu/--alpha/--at)"},
               {"mu", rep.mu},
               {"alpha", rep.alpha},
               {"perceptual_r", r},
               {"layout", rep.paired ? "points: value i at (mu[i], alpha[i]), flat arrays"
                                     : "arrays are [alpha index][mu index]"}};
  if (rep.paired) j["grid"]["points"] = true;
  if (!rep.opt.roughness.empty()) j["grid"]["roughness"] = rep.opt.roughness;  // the given r, alpha = r²
  if (!rep.opt.layout.empty()) j["grid"]["engine_layout"] = rep.opt.layout;
  if (!rep.opt.eta.empty()) {  // a glass layout: the widths are (eta, roughness) pairs, eta slowest
    j["grid"]["eta"] = rep.opt.eta;
    j["grid"]["layout"] = "arrays are [width index][mu index], width = (eta, roughness) pair, eta slowest";
  }

  const auto& o = rep.opt;
  j["options"] = {{"seed", o.seed},
                  {"target_se", o.target},
                  {"replicates", o.replicates},
                  {"min_points", o.min_points},
                  {"max_points", o.max_points},
                  {"models", o.models},
                  {"reference_samples", o.reference_samples},
                  {"reference_every", o.reference_every}};
  if (o.fp64) j["options"]["fp64"] = true;  // the kernels in double
  j["summary"] = {{"max_se", rep.max_se},
                  {"max_se_at", rep.max_se_at},
                  {"values_above_target", rep.above_target},
                  {"values_run_again", rep.topped_up},
                  {"seconds", rep.seconds},
                  {"build_seconds", rep.build_seconds},
                  {"samples", rep.samples},
                  {"samples_per_second", rep.samples_per_second}};
  j["reference"] = {{"compared", rep.reference_compared},
                    {"worst_relative", rep.reference_worst},
                    {"bound", rep.reference_bound},
                    {"worst_at", rep.reference_worst_at},
                    {"ok", rep.reference_worst <= rep.reference_bound}};
  j["combinations"] = json::array();
  for (auto& t : rep.tables) j["combinations"].push_back(table_json(rep, t));
  j["models"] = json::array();
  for (auto& me : rep.models) j["models"].push_back(model_json(me, rep.mu));
  return j.dump(1);
}

namespace {

// Whole models: one row per point and light cosine; E_avg per point.
std::string models_csv(const EnergyReport& rep) {
  std::string s = fmt::format(
      "# mfv energy {}: whole models (host/catalog/models.cpp), E(mu_l) with mu_l = cos of the "
      "light, F as the model has it; seed {}; commit {}\n# grid: mu_l = (m + 1/2)/N_MU\n# "
      "method: {}\n",
      MFV_VERSION, rep.opt.seed, MFV_GIT_COMMIT, kMethod);
  s += "name,model,params,mu_index,mu_l,theta_l_deg,E,E_se,energy_loss,points\n";
  for (auto& me : rep.models) {
    std::string ps;
    for (size_t i = 0; i < me.point.model->params.size(); ++i)
      ps += fmt::format("{}{}={:.9g}", i ? ";" : "", me.point.model->params[i].name, me.point.p[i]);
    for (size_t m = 0; m < rep.mu.size(); ++m)
      s += fmt::format("\"{}\",{},{},{},{:.9g},{:.6f},{:.9g},{:.3e},{:.9g},{}\n", me.point.name, me.point.model->id, ps,
                       m, rep.mu[m], std::acos(rep.mu[m]) * 180 / M_PI, me.E[m].mean, me.E[m].se, 1 - me.E[m].mean,
                       me.points[m]);
  }
  return s;
}

std::string models_eavg_csv(const EnergyReport& rep) {
  std::string s = fmt::format(
      "# mfv energy {}: whole models, E_avg = 2 int E(mu_l) mu_l dmu_l (own integral; "
      "quadrature: midpoint rule over the mu grid), energy loss 1 - E_avg, largest E and "
      "whether it exceeds 1 beyond noise\n",
      MFV_VERSION);
  s += "name,model,E_avg,E_avg_se,E_avg_quadrature,E_avg_quadrature_se,energy_loss,max_E,max_E_se,max_E_mu_l,"
       "excess_p,gains,catalog_expect\n";
  for (auto& me : rep.models)
    s += fmt::format("\"{}\",{},{:.9g},{:.3e},{:.9g},{:.3e},{:.9g},{:.9g},{:.3e},{:.9g},{:.3e},{},{}\n", me.point.name,
                     me.point.model->id, me.eavg.mean, me.eavg.se, me.eavg_quad.mean, me.eavg_quad.se, me.loss(),
                     me.E[me.max_at].mean, me.E[me.max_at].se, rep.mu[me.max_at], me.excess_p, me.gains ? 1 : 0,
                     expect_name(me.point.expect));
  return s;
}

std::string csv_of(const EnergyReport& rep, const EnergyTable& t) {
  const size_t nm = rep.mu.size();
  std::string s = fmt::format("# mfv energy {}: D = {}, G = {}, F = none; seed {}; commit {}\n", MFV_VERSION, t.d->id,
                              t.g->id, rep.opt.seed, MFV_GIT_COMMIT);
  s += fmt::format("# parameterization: {}\n# grid: {} ({} x {})\n# method: {}\n", kEnergyParam, energy_grid_text(rep), nm, rep.alpha.size(),
                   kMethod);
  s += fmt::format("# accuracy: target standard error {:.1e}; *_se columns are each value's standard error\n",
                   rep.opt.target);
  s += fmt::format("alpha_index,alpha,perceptual_r,{},{},mu_index,mu,theta_deg,E,E_se,A,A_se,B,B_se,points\n",
                   "d_" + t.d->params[0].name, t.g->params.empty() ? "g_param" : "g_" + t.g->params[0].name);
  for (const CellAt& cell : rep.cells()) {
    const size_t a = cell.a, m = cell.m, c = cell.c;
    s += fmt::format("{},{:.9g},{:.9g},{:.9g},{:.9g},{},{:.9g},{:.6f},{:.9g},{:.3e},{:.9g},{:.3e},{:.9g},{:.3e},{}\n", a,
                     rep.alpha[a], std::sqrt(rep.alpha[a]), t.pd[a], t.pg[a], m, rep.mu[m],
                     std::acos(rep.mu[m]) * 180 / M_PI, t.E[c].mean, t.E[c].se, t.A[c].mean, t.A[c].se, t.B[c].mean,
                     t.B[c].se, t.points[c]);
  }
  return s;
}

std::string eavg_csv(const EnergyReport& rep) {
  std::string s = fmt::format(
      "# mfv energy {}: average albedo E_avg(alpha) = 2 int E(mu) mu dmu, F = none\n# "
      "parameterization: {}\n# grid: {}\n# E_avg: own integral; E_avg_quadrature: midpoint "
      "rule over the mu grid (cross-check)\n",
      MFV_VERSION, kEnergyParam, energy_grid_text(rep));
  s += "d,g,alpha_index,alpha,perceptual_r,E_avg,E_avg_se,E_avg_quadrature,E_avg_quadrature_se\n";
  for (auto& t : rep.tables)
    for (size_t a = 0; a < rep.alpha.size(); ++a)
      s += fmt::format("{},{},{},{:.9g},{:.9g},{:.9g},{:.3e},{:.9g},{:.3e}\n", t.d->id, t.g->id, a, rep.alpha[a],
                       std::sqrt(rep.alpha[a]), t.eavg[a].mean, t.eavg[a].se, t.eavg_quad[a].mean, t.eavg_quad[a].se);
  return s;
}

std::string report_md(const EnergyReport& rep, const Runtime& rt, const std::vector<std::string>& plots,
                      const BaselineDiff* base) {
  const auto& o = rep.opt;
  const size_t na = rep.alpha.size();
  std::string s = "# mfv energy: energy loss of single-scattering microfacet BRDFs\n\n";
  s += fmt::format("mfv {} (commit {}), seed {}, device {} ({}), {}.\n\n", MFV_VERSION, MFV_GIT_COMMIT, o.seed,
                   rt.device().name, rt.device().platform, utc_timestamp());
  s += fmt::format("- **Parameterization:** {}.\n- **Grid:** {} ({} x {}).\n- **Method:** {}.\n", kEnergyParam, energy_grid_text(rep),
                   rep.mu.size(), na, kMethod);
  s += fmt::format(
      "- **Accuracy:** target standard error {:.1e} per value (R = {} replicates of {}..{} points, "
      "doubled or more where above target); achieved max standard error **{:.2e}** ({}); {} values above "
      "target.\n",
      o.target, o.replicates, o.min_points, o.max_points, rep.max_se, rep.max_se_at, rep.above_target);
  s += fmt::format(
      "- **Reference:** the double-precision twin of the estimator on identical samples, {} integrals x {} "
      "samples: worst relative difference {:.2e} (bound {:.0e}).\n",
      rep.reference_compared, o.reference_samples, rep.reference_worst, rep.reference_bound);
  s += fmt::format(
      "- **Speed:** {:.3g} QMC points (one BRDF evaluation each, E and B together) in {:.1f} s ({:.1f} s "
      "kernel build), {:.3g} points/s.\n\n",
      double(rep.samples), rep.seconds, rep.build_seconds, rep.samples_per_second);
  // the files this run writes (energy_outputs): the tables' only where there are tables
  s += rep.tables.empty() ? "Files: `energy.json` (everything), `csv/models.csv`, `csv/models_eavg.csv`.\n\n"
                          : "Files: `energy.json` (everything, arrays [alpha][mu]), `csv/<d>__<g>.csv` (one per "
                            "combination, grid in the header), `csv/eavg.csv`, `kulla_conty.h` (E and E_avg arrays "
                            "for a renderer).\n\n";
  if (base) {
    s += fmt::format(
        "## Baseline comparison\n\n{} values compared (Welch t-test on the two standard errors, "
        "Bonferroni threshold p < {:.2e}): **{} moved**.\n\n",
        base->compared, base->threshold_p, base->moved.size());
    for (size_t i = 0; i < base->moved.size() && i < 50; ++i)
      s += fmt::format("- {}: {:.6f} -> {:.6f} (se {:.1e}, p = {:.1e})\n", base->moved[i].where, base->moved[i].before,
                       base->moved[i].after, base->moved[i].se, base->moved[i].p);
    for (auto& n : base->notes) s += "- note: " + n + "\n";
    s += "\n";
  }
  std::vector<size_t> cols;
  for (size_t a = 0; a < na; a += std::max<size_t>(1, na / 6)) cols.push_back(a);
  if (cols.back() != na - 1) cols.push_back(na - 1);
  if (!rep.tables.empty()) {
    s += "## E_avg(alpha)\n\n| D / G |";
    for (size_t c : cols) s += fmt::format(" alpha={:.3g} |", rep.alpha[c]);
    s += "\n|---|";
    for (size_t i = 0; i < cols.size(); ++i) s += "---|";
    s += "\n";
  }
  for (auto& t : rep.tables) {
    s += "| " + t.name() + " |";
    for (size_t c : cols) s += fmt::format(" {:.5f} |", t.eavg[c].mean);
    s += "\n";
  }
  if (!rep.models.empty()) {
    s += fmt::format(
        "\n## Whole models\n\nE(mu_l) with mu_l the light's cosine and F as the model has it "
        "(`csv/models.csv`, `csv/models_eavg.csv`); *gains*: some E(mu_l) exceeds 1 beyond noise "
        "(one-sided t, Bonferroni over {} cells, family-wise {:g}); *catalog*: what `mfv run`'s energy "
        "check expects at cos_l from 1e-4 to 1.\n\n",
        rep.models.size() * rep.mu.size(), o.gain_alpha);
    s += fmt::format(
        "| model[case] | E(mu_l={:.3g}) | max E (mu_l) | E_avg | 1 - E_avg | gains | catalog |\n"
        "|---|---|---|---|---|---|---|\n",
        rep.mu.back());
    for (auto& me : rep.models)
      s += fmt::format("| {} | {:.5f} ± {:.1e} | {:.4f} ± {:.1e} ({:.3g}) | {:.5f} ± {:.1e} | {:.5f} | {} | {} |\n",
                       me.point.name, me.E.back().mean, me.E.back().se, me.E[me.max_at].mean, me.E[me.max_at].se,
                       rep.mu[me.max_at], me.eavg.mean, me.eavg.se, me.loss(),
                       me.gains        ? "**yes**"
                       : me.unresolved ? "unresolved"
                                       : "no",
                       expect_name(me.point.expect));
  }
  if (!plots.empty()) {
    s += "\n## Plots\n\n";
    for (auto& p : plots) s += fmt::format("![{}](plots/{})\n\n", p, p);
  } else if (!rep.tables.empty()) {
    s += "\n(No plots: gnuplot was not available.)\n";
  }
  return s;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> energy_outputs(const EnergyReport& rep, const Runtime& rt,
                                                                const std::string& dir, const BaselineDiff* baseline) {
  std::vector<std::pair<std::string, std::string>> files;
  files.push_back({dir + "/energy.json", energy_json(rep, rt)});
  // a glass layout's tables (eta per width) are in energy.json and the layout's own files only
  const bool dxg = rep.opt.eta.empty();
  for (auto& t : rep.tables)
    if (dxg) files.push_back({dir + "/csv/" + energy_file_stem(t) + ".csv", csv_of(rep, t)});
  std::vector<std::string> names;
  if (!rep.tables.empty() && dxg) {  // D x G tables: their E_avg, the Kulla-Conty data, the plots
    files.push_back({dir + "/csv/eavg.csv", eavg_csv(rep)});
    files.push_back({dir + "/kulla_conty.h", energy_c_header(rep)});
    // KHR_materials_sheen's E_sheen (kernels/abi/sheen_table.h), on the default grid only
    const std::string sheen = rep.opt.mu_axis.empty() ? sheen_table_block(rep) : "";
    if (!sheen.empty()) files.push_back({dir + "/sheen_table.h", sheen});
    for (auto& [n, png] : energy_plots(rep, names)) files.push_back({dir + "/plots/" + n, png});
  }
  if (!rep.models.empty()) {
    files.push_back({dir + "/csv/models.csv", models_csv(rep)});
    files.push_back({dir + "/csv/models_eavg.csv", models_eavg_csv(rep)});
  }
  files.push_back({dir + "/report.md", report_md(rep, rt, names, baseline)});
  return files;
}

}  // namespace mfv
