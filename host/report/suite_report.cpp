#include "report/suite_report.hpp"
#include "mfv_git_commit.h"

#include "report/junit.hpp"
#include "runtime/provenance.hpp"
#include "util/files.hpp"
#include "util/parallel.hpp"
#include "util/version.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>

namespace mfv {
namespace {

// x to n significant digits, so the JSON carries what the statistics support
// and stays a few tens of bytes per record.
double sig(double x, int n) {
  if (!std::isfinite(x) || x == 0) return x;
  // strtod, not stod: a subnormal (a bound of 1e-320) reads back, stod throws out_of_range
  return std::strtod(fmt::format("{:.{}g}", x, n).c_str(), nullptr);
}

std::string params_text(const PointResult& p) {
  std::string s;
  for (auto& [k, v] : p.params) s += fmt::format("{}{}={:g}", s.empty() ? "" : " ", k, v);
  return s;
}

double total_seconds(const SuiteReport& rep) {
  double s = 0;
  for (auto& c : rep.stats) s += c.seconds;
  return s;
}

}  // namespace

std::string point_text(const PointResult& p) {
  if (p.bounded)
    return fmt::format("{} {:.3g} (bound {:.0e}){}{}{}{}", p.measure, p.estimate, p.bound,
                       p.params.empty() ? "" : " at ", params_text(p), p.detail.empty() ? "" : ": ", p.detail);
  // a NaN or infinite mean says why; a z beyond 1e6 in 2 significant digits, not hundreds of digits
  if (!std::isfinite(p.estimate) || !std::isfinite(p.stderr_))
    return fmt::format(
        "{} ± {} (some samples of the integrand were NaN or infinite; the check 'finite' or mfv "
        "stability names such inputs) vs {:g}{} at {}",
        p.estimate, p.stderr_, p.expected, p.upper_only ? " (max)" : "", params_text(p));
  const std::string z = std::fabs(p.z) < 1e6 ? fmt::format("{:.1f}", p.z) : fmt::format("{:.1e}", p.z);
  // detail: mfv check's double twin names the cause (formula error or float conditioning)
  return fmt::format("{:.6f} ± {:.1e} (+ bias {:.0e}, z {}) vs {:g}{} at {}{}{}", p.estimate, p.stderr_, p.bias, z,
                     p.expected, p.upper_only ? " (max)" : "", params_text(p), p.detail.empty() ? "" : ": ", p.detail);
}

std::string worst_text(const SuiteReport& rep, const GroupResult& g) { return point_text(rep.points[g.worst]); }

// The pooled test of a group, one line (stats/verdict.hpp).
std::string pooled_text(const GroupResult& g) {
  const stats::Pooled& p = g.pooled;
  return fmt::format("pooled over {} integrals: mean deviation {:+.2e} ± {:.1e} (bias bound {:.1e}), {} {:.2f} -> {}{}",
                     p.n, p.mean, p.se, p.bias, p.upper_only ? "one-sided z >" : "|z| >", p.threshold,
                     p.failed ? "FAIL" : "pass",
                     std::isfinite(p.mean + p.se) ? "" : " (some samples were NaN or infinite)");
}

// The same-sample comparison in one line: the double twin's derived bounds
// (reference_compare.hpp) or, without fp64, the float kernel's fixed bound.
std::string reference_line(const SuiteReport& rep) {
  const std::string at = rep.reference_worst_at.empty() ? "" : " at " + rep.reference_worst_at;
  if (rep.reference_twin)
    return fmt::format(
        "reference on the same samples (float kernel, its double twin, double reference): {} integrals "
        "compared, worst formula gap {:.2g} x its derived bound ({}){}",
        rep.reference_compared, rep.reference_worst, rep.reference_ok() ? "ok" : "FAILED", at);
  return fmt::format(
      "reference on the same samples: {} integrals compared, worst disagreement {:.2e} (bound {:g}: {}){}",
      rep.reference_compared, rep.reference_worst, rep.reference_bound, rep.reference_ok() ? "ok" : "FAILED", at);
}

OutputContext output_context(const Runtime& rt) {
  return {rt.device(), rt.base_options(), rt.build_stats().builds, provenance_json()};
}

void print_suite_console(const SuiteReport& rep, const Runtime& rt, const SuiteOptions& opt) {
  print_suite_console(rep, rt.device(), opt);
}

void print_suite_console(const SuiteReport& rep, const DeviceInfo& device, const SuiteOptions& opt) {
  fmt::print("device: {} ({}), {}\n", device.name, device.platform, device.driver);
  for (size_t d = 0; d < rep.device_shares.size(); ++d) {
    const DeviceShare& s = rep.device_shares[d];
    fmt::print("  device {} of {}: #{} {} ({}): {} integrals, {:.2f} s busy{}\n", d + 1, rep.device_shares.size(),
               s.index, s.name, s.platform, s.integrals, s.seconds, d == 0 ? "; reference, reciprocity, pointwise" : "");
  }
  fmt::print("{:<16} {:>10} {:>14} {:>8} {:>14}\n", "check", "integrals", "samples", "seconds", "samples/s");
  for (auto& c : rep.stats)
    fmt::print("{:<16} {:>10} {:>14} {:>8.2f} {:>14.3g}\n", c.check, c.integrals, c.samples, c.seconds,
               c.seconds > 0 ? double(c.samples) / c.seconds : 0.0);
  fmt::print(
      "kernel builds {:.2f} s (apart from run time); {} statistical tests and {} pooled, family-wise false-alarm "
      "{:g} (half each) -> |z| > {:.2f} per integral\n",
      rep.build_seconds, rep.tests, rep.pooled_tests, opt.family_alpha, rep.z_threshold);
  if (!rep.reference_note.empty())
    fmt::print("{}\n", rep.reference_note);
  else
    fmt::print("{}\n", reference_line(rep));
  size_t counts[5] = {0, 0, 0, 0, 0};
  for (auto& g : rep.groups) counts[int(g.verdict)]++;
  for (auto& g : rep.groups) {
    // pass lines are many; print the ones a person should read
    if (g.verdict == Verdict::Pass && !rep.list_passes) continue;
    fmt::print("{:<6} {:<15} {:<42} {}\n", verdict_name(g.verdict), g.check, g.model, worst_text(rep, g));
    if (!g.reason.empty() && g.verdict != Verdict::Fail) fmt::print("       {:<15} reason: {}\n", "", g.reason);
    if (g.pooled.failed) fmt::print("       {:<15} {}\n", "", pooled_text(g));
  }
  fmt::print("{} model x check verdicts: {} pass, {} xfail, {} FAIL, {} XPASS{}; {:.1f} s of integration\n",
             rep.groups.size(), counts[0], counts[2], counts[1], counts[3],
             counts[4] ? fmt::format(", {} INCONCLUSIVE", counts[4]) : "", total_seconds(rep));
  fmt::print("gate: {}\n", rep.gate_ok() ? "ok (every verdict matches expectation)" : "FAILED");
  for (auto& line : rep.gate_failures()) fmt::print("  because {}\n", line);
}

nlohmann::json point_record(const PointResult& p) {
  using nlohmann::json;
  json params = json::object();
  for (auto& [k, v] : p.params) params[k] = sig(v, 6);
  json r{{"check", p.check},
         {"D", p.d ? p.d->id : ""},
         {"G", p.g ? p.g->id : ""},
         {"F", p.f ? p.f->id : ""},
         {"model", p.model},
         {"params", params},
         {"estimate", std::isfinite(p.estimate) ? json(sig(p.estimate, 9)) : json(nullptr)},
         {"stderr", sig(p.stderr_, 3)},
         // upper bound on the float estimator's rounding bias (the double twin's), 0 where not measured
         {"rounding_bound", sig(p.rounding_bound, 3)},
         {"bias", sig(p.bias, 3)},  // the bias bound tested with (rounding + documented tolerance)
         {"z", std::isfinite(p.z) ? json(sig(p.z, 3)) : json(nullptr)},  // deviation / (stderr + bias)
         {"expected", p.expected},
         {"bound", sig(p.bound, 4)},
         {"samples", p.samples},
         {"verdict", p.failed ? "fail" : p.inconclusive ? "inconclusive" : "pass"}};
  if (p.reference_failed) r["reference"] = p.reference_detail;
  if (p.known) r["known"] = {{"value", sig(p.known_value, 9)}, {"error", sig(p.known_error, 3)}};
  // the catalog's prediction where it is not "holds"; the reason is in the group
  if (p.expect != Expect::Hold) r["expect"] = p.expect == Expect::Fail ? "fail" : "may_fail";
  if (p.bounded) r["measure"] = p.measure;  // a measured maximum against a fixed bound, not a z-test
  if (!p.detail.empty()) r["at"] = p.detail;
  return r;
}

// Compact JSON of the records, one per integral, over 10^5 of them: each
// record built and dumped on the host's threads into its own slot, then
// joined in order, the bytes of dumping the array (a compact array is
// "[" + its elements joined by "," + "]").
std::string results_array_json(const std::vector<PointResult>& points) {
  std::vector<std::string> records(points.size());
  parallel_for(points.size(), host_threads(), [&](size_t i) { records[i] = point_record(points[i]).dump(); });
  size_t length = 2 + records.size();
  for (auto& r : records) length += r.size();
  std::string out;
  out.reserve(length);
  out += '[';
  for (size_t i = 0; i < records.size(); ++i) {
    if (i) out += ',';
    out += records[i];
  }
  return out += ']';
}

// j.dump() with the value of the key "results" given as its text: a compact
// object is "{" + "KEY":VALUE joined by "," + "}", keys in j's (sorted) order.
std::string dump_with_results(const nlohmann::json& j, const std::string& results) {
  std::string out = "{";
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it != j.begin()) out += ',';
    out += nlohmann::json(it.key()).dump() + ':' + (it.key() == "results" ? results : it.value().dump());
  }
  return out += '}';
}

