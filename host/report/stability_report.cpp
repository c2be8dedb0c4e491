// Outputs of mfv stability: console table, JSON (schema mfv-stability/1),
// Markdown, and gnuplot plots of error over θ and α. Files are written whole
// or not at all (docs/design.md §7).
#include "report/stability_report.hpp"
#include "mfv_git_commit.h"

#include "report/gnuplot.hpp"
#include "runtime/provenance.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>

namespace mfv {
namespace {

std::string num(double x) {
  if (std::isinf(x)) return "inf";
  if (x == 0) return "0";
  return fmt::format("{:.3g}", x);
}

// The region where a case breaks first (in region order), or "-".
const RegionResult* first_broken(const StabilityCase& c) {
  for (auto& r : c.regions)
    if (r.breaks) return &r;
  return nullptr;
}

std::string breaks_in(const StabilityCase& c) {
  std::string s;
  for (auto& r : c.regions)
    if (r.breaks) s += (s.empty() ? "" : ", ") + fmt::format("{} ({}/{})", r.region, r.breaks, r.points);
  return s.empty() ? "-" : s;
}

uint64_t points_of(const StabilityCase& c) {
  uint64_t n = 0;
  for (auto& r : c.regions) n += r.points;
  return n;
}

}  // namespace

std::string stability_console(const StabilityReport& rep) {
  std::string o;
  o += fmt::format("device: {} ({}), {}; kernels in {}\n", rep.device, rep.platform, rep.driver, rep.precision);
  o += fmt::format("{:<40} {:>6} {:>5} {:>5} {:>5} {:>10} {:>6}  {}\n", "case (in-domain regions)", "points", "NaN",
                   "Inf", "neg", "max ulps", "stable", "breaks in (count/points)");
  auto row = [&](const StabilityCase& c) {
    std::string mark = c.group == "variant" ? (c.is_default ? "dflt" : "alt") : (c.stable ? "yes" : "no");
    o += fmt::format("{:<40} {:>6} {:>5} {:>5} {:>5} {:>10} {:>6}  {}\n", c.name, points_of(c),
                     c.count(&RegionResult::nan, true), c.count(&RegionResult::inf, true),
                     c.count(&RegionResult::negative, true), num(c.max_ulps()), mark, breaks_in(c));
  };
  uint64_t brdfs = 0, brdf_nan = 0, brdf_inf = 0, brdf_neg = 0, brdf_breaks = 0;
  double brdf_ulps = 0;
  std::string brdf_worst;
  for (auto& c : rep.cases) {
    if (c.group != "brdf") {
      row(c);
      continue;
    }
    ++brdfs;
    brdf_nan += c.count(&RegionResult::nan, true);
    brdf_inf += c.count(&RegionResult::inf, true);
    brdf_neg += c.count(&RegionResult::negative, true);
    brdf_breaks += c.count(&RegionResult::breaks, true);
    if (c.max_ulps() >= brdf_ulps) {
      brdf_ulps = c.max_ulps();
      brdf_worst = c.name;
    }
    // A BRDF that gives NaN, Inf or negative values gets its own line.
    if (c.count(&RegionResult::nan, true) + c.count(&RegionResult::inf, true) + c.count(&RegionResult::negative, true))
      row(c);
  }
  if (brdfs)
    o += fmt::format("{} BRDF combinations: {} NaN, {} Inf, {} negative, {} breaking points; max {} ulps ({})\n", brdfs,
                     brdf_nan, brdf_inf, brdf_neg, brdf_breaks, num(brdf_ulps), brdf_worst);
  for (auto& c : rep.cases)
    if (c.group == "variant")
      if (auto* r = first_broken(c)) o += fmt::format("  {} first breaks at {}\n", c.name, r->first_break);
  o += fmt::format("{} points; build {:.2f} s, kernel {:.2f} s, reference {:.2f} s, total {:.2f} s\n", rep.points,
                   rep.build_seconds, rep.kernel_seconds, rep.reference_seconds, rep.total_seconds);
  if (rep.gate_pass())
    o += "gate: pass (no term marked stable gives NaN or Inf on in-domain inputs)\n";
  else
    for (auto& f : rep.gate_failures) o += "gate: FAIL " + f + "\n";
  return o;
}

std::string stability_json(const StabilityReport& rep) {
  using nlohmann::json;
  json j;
  j["schema"] = "mfv-stability/1";
  j["tool"] = {{"version", MFV_VERSION}, {"commit", MFV_GIT_COMMIT}};
  j["provenance"] = provenance_json();  // command line, --kernel-dir, kernel hashes, device (runtime/provenance.hpp)
  if (!rep.shards.empty()) j["provenance"]["shards"] = rep.shards;  // mfv stability --merge
  j["created"] = utc_timestamp();
  j["device"] = {{"name", rep.device}, {"platform", rep.platform}, {"driver", rep.driver}};
  j["precision"] = rep.precision;
  j["build_options"] = rep.build_options;
  j["break_ulps"] = kBreakUlps;
  j["reference_limited"] = rep.precision == "float64";  // a double reference judges a double kernel
  j["points"] = rep.points;
  j["seconds"] = {{"build", rep.build_seconds},
                  {"kernel", rep.kernel_seconds},
                  {"reference", rep.reference_seconds},
                  {"total", rep.total_seconds}};
  j["gate"] = {{"pass", rep.gate_pass()}, {"failures", rep.gate_failures}};
  j["cases"] = json::array();
  for (auto& c : rep.cases) {
    json jc{{"name", c.name},       {"group", c.group},   {"family", c.family},
            {"formula", c.formula}, {"stable", c.stable}, {"default", c.is_default}};
    jc["regions"] = json::array();
    for (auto& r : c.regions) {
      json jr{{"region", r.region},     {"inputs", r.what},   {"in_domain", r.in_domain},
              {"points", r.points},     {"nan", r.nan},       {"inf", r.inf},
              {"negative", r.negative}, {"breaks", r.breaks}, {"max_rel", r.max_rel},
              {"max_ulps", r.max_ulps}, {"worst", r.worst},   {"first_break", r.first_break}};
      jr["out_of_domain"] = r.out_of_domain;  // outside the value's domain where the reference is inside
      if (!r.first_out_of_domain.empty()) jr["first_out_of_domain"] = r.first_out_of_domain;
      if (!r.expect.empty()) {
        jr["expect"] = r.expect;
        jr["violations"] = r.violations;
        jr["reference_violations"] = r.ref_violations;
      }
      jc["regions"].push_back(jr);
    }
    j["cases"].push_back(jc);
  }
  return j.dump(1) + "\n";
}

std::string stability_markdown(const StabilityReport& rep) {
  std::string o;
  o += "# mfv stability\n\n";
  o += fmt::format("Device **{}** ({}, {}), kernels in **{}**, build options `{}`; mfv {} ({}), {}.\n\n", rep.device,
                   rep.platform, rep.driver, rep.precision, rep.build_options, MFV_VERSION, MFV_GIT_COMMIT,
                   utc_timestamp());
  o += fmt::format("{} points; build {:.2f} s, kernel {:.2f} s, reference {:.2f} s, total {:.2f} s.\n\n", rep.points,
                   rep.build_seconds, rep.kernel_seconds, rep.reference_seconds, rep.total_seconds);
  o += "Every point is evaluated by the kernel and by the double reference on identical (rounded) inputs. ";
  o += fmt::format(
      "*Inf* counts kernel infinities where the reference is finite; *neg* counts negative kernel "
      "values where the reference is not; a point *breaks* when it is NaN, Inf, negative or more than "
      "{} ulps from the reference (and further from it than the smallest normal number). *expect* is "
      "the value the seeds prescribe (seed 000: G1 = 1 at (v.n) >= 1 and at tan = 0; every D, G, G1 and "
      "BRDF is 0 below the horizon), with violations by kernel / reference.\n\n",
      kBreakUlps);
  if (rep.precision == "float64")
    o += "In float64 the double reference is no more precise than the kernel: accuracy breaks there include the "
         "reference's own losses (e.g. D through n.h where 1 - n.h is below ~1e-8, or (n.h)^alpha_p for large "
         "alpha_p); the NaN, Inf and negative counts do not depend on it.\n\n";
  o += rep.gate_pass() ? "**Gate: pass** — no term marked stable gives NaN or Inf on in-domain inputs.\n\n"
                       : "**Gate: FAIL**\n\n";
  for (auto& f : rep.gate_failures) o += "- " + f + "\n";
  if (!rep.gate_pass()) o += "\n";

  auto table = [&](const std::string& title, const std::string& group) {
    bool any = std::any_of(rep.cases.begin(), rep.cases.end(), [&](auto& c) { return c.group == group; });
    if (!any) return;
    o += "## " + title + "\n\n";
    o += "| case | region | in domain | points | NaN | Inf | neg | breaks | expect (viol. k/r) | max rel | max ulps | "
         "first break |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (auto& c : rep.cases) {
      if (c.group != group) continue;
      std::string name =
          c.name + (group == "variant" ? (c.is_default ? " (default)" : "") : (c.stable ? "" : " (not stable)"));
      for (auto& r : c.regions) {
        std::string ex = r.expect.empty() ? "" : fmt::format("{} ({}/{})", r.expect, r.violations, r.ref_violations);
        o += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", name, r.region,
                         r.in_domain ? "yes" : "no", r.points, r.nan, r.inf, r.negative, r.breaks, ex, num(r.max_rel),
                         num(r.max_ulps), r.first_break.empty() ? "" : "`" + r.first_break + "`");
      }
    }
    o += "\n";
  };
  table("Terms and Smith G1", "term");
  table("Alternative formulations (where each form breaks)", "variant");
  table("Rough dielectric BTDFs (Walter et al. 2007, both sides)", "bsdf");
  bool any_brdf = std::any_of(rep.cases.begin(), rep.cases.end(), [](auto& c) { return c.group == "brdf"; });
  if (any_brdf) {
    o += "## Assembled BRDFs (kd = 0)\n\nOne row per D/G/F combination over every region; regions in which it "
         "breaks are named with count/points.\n\n";
    o += "| BRDF | stable | points | NaN | Inf | neg | breaks | max ulps | breaks in | first break |\n"
         "|---|---|---|---|---|---|---|---|---|---|\n";
    for (auto& c : rep.cases) {
      if (c.group != "brdf") continue;
      auto* fb = first_broken(c);
      o += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", c.name, c.stable ? "yes" : "no",
                       points_of(c), c.count(&RegionResult::nan, false), c.count(&RegionResult::inf, false),
                       c.count(&RegionResult::negative, false), c.count(&RegionResult::breaks, false),
                       num(c.max_ulps()), breaks_in(c), fb ? "`" + fb->first_break + "`" : "");
    }
    o += "\nBRDF regions: ";
    for (auto& c : rep.cases)
      if (c.group == "brdf") {
        for (auto& r : c.regions) o += fmt::format("*{}*: {}. ", r.region, r.what);
        break;
      }
    o += "\n\n";
  }
  o += "## Plots\n\n`error_theta_d.svg`, `error_theta_g1.svg` (and `.png`): ulps against the reference over θ (near "
       "the normal and "
       "near grazing) for the GGX forms and the catalog terms; `error_alpha.svg`: the largest error over θ for each "
       "alpha. NaN, Inf and negative results are drawn at 1e12 ulps, exact results at 0.01.\n";
  return o;
}

