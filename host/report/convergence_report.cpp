// Outputs of mfv convergence: console summary, convergence.json (schema
// mfv-convergence/1), convergence.md (slopes, samples and time to 1e-3,
// 1e-4, 1e-5) and gnuplot log-log plots of error against samples and time.
#include "checks/convergence.hpp"
#include "mfv_git_commit.h"
#include "report/gnuplot.hpp"
#include "runtime/provenance.hpp"
#include "util/files.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace mfv {
namespace {

std::string num(double v, const char* f = "{:.3g}") { return std::isfinite(v) ? fmt::format(f, v) : "-"; }

std::string reach_cell(const ToleranceReach& t, bool samples) {
  if (std::isnan(t.n)) return "not reached";
  const double v = samples ? t.n : t.seconds;
  return (t.extrapolated ? "~" : "") + fmt::format(samples ? "{:.3g}" : "{:.2g} s", v);
}

size_t check_index(const ConvergenceReport& r, const std::string& c) {
  return size_t(std::find(r.checks.begin(), r.checks.end(), c) - r.checks.begin());
}

std::string stem(const ConvergenceReport& r, const std::string& check, size_t k) {
  const auto& c = r.cases[k];
  return fmt::format("{}_{}_a{:g}_cos{:g}", check, c.d, c.alpha, c.cos_o);
}

std::string tables(const ConvergenceReport& r, bool full) {
  std::string s;
  for (auto& ch : r.checks) {
    s += fmt::format(
        "\n### {}\n\n| case | truth | estimator | engine | slope | error at max n | n | N to 1e-3 | N to "
        "1e-4 | N to 1e-5 |{}\n|---|---|---|---|---|---|---|---|---|---|{}\n",
        ch, full ? " time to 1e-3 | time to 1e-4 | time to 1e-5 | z (top level) |" : "",
        full ? "---|---|---|---|" : "");
    const size_t ci = check_index(r, ch);
    for (size_t k = 0; k < r.cases.size(); ++k)
      for (auto& se : r.series) {
        if (se.check != ch || se.case_index != k || se.levels.empty()) continue;
        const auto& t = r.truth[ci][k];
        const auto& last = se.levels.back();
        s += fmt::format("| {} | {:.7f} | {} | {} | {} | {:.2e} | {} | {} | {} | {} |", r.cases[k].name(), t.value,
                         se.estimator, se.engine, num(se.slope, "{:.2f}"), last.rmse, last.n,
                         reach_cell(se.reach[0], true), reach_cell(se.reach[1], true), reach_cell(se.reach[2], true));
        if (full)
          s += fmt::format(" {} | {} | {} | {}{} |", reach_cell(se.reach[0], false), reach_cell(se.reach[1], false),
                           reach_cell(se.reach[2], false), num(se.z, "{:.1f}"), se.consistent ? "" : " INCONSISTENT");
        s += "\n";
      }
  }
  return s;
}

std::string json_of(const ConvergenceReport& r) {
  using nlohmann::json;
  auto finite = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json j;
  j["schema"] = "mfv-convergence/1";
  j["tool"] = {{"name", "mfv"}, {"version", MFV_VERSION}, {"commit", MFV_GIT_COMMIT}};
  j["provenance"] = provenance_json();  // command line, --kernel-dir, kernel hashes, device (runtime/provenance.hpp)
  j["date"] = r.date;
  j["device"] = {{"name", r.device}, {"platform", r.platform}};
  j["options"] = {{"min_log2", r.opt.min_log2},
                  {"max_log2", r.opt.max_log2},
                  {"ref_max_log2", r.opt.ref_max_log2},
                  {"replicates", r.opt.replicates},
                  {"quad_max_order", r.opt.quad_max_order},
                  {"seed", r.opt.seed},
                  {"reference", r.opt.reference}};
  j["seconds"] = r.seconds;
  j["consistency_level"] = r.level;
  j["cases"] = json::array();
  for (auto& c : r.cases) j["cases"].push_back({{"d", c.d}, {"alpha", c.alpha}, {"cos_o", c.cos_o}});
  j["truth"] = json::object();
  for (size_t ci = 0; ci < r.checks.size(); ++ci) {
    json a = json::array();
    for (auto& t : r.truth[ci])
      a.push_back(
          {{"value", t.value}, {"error", t.error}, {"method", t.method}, {"quadrature_check", t.quadrature_check}});
    j["truth"][r.checks[ci]] = a;
  }
  j["series"] = json::array();
  for (auto& s : r.series) {
    json x{{"check", s.check},          {"estimator", s.estimator},
           {"engine", s.engine},        {"case", s.case_index},
           {"slope", finite(s.slope)},  {"fit_from_n", s.levels.empty() ? 0 : s.levels[s.fit_from].n},
           {"z", finite(s.z)},          {"p", finite(s.p)},
           {"consistent", s.consistent}};
    x["levels"] = json::array();
    for (auto& l : s.levels)
      x["levels"].push_back(
          {{"n", l.n}, {"mean", l.mean}, {"rmse", l.rmse}, {"est_se", finite(l.est_se)}, {"seconds", l.seconds}});
    x["reach"] = json::array();
    for (auto& t : s.reach)
      x["reach"].push_back(
          {{"tol", t.tol}, {"n", finite(t.n)}, {"seconds", finite(t.seconds)}, {"extrapolated", t.extrapolated}});
    j["series"].push_back(x);
  }
  const auto& t = r.target;
  j["target"] = {{"measured", t.measured},
                 {"best", t.best},
                 {"best_n", t.best_n},
                 {"best_extrapolated", t.best_extrapolated},
                 {"uniform_n", finite(t.uniform_n)},
                 {"uniform_variance", finite(t.uniform_variance)},
                 {"uniform_n_variance", finite(t.uniform_n_variance)},
                 {"uniform_extrapolated", t.uniform_extrapolated},
                 {"uniform_n_clt", finite(t.uniform_n_clt)},
                 {"ratio", finite(t.ratio)},
                 {"text", t.line()}};
  return j.dump(1) + "\n";
}

// One PNG per check and case: error against samples and against time.
// One colour and point type per estimator (seven, none reused), solid for
// the device and dashed for the reference.
std::string series_style(const std::string& estimator, bool device) {
  static const std::vector<std::pair<std::string, std::string>> colours = {
      {"uniform", "#9400d3"}, {"cosine", "#009e73"}, {"mis", "#56b4e9"},       {"dsample", "#e69f00"},
      {"vndf", "#0072b2"},    {"rqmc", "#d55e00"},   {"quadrature", "#000000"}};
  size_t i = 0;
  while (i < colours.size() && colours[i].first != estimator) ++i;
  const std::string colour = i < colours.size() ? colours[i].second : "#808080";
  return fmt::format("lc rgb '{}' pt {} dt {}", colour, 4 + int(i) % 10, device ? 1 : 2);
}

NamedBytes plots(const ConvergenceReport& r, std::vector<std::string>& names) {
  NamedBytes data;
  std::string gp =
      "set encoding utf8\nset datafile missing 'nan'\nset logscale xy\nset format y '10^{%L}'\n"
      "set format x '10^{%L}'\nset key outside right noenhanced font ',8'\nset grid\n";
  for (auto& ch : r.checks)
    for (size_t k = 0; k < r.cases.size(); ++k) {
      const std::string st = stem(r, ch, k);
      std::string dat;
      std::vector<std::string> titles, styles;
      for (auto& s : r.series) {
        if (s.check != ch || s.case_index != k || s.levels.empty()) continue;
        for (auto& l : s.levels)  // one gnuplot block per series: n, error, seconds, estimated se
          dat += fmt::format("{} {:.6e} {:.6e} {:.6e}\n", l.n, std::max(l.rmse, 1e-16), l.seconds, l.est_se);
        dat += "\n\n";
        titles.push_back(fmt::format("{} ({}{})", s.estimator, s.engine == "device" ? "dev" : "ref",
                                     std::isfinite(s.slope) ? fmt::format(", {:.2f}", s.slope) : ""));
        styles.push_back(series_style(s.estimator, s.engine == "device"));
      }
      if (titles.empty()) continue;
      data.push_back({st + ".dat", dat});
      names.push_back(st + ".png");
      gp += fmt::format("set terminal pngcairo size 1300,480 font ',9'\nset output '{}.png'\n", st);
      gp += fmt::format("set multiplot layout 1,2 title '{}: {} (truth {:.7f})' noenhanced\n", ch, r.cases[k].name(),
                        r.truth[check_index(r, ch)][k].value);
      for (int panel = 0; panel < 2; ++panel) {
        gp += panel == 0 ? "set xlabel 'samples (quadrature: evaluations) per run'\nset ylabel 'RMS error'\n"
                         : "set xlabel 'wall seconds per run'\nset ylabel 'RMS error'\n";
        gp += "plot ";
        // The time panel joins its points in order of time ("smooth unique"):
        // at small counts launch overhead makes time non-monotone in samples,
        // and joining in sample order drew lines running backwards.
        for (size_t i = 0; i < titles.size(); ++i)
          gp += fmt::format("{}'{}.dat' index {} using {}:2 {}with linespoints {} ps 0.6 title '{}'", i ? ", " : "", st,
                            i, panel == 0 ? 1 : 3, panel == 0 ? "" : "smooth unique ", styles[i], titles[i]);
        gp += "\n";
      }
      gp += "unset multiplot\n";
    }
  NamedBytes pngs = render_gnuplot(data, gp, names);
  if (pngs.empty()) names.clear();
  return pngs;
}

std::string markdown(const ConvergenceReport& r, const std::vector<std::string>& pngs) {
  std::string s = "# mfv convergence: error against samples and time per estimator\n\n";
  s += fmt::format("mfv {} (commit {}), device {} ({}), {}; run took {:.0f} s.\n\n", MFV_VERSION, MFV_GIT_COMMIT,
                   r.device, r.platform, r.date, r.seconds);
  s += fmt::format(
      "- **Runs:** sample counts 2^{}..2^{} on the device, 2^{}..2^{} in the double reference (one thread, the same "
      "Philox samples, so its errors repeat the device's up to float rounding; it differs in time); {} independent "
      "replicates per count (RQMC: independent random shifts).\n",
      r.opt.min_log2, r.opt.max_log2, r.opt.min_log2, std::min(r.opt.ref_max_log2, r.opt.max_log2), r.opt.replicates);
  s += "- **Error** is the RMS over replicates of |estimate - truth|, the error one run of n samples makes. The "
       "**estimated standard error** of one run comes from its samples (MC), from the spread of the random shifts "
       "(RQMC), or from the previous order (quadrature). **Time** is wall seconds per run: a device launch holds "
       "every case and replicate of one estimator and count, and its time is divided among them.\n";
  s += "- **Slope** is the least-squares slope of log error on log n over the upper half of the counts (the "
       "asymptotic regime), above the float floor (3e-7 relative). MC estimators converge as n^-1/2, RQMC on smooth "
       "integrands close to n^-1; quadrature faster than any power until its floor.\n";
  s += "- **N / time to a tolerance:** the first count from which every measured error stays at or below it; `~` "
       "marks an extrapolation from the last measured error at n^-1/2 (iid MC: the CLT rate) or at the fitted "
       "slope (RQMC, at most -1/2), time proportional to n; pre-asymptotic runs (error ~ the integral: the lobe not "
       "yet found) make such extrapolations far too optimistic. \"not reached\": quadrature that stopped short.\n";
  s += fmt::format(
      "- **z (top level):** (mean of the replicates - truth) / its standard error; INCONSISTENT where "
      "p < {:.1e} (Sidak, family-wise 1e-3; Student t with R-1 dof for RQMC). A biased estimator "
      "shows here, and so does an unbiased one whose samples have not yet found the lobe "
      "(pre-asymptotic: uniform or cosine sampling at alpha = 1e-3), where the standard error "
      "estimate means nothing yet; and a rare event not yet drawn: at GGX alpha = 1e-3 and normal view "
      "the albedo's whole loss (4e-8 of 0.04) comes from half vectors beyond 45 degrees, which D "
      "sampling draws with probability alpha^2 = 1e-6, so runs without one estimate 0.04 with a "
      "standard error of 0. The device's float rounding (3e-7 relative) is part of the allowed "
      "deviation.\n",
      r.level);
  s += "- **Estimators:** uniform hemisphere; cosine-weighted; mis = the conformance suite's proposal (d_norm: "
       "cosine lobe + Cauchy slopes, stratified; albedo: cosine + reflected mixture, balance heuristic); dsample = "
       "half vectors from D of the case's shape (GGX or Beckmann, width alpha), albedo only; vndf = visible normals "
       "of the GGX shape (Heitz 2018; Dupuy & Benyoub 2023), albedo only; rqmc = Roberts' 2D Kronecker points with "
       "a Philox Cranley-Patterson shift (albedo: through vndf; d_norm: through the Cauchy slopes); quadrature = "
       "the product Gauss-Legendre rule of the truth at orders 2..max, reference only. D normalization is never "
       "estimated by sampling D: its weight would be 1 by construction.\n";
  s += "- **Truth:** d_norm = 1 (closed form); albedo by the product rule over half vectors (panels geometric "
       "towards the peak and towards the horizon cut), with its error from a coarser rule.\n\n";
  s += "## Target\n\n" + r.target.line() +
       "\n\n## Truth\n\n| check | case | value | error estimate |\n|---|---|---|---|\n";
  for (size_t ci = 0; ci < r.checks.size(); ++ci)
    for (size_t k = 0; k < r.cases.size(); ++k) {
      const auto& t = r.truth[ci][k];
      s += fmt::format("| {} | {} | {:.9f} | {} |\n", r.checks[ci], r.cases[k].name(), t.value,
                       r.checks[ci] == "d_norm"
                           ? fmt::format("exact (quadrature gives 1 {:+.1e})", t.quadrature_check - 1)
                           : fmt::format("{:.1e}", t.error));
    }
  s += "\n## Slopes and samples / time to tolerance\n" + tables(r, true);
  if (!pngs.empty()) {
    s += "\n## Plots\n\n";
    for (auto& p : pngs) s += fmt::format("![{}](plots/{})\n\n", p, p);
  } else {
    s += "\n(No plots: gnuplot was not available.)\n";
  }
  return s;
}

}  // namespace

void print_convergence(const ConvergenceReport& r) {
  fmt::print("device: {} ({}); {} cases x {} checks; {:.1f} s\n", r.device, r.platform, r.cases.size(), r.checks.size(),
             r.seconds);
  fmt::print("{}\n", tables(r, false));
  int bad = 0;
  for (auto& s : r.series)
    if (!s.consistent) {
      if (bad++ < 20)
        fmt::print("inconsistent: {} {} {} {}: z = {:.1f} (biased, or not yet resolving the lobe)\n", s.check,
                   r.cases[s.case_index].name(), s.estimator, s.engine, s.z);
    }
  fmt::print("{} series inconsistent with the truth at p < {:.1e}\n{}\n", bad, r.level, r.target.line());
}

std::vector<std::pair<std::string, std::string>> convergence_outputs(const ConvergenceReport& rep,
                                                                     const std::string& dir) {
  std::vector<std::pair<std::string, std::string>> files;
  files.push_back({dir + "/convergence.json", json_of(rep)});
  std::vector<std::string> names;
  for (auto& [n, png] : plots(rep, names)) files.push_back({dir + "/plots/" + n, png});
  files.push_back({dir + "/convergence.md", markdown(rep, names)});
  return files;
}

}  // namespace mfv