std::string suite_json(const SuiteReport& rep, const Runtime& rt, const SuiteOptions& opt) {
  return suite_json(rep, output_context(rt), opt);
}

std::string suite_json(const SuiteReport& rep, const OutputContext& ctx, const SuiteOptions& opt) {
  using nlohmann::json;
  const DeviceInfo& dev = ctx.device;
  json j;
  j["schema"] = "mfv-run/1";
  j["tool"] = {{"name", "mfv"},
               {"version", MFV_VERSION},
               {"commit", MFV_GIT_COMMIT},
               {"describe", MFV_GIT_DESCRIBE},
               {"command", rep.title}};
  j["provenance"] = ctx.provenance;  // command line, --kernel-dir, kernel hashes, device (runtime/provenance.hpp)
  j["run"] = {{"seed", opt.seed},
              {"scale", opt.scale},
              {"family_alpha", opt.family_alpha},
              {"z_threshold", rep.z_threshold},
              {"tests", rep.tests},
              {"pooled_tests", rep.pooled_tests},
              {"date", utc_timestamp()},
              {"checks", opt.checks},
              {"models", opt.models}};
  j["device"] = {{"name", dev.name},
                 {"platform", dev.platform},
                 {"driver", dev.driver},
                 {"version", dev.version},
                 {"fp64", dev.fp64}};
  for (const DeviceShare& s : rep.device_shares)  // mfv run --device all: who integrated what
    j["device"]["shared"].push_back({{"index", s.index},
                                     {"name", s.name},
                                     {"platform", s.platform},
                                     {"integrals", s.integrals},
                                     {"seconds", s.seconds}});
  j["build"] = {{"options", ctx.build_options}, {"seconds", rep.build_seconds}, {"builds", ctx.builds}};
  j["timings"] = json::array();
  for (auto& c : rep.stats)
    j["timings"].push_back(
        {{"check", c.check}, {"integrals", c.integrals}, {"samples", c.samples}, {"seconds", c.seconds}});
  j["reference"] = {{"compared", rep.reference_compared},    {"samples_each", opt.reference_samples},
                    {"worst_relative", rep.reference_worst}, {"bound", rep.reference_bound},
                    {"derived_bounds", rep.reference_twin},  {"ok", rep.reference_ok()},
                    {"worst_at", rep.reference_worst_at}};
  j["groups"] = json::array();
  for (auto& g : rep.groups)
    j["groups"].push_back({{"check", g.check},
                           {"model", g.model},
                           {"verdict", verdict_name(g.verdict)},
                           {"expected_fail", g.expect_fail},
                           {"reason", g.reason},
                           {"tolerance", g.tolerance},
                           {"points", g.points.size()},
                           {"failures", g.failures},
                           {"worst", worst_text(rep, g)},
                           {"pooled",
                            {{"integrals", g.pooled.n},
                             {"mean_deviation", sig(g.pooled.mean, 4)},
                             {"stderr", sig(g.pooled.se, 3)},
                             {"bias_bound", sig(g.pooled.bias, 3)},
                             {"z", sig(g.pooled.z, 3)},
                             {"threshold", sig(g.pooled.threshold, 4)},
                             {"upper_only", g.pooled.upper_only},
                             {"failed", g.pooled.failed}}}});
  j["results"] = json::array();  // its text is results_array_json's
  return dump_with_results(j, results_array_json(rep.points));
}