namespace {

// Plot data: one block per series (gnuplot `index`), columns theta, ulps.
struct Plot {
  std::string file, title;
  std::vector<std::pair<std::string, std::vector<std::pair<double, double>>>> series;  // name, (x, y)
  bool log_x = true;
  std::string xlabel;
};

double plot_y(double ulps) { return std::isinf(ulps) || std::isnan(ulps) ? 1e12 : std::max(ulps, 1e-2); }

const ScanSeries* find_scan(const StabilityReport& rep, const std::string& name) {
  for (auto& s : rep.scans)
    if (s.name == name) return &s;
  return nullptr;
}

void add_theta_series(Plot& p, const StabilityReport& rep, const std::string& name, double alpha) {
  auto* s = find_scan(rep, name);
  if (!s) return;
  std::vector<std::pair<double, double>> pts;
  for (auto& q : s->points)
    if (q.alpha == alpha) pts.push_back({q.theta, plot_y(q.ulps)});
  if (!pts.empty()) p.series.push_back({fmt::format("{} (alpha {:g})", name, alpha), pts});
}

std::string data_text(const Plot& p) {
  std::string o = "# " + p.title + "\n";
  for (auto& [name, pts] : p.series) {
    o += "# " + name + "\n";
    for (auto& [x, y] : pts) o += fmt::format("{:.17g} {:.6g}\n", x, y);
    o += "\n\n";
  }
  return o;
}

// The plot as SVG and as PNG: the same commands under two terminals, written
// to OUT.svg.tmp-mfv and OUT.png.tmp-mfv (renamed in place on success).
std::string gnuplot_body(const Plot& p, const std::string& data);
std::string gnuplot_text(const Plot& p, const std::string& data, const std::string& out) {
  const int height = p.log_x ? 900 : 560;
  return fmt::format("set terminal svg size 1200,{} dynamic noenhanced\nset output '{}.svg.tmp-mfv'\n", height, out) +
         gnuplot_body(p, data) +
         fmt::format("set terminal pngcairo size 1200,{} noenhanced font ',9'\nset output '{}.png.tmp-mfv'\n", height,
                     out) +
         gnuplot_body(p, data);
}

std::string gnuplot_body(const Plot& p, const std::string& data) {
  std::string o = "reset\nset logscale y\nset format y '1e%L'\nset key outside right\n";
  o += "set ylabel 'ulps vs double reference'\nset yrange [1e-2:1e13]\n";
  if (p.log_x) {
    // θ near the normal on the left panel, π/2 − θ near grazing on the right.
    o += "set multiplot layout 2,1 title '" + p.title + "'\nset logscale x\nset format x '1e%L'\n";
    o += "set xlabel 'theta (rad), near the normal'\nset xrange [1e-8:1]\nplot ";
    for (size_t i = 0; i < p.series.size(); ++i)
      o += fmt::format("{}'{}' index {} using 1:($1 < 1 ? $2 : 1/0) with linespoints {} title '{}'", i ? ", " : "",
                       data, i, series_colour(i), p.series[i].first);
    o += "\nset xlabel 'pi/2 - theta (rad), near grazing'\nset xrange [1e-8:1]\nplot ";
    for (size_t i = 0; i < p.series.size(); ++i)
      o += fmt::format("{}'{}' index {} using (pi/2 - $1):($1 > 1 ? $2 : 1/0) with linespoints {} title '{}'",
                       i ? ", " : "", data, i, series_colour(i), p.series[i].first);
    o += "\nunset multiplot\n";
  } else {
    o += "set title '" + p.title + "'\nset logscale x\nset format x '1e%L'\nset xlabel '" + p.xlabel + "'\nplot ";
    for (size_t i = 0; i < p.series.size(); ++i)
      o += fmt::format("{}'{}' index {} using 1:2 with linespoints {} title '{}'", i ? ", " : "", data, i,
                       series_colour(i), p.series[i].first);
    o += "\n";
  }
  return o;
}

std::vector<Plot> make_plots(const StabilityReport& rep) {
  std::vector<Plot> plots;
  Plot d{"error_theta_d", "GGX D forms and catalog D terms, " + rep.precision, {}, true, ""};
  for (double a : {1e-3, 0.3})
    for (auto* n : {"variant D_ggx via tan2", "variant D_ggx via (n.h)^2(a^2-1)+1", "variant D_ggx via |n x h|^2"})
      add_theta_series(d, rep, n, a);
  for (auto& s : rep.scans)
    if (s.name.rfind("D ", 0) == 0) add_theta_series(d, rep, s.name, 1e-2);
  Plot g{"error_theta_g1", "Smith GGX Lambda and G1 forms and catalog G1 terms, " + rep.precision, {}, true, ""};
  for (auto* n :
       {"variant Lambda_ggx via tan2", "variant Lambda_ggx via cos", "variant Lambda_ggx via x/(2(1+sqrt(1+x)))",
        "variant G1_smith_ggx via Lambda", "variant G1_smith_ggx closed form"})
    add_theta_series(g, rep, n, 0.3);
  for (auto& s : rep.scans)
    if (s.name.rfind("G1 ", 0) == 0) add_theta_series(g, rep, s.name, 0.3);
  Plot a{"error_alpha", "largest error over theta, per alpha, " + rep.precision, {}, false, "alpha (shared width)"};
  for (auto& s : rep.scans) {
    std::map<double, double> worst;
    for (auto& q : s.points) worst[q.alpha] = std::max(worst[q.alpha], plot_y(q.ulps));
    std::vector<std::pair<double, double>> pts(worst.begin(), worst.end());
    a.series.push_back({s.name, pts});
  }
  for (auto* p : {&d, &g, &a})
    if (!p->series.empty()) plots.push_back(*p);
  return plots;
}

// gnuplot from MFV_GNUPLOT, else from PATH; "" when there is none.
std::string find_gnuplot() {
  if (const char* e = std::getenv("MFV_GNUPLOT")) return ::access(e, X_OK) == 0 ? e : "";
  const char* path = std::getenv("PATH");
  std::string p = path ? path : "";
  size_t start = 0;
  while (start <= p.size()) {
    size_t end = p.find(':', start);
    if (end == std::string::npos) end = p.size();
    std::string cand = p.substr(start, end - start) + "/gnuplot";
    if (end > start && ::access(cand.c_str(), X_OK) == 0) return cand;
    start = end + 1;
  }
  return "";
}

std::string shell_quote(const std::string& s) {
  std::string o = "'";
  for (char c : s) o += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return o + "'";
}

}  // namespace