void write_suite_outputs(const SuiteReport& rep, const Runtime& rt, const SuiteOptions& opt, const std::string& dir) {
  write_files_atomically(suite_output_files(rep, rt, opt, dir));
}

std::vector<std::pair<std::string, std::string>> suite_output_files(const SuiteReport& rep, const Runtime& rt,
                                                                    const SuiteOptions& opt, const std::string& dir) {
  return suite_output_files(rep, output_context(rt), opt, dir);
}

std::vector<std::pair<std::string, std::string>> suite_output_files(const SuiteReport& rep, const OutputContext& ctx,
                                                                    const SuiteOptions& opt, const std::string& dir) {
  const DeviceInfo& dev = ctx.device;
  // report.md
  std::string md = rep.title == "mfv run" ? "# microfacet-verify conformance report\n\n"
                                          : fmt::format("# microfacet-verify: {}\n\n", rep.title);
  md += fmt::format("Device: {} ({}), driver {}. Seed {}, scale {:g}, mfv {}.\n\n", dev.name, dev.platform,
                    dev.driver, opt.seed, opt.scale, version_text());
  md += fmt::format(
      "{} statistical tests and {} pooled ones (docs/statistics.md); family-wise false-alarm rate {:g}, "
      "half to each family, so a deviation must exceed {:.2f} standard errors plus its bias bound "
      "(float rounding and the model's documented tolerance) to fail.\n\n",
      rep.tests, rep.pooled_tests, opt.family_alpha, rep.z_threshold);
  md += "| check | what it tests | integrals | samples | seconds | samples/s |\n|---|---|---:|---:|---:|---:|\n";
  for (auto& c : rep.stats) {
    const CheckKind* kind = find_check_kind(c.check);  // the registry's report line
    md += fmt::format("| {} | {} | {} | {} | {:.2f} | {:.3g} |\n", c.check, kind ? kind->summary : "", c.integrals,
                      c.samples, c.seconds, c.seconds > 0 ? double(c.samples) / c.seconds : 0.0);
  }
  md += fmt::format("\nKernel builds: {:.2f} s. ", rep.build_seconds);
  md += (!rep.reference_note.empty() ? rep.reference_note : reference_line(rep)) + "\n\n";
  md += "| verdict | check | model | worst case | expected failure because |\n|---|---|---|---|---|\n";
  for (auto& g : rep.groups)
    md += fmt::format("| {} | {} | {} | {} | {} |\n", verdict_name(g.verdict), g.check, g.model, worst_text(rep, g),
                      g.reason);
  md += fmt::format("\nGate: **{}**\n", rep.gate_ok() ? "ok" : "FAILED");
  for (auto& line : rep.gate_failures()) md += fmt::format("\n- because {}", line);
  if (!rep.gate_ok()) md += "\n";
  // every failing point of a failed group, not only its worst
  std::string failing;
  for (auto& g : rep.groups) {
    if (g.verdict != Verdict::Fail) continue;
    for (size_t i : g.points)
      if (rep.points[i].failed)
        failing += fmt::format("| {} | {} | {} |\n", g.check, g.model, point_text(rep.points[i]));
  }
  if (!failing.empty()) md += "\n## Every failing point\n\n| check | model | point |\n|---|---|---|\n" + failing;

  return {{dir + "/results.json", suite_json(rep, ctx, opt)},
          {dir + "/report.md", md},
          {dir + "/junit.xml", suite_junit(rep, opt)}};
}

}  // namespace mfv