std::vector<std::string> write_stability_outputs(const StabilityReport& rep, const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw Error(fmt::format("--out {}: cannot create that folder", dir));
  auto plots = make_plots(rep);
  std::vector<std::pair<std::string, std::string>> files = {{dir + "/stability.json", stability_json(rep)},
                                                            {dir + "/stability.md", stability_markdown(rep)}};
  for (auto& p : plots) {
    files.push_back({dir + "/" + p.file + ".dat", data_text(p)});
    // The script writes to a temporary name; the svg is renamed in place only when gnuplot succeeded.
    files.push_back({dir + "/" + p.file + ".gp", gnuplot_text(p, p.file + ".dat", p.file)});
  }
  write_files_atomically(files);

  std::vector<std::string> notes;
  notes.push_back(fmt::format("wrote {}/stability.json and {}/stability.md", dir, dir));
  if (plots.empty()) return notes;
  std::string gp = find_gnuplot();
  if (gp.empty()) {
    notes.push_back("plots skipped: gnuplot not found (apt-get install gnuplot-nox); plot data and scripts are in " +
                    dir);
    return notes;
  }
  std::vector<std::string> made;
  for (auto& p : plots) {
    std::string cmd = fmt::format("cd {} && {} {}.gp >/dev/null 2>&1", shell_quote(dir), shell_quote(gp), p.file);
    int st = std::system(cmd.c_str());
    for (const char* ext : {".svg", ".png"}) {
      fs::path tmp = fs::path(dir) / (p.file + ext + ".tmp-mfv"), out = fs::path(dir) / (p.file + ext);
      if (st == 0 && WIFEXITED(st) && fs::exists(tmp)) {
        fs::rename(tmp, out, ec);
        if (!ec) made.push_back(out.string());
      } else {
        fs::remove(tmp, ec);
      }
    }
    if (!(st == 0 && WIFEXITED(st))) notes.push_back(fmt::format("plot {} failed: {} exited with {}", p.file, gp, st));
  }
  if (!made.empty()) {
    std::string list;
    for (auto& m : made) list += (list.empty() ? "" : ", ") + m;
    notes.push_back("plots: " + list);
  }
  return notes;
}

}  // namespace mfv
