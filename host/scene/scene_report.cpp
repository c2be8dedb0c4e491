// Console, results.json and report.md sections of mfv run --scene: one entry
// per material, by name; what was left out against the full catalog; time.
#include "report/junit.hpp"
#include "report/suite_report.hpp"
#include "scene/scene_checks.hpp"
#include "util/files.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>

namespace mfv {
namespace {

using nlohmann::json;

// One check of one material in a line: verdict and the number that matters.
struct CheckLine {
  std::string check, set, verdict, text, reason;
  double e_normal = std::numeric_limits<double>::quiet_NaN(),
         e_grazing = e_normal;  // furnace: E at cos 1 and the smallest cos
  double grazing_cos = 0;
};

// The fixed direction's cosine: the view (cos_o) of a D/G/F integral, the
// light (cos_l) of a whole model's albedo (checks/suite.hpp).
double fixed_cos(const PointResult& p) {
  auto it = p.params.find("cos_o");
  return it != p.params.end() ? it->second : p.params.at("cos_l");
}
const char* fixed_name(const PointResult& p) { return p.params.count("cos_o") ? "cos_o" : "cos_l"; }

CheckLine check_line(const SuiteReport& rep, const GroupResult& g) {
  CheckLine c{g.check, g.model, verdict_name(g.verdict), "", g.verdict == Verdict::Pass ? "" : g.reason};
  const PointResult& w = rep.points[g.worst];
  if (g.check == "reciprocity") {
    c.text = fmt::format("max asymmetry {:.2g} (bound {:.0e})", w.estimate, w.bound);
  } else if (g.check == "d_norm") {
    c.text = fmt::format("{:.7f} ± {:.1e} (= 1)", w.estimate, w.stderr_);
  } else if (g.check == "masking") {
    c.text = fmt::format("worst {:.4f} ± {:.1e} at cos_o={:.3g} (= 1)", w.estimate, w.stderr_, w.params.at("cos_o"));
  } else if (const Shape sh = shape_of(check_kind(g.check));
             sh == Shape::Exact || sh == Shape::BsdfFlux || sh == Shape::MaskingT || sh == Shape::BsdfAvg) {
    // two-sided against an expected value (closed_form; a refracting material's bsdf_* kinds): the worst point
    std::string where;
    for (const char* k : {"cos_i", "cos_o", "cos_l", "side", "lobe", "eta"})
      if (auto it = w.params.find(k); it != w.params.end()) where += fmt::format(" {}={:.3g}", k, it->second);
    c.text = fmt::format("worst {:.4g} ± {:.1e} against {:.4g} (two-sided){}", w.estimate, w.stderr_, w.expected,
                         where.empty() ? "" : " at" + where);
  } else {
    double emax = -1;
    const PointResult* at = nullptr;
    double lo_cos = 2;
    for (size_t i : g.points) {
      const PointResult& p = rep.points[i];
      if (!(p.estimate <= emax)) emax = p.estimate, at = &p;
      const double co = fixed_cos(p);
      if (co == 1.0) c.e_normal = p.estimate;
      if (co < lo_cos) lo_cos = co, c.e_grazing = p.estimate, c.grazing_cos = co;
    }
    const char* dir = at ? fixed_name(*at) : "cos_o";
    c.text = fmt::format("max E {:.4f} at {}={:.3g} (<= 1)", emax, dir, at ? fixed_cos(*at) : 0.0);
    if (g.check == "furnace")
      c.text += fmt::format("; energy loss 1-E {:.4f} at normal {}, {:.4f} at {}={:.0e}", 1 - c.e_normal,
                            std::string(dir) == "cos_l" ? "incidence" : "view", 1 - c.e_grazing, dir, c.grazing_cos);
  }
  return c;
}

std::string material_params(const SceneMaterial& m) {
  if (m.gltf && m.factors.anisotropy_strength > 0.0) {
    const GltfChannelParams lobe = m.channels().front();
    return fmt::format(
        "gltf: baseColor ({:g}, {:g}, {:g}), metallic {:g}, roughness {:g}, anisotropyStrength {:g} "
        "(alpha_t {:g}, alpha_b {:g}), ior {:g}, specular {:g}, specularColor ({:g}, {:g}, {:g})",
        m.factors.base[0], m.factors.base[1], m.factors.base[2], m.factors.metallic, m.factors.roughness,
        m.factors.anisotropy_strength, lobe.alpha, lobe.alpha_b, m.factors.ior, m.factors.specular,
        m.factors.specular_color[0], m.factors.specular_color[1], m.factors.specular_color[2]);
  }
  if (m.gltf)
    return fmt::format(
        "{}: baseColor ({:g}, {:g}, {:g}), metallic {:g}, roughness {:g} (alpha {:g}), ior {:g}, "
        "specular {:g}, specularColor ({:g}, {:g}, {:g})",
        m.model(), m.factors.base[0], m.factors.base[1], m.factors.base[2], m.factors.metallic, m.factors.roughness, m.alpha,
        m.factors.ior, m.factors.specular, m.factors.specular_color[0], m.factors.specular_color[1],
        m.factors.specular_color[2]);
  std::string s = fmt::format("{}: D {}={:g}", m.model(), m.d->params[0].name, m.pd);
  if (!m.g->params.empty()) s += fmt::format(", G {}={:g}", m.g->params[0].name, m.pg);
  for (size_t i = 0; i < m.f->params.size(); ++i) s += fmt::format(", {}={:g}", m.f->params[i].name, i ? m.f1 : m.f0);
  if (m.kd > 0) s += fmt::format(", kd={:g}", m.kd);
  return s + fmt::format(" (alpha {:g})", m.alpha);
}

std::string range_text(const char* name, const ParamRange& r) {
  if (!r.varies()) return fmt::format("{} {:g}", name, r.hi);
  return fmt::format("{} [{:.4g}, {:.4g}] ({})", name, r.lo, r.hi, r.source);
}

// The ranges a glTF material was checked over, and at which points (issue 21).
std::string ranges_text(const SceneMaterial& m) {
  std::string s = "checked over " + range_text("roughness", m.roughness);
  if (m.roughness.varies()) {
    s += " at alpha";
    for (double a : m.alphas()) s += fmt::format(" {:.4g}", a);
  }
  s += "; " + range_text("metallic", m.metallic);
  for (size_t k = 0; k < 3; ++k)
    s += fmt::format("; {}", range_text(k == 0 ? "base r" : k == 1 ? "base g" : "base b", m.base[k]));
  if (m.specular.varies()) s += "; " + range_text("specular", m.specular);
  for (size_t k = 0; k < 3; ++k)
    if (m.specular_color[k].varies()) s += "; " + range_text("specularColor", m.specular_color[k]);
  if (m.anisotropy_strength.hi > 0) s += "; " + range_text("anisotropyStrength", m.anisotropy_strength);
  if (m.coat_checked) {
    s += "; " + range_text("clearcoat", m.clearcoat) + "; " + range_text("clearcoatRoughness", m.clearcoat_roughness);
    s += fmt::format(" ({} gltf_clearcoat points, {} gltf_clearcoat_aniso points)", m.coat_points().size(),
                     m.coat_aniso_points().size());
  }
  if (m.sheen_checked) {
    for (size_t k = 0; k < 3; ++k) s += "; " + range_text(fmt::format("sheenColor[{}]", k).c_str(), m.sheen_color[k]);
    s += "; " + range_text("sheenRoughness", m.sheen_roughness) +
         fmt::format(" ({} gltf_sheen points)", m.sheen_points().size());
  }
  if (m.thin_checked)
    s += "; " + range_text("transmission", m.transmission) +
         fmt::format(" ({} gltf_transmission points)", m.whole_points().size());
  return s + fmt::format(" ({} parameter points; the ends of every range, roughness and anisotropy also inside)",
                         m.channels().size());
}

// The account of one material: what is checked over which range, what is not and why.
std::vector<std::string> account_lines(const SceneMaterial& m) {
  std::vector<std::string> out;
  if (!m.not_checked.empty())
    out.push_back("NOT checked: " + m.not_checked);
  else if (m.gltf)
    out.push_back(ranges_text(m));
  for (auto& a : m.account) out.push_back(a);
  return out;
}

// Account lines that are a part of the material not checked: junit skipped testcases.
bool is_skip(const std::string& line) {
  return line.rfind("NOT checked", 0) == 0 || line.find("is NOT checked") != std::string::npos ||
         line.find("nothing to check") != std::string::npos;
}

// The worst verdict over a material's checks.
std::string material_verdict(const SceneRun& run, size_t mi) {
  if (!run.scene.materials[mi].not_checked.empty()) return "NOT CHECKED";
  bool fail = false, xpass = false, xfail = false;
  for (size_t gi : run.material_groups[mi]) {
    Verdict v = run.rep.groups[gi].verdict;
    fail |= v == Verdict::Fail;
    xpass |= v == Verdict::XPass;
    xfail |= v == Verdict::XFail;
  }
  return fail ? "FAIL" : xpass ? "XPASS" : xfail ? "xfail" : "pass";
}

std::string pct(uint64_t part, uint64_t whole) {
  return whole ? fmt::format("{:.2f} %", 100.0 * double(part) / double(whole)) : "-";
}

std::string time_text(const SceneRun& run) {
  if (!run.full_measured)
    return fmt::format(
        "time: this scene run {:.2f} s (measured: builds, integration, reference); the full catalog "
        "was not run (--compare-full runs it and measures the time saved)",
        run.seconds);
  return fmt::format(
      "time: this scene run {:.2f} s, the full catalog {:.2f} s (both measured the same way on this "
      "device: builds, integration, reference): saved {:.2f} s ({:.1f}x faster)",
      run.seconds, run.full_seconds, run.full_seconds - run.seconds,
      run.seconds > 0 ? run.full_seconds / run.seconds : 0.0);
}

// junit.xml: one skipped testcase per part of a material that is not checked, with the reason.
std::string with_skipped_testcases(std::string xml, const Scene& sc) {
  std::string cases;
  size_t skipped = 0;
  for (auto& m : sc.materials)
    for (auto& line : account_lines(m))
      if (is_skip(line)) {
        ++skipped;
        cases +=
            fmt::format("  <testcase classname=\"scene\" name=\"material {}\"><skipped message=\"{}\"/></testcase>\n",
                        xml_escape(m.name), xml_escape(line));
      }
  const size_t end = xml.rfind("</testsuite>");
  if (skipped == 0 || end == std::string::npos) return xml;
  xml.insert(end, cases);
  // the counts of <testsuites> and <testsuite> (report/junit.cpp writes both,
  // each with tests="N" ... skipped="S"): both grow by the skipped cases
  const size_t header_end = xml.find("<testcase");
  for (const char* attr : {"tests=\"", "skipped=\""})
    for (size_t at = xml.find(attr); at != std::string::npos && at < header_end; at = xml.find(attr, at + 1)) {
      const size_t from = at + std::char_traits<char>::length(attr), q = xml.find('"', from);
      xml.replace(from, q - from, std::to_string(std::stoul(xml.substr(from, q - from)) + skipped));
    }
  return xml;
}

}  // namespace

void print_scene_console(const SceneRun& run) {
  const Scene& sc = run.scene;
  fmt::print("\nscene {} ({}): {} material{} used ({} in the file)\n", sc.path, sc.format, sc.materials.size(),
             sc.materials.size() == 1 ? "" : "s", sc.materials_in_file);
  for (auto& w : sc.warnings) fmt::print("  warning: {}\n", w);
  for (size_t mi = 0; mi < sc.materials.size(); ++mi) {
    const SceneMaterial& m = sc.materials[mi];
    fmt::print("material '{}' [{}] {}: {}\n", m.name, m.origin, material_verdict(run, mi), material_params(m));
    for (auto& w : m.warnings) fmt::print("  warning: {}\n", w);
    for (auto& a : account_lines(m)) fmt::print("  account: {}\n", a);
    for (size_t gi : run.material_groups[mi]) {
      CheckLine c = check_line(run.rep, run.rep.groups[gi]);
      fmt::print("  {:<6} {:<15} {}\n", c.verdict, c.check, c.text);
      fmt::print("  {:<6} {:<15} set: {}\n", "", "", c.set);
      if (!c.reason.empty()) fmt::print("  {:<6} {:<15} reason: {}\n", "", "", c.reason);
    }
  }
  fmt::print("left out against the full catalog (same checks and scale):\n");
  fmt::print("  {:<15} {:>22} {:>24} {:>26}\n", "check", "models run/full", "integrals run/full",
             "samples run (share)");
  for (auto& lo : run.left_out)
    fmt::print("  {:<15} {:>22} {:>24} {:>26}\n", lo.check,
               fmt::format("{}/{}", lo.scene_combinations, lo.full_combinations),
               fmt::format("{}/{}", lo.scene_integrals, lo.full_integrals),
               fmt::format("{} ({})", lo.scene_samples, pct(lo.scene_samples, lo.full_samples)));
  fmt::print("  kernel builds: {} run, {} in a full run\n", run.scene_builds, run.full_builds);
  fmt::print("{}\n", time_text(run));
}

std::string scene_json(const SceneRun& run) {
  const Scene& sc = run.scene;
  json j;
  j["path"] = sc.path;
  j["format"] = sc.format;
  j["materials_in_file"] = sc.materials_in_file;
  j["warnings"] = sc.warnings;
  j["materials"] = json::array();
  for (size_t mi = 0; mi < sc.materials.size(); ++mi) {
    const SceneMaterial& m = sc.materials[mi];
    json mj{{"name", m.name},
            {"origin", m.origin},
            {"model", m.model()},
            {"alpha", m.alpha},
            {"verdict", material_verdict(run, mi)},
            {"parameters", material_params(m)},
            {"warnings", m.warnings},
            {"account", account_lines(m)},
            {"not_checked", m.not_checked}};
    if (m.gltf) {
      mj["factors"] = {{"baseColor", m.factors.base},      {"metallic", m.factors.metallic},
                       {"roughness", m.factors.roughness}, {"ior", m.factors.ior},
                       {"specular", m.factors.specular},   {"specularColor", m.factors.specular_color}};
      mj["channels_checked"] = m.channels().size();
    }
    mj["checks"] = json::array();
    for (size_t gi : run.material_groups[mi]) {
      CheckLine c = check_line(run.rep, run.rep.groups[gi]);
      json cj{{"check", c.check}, {"set", c.set}, {"verdict", c.verdict}, {"summary", c.text}, {"reason", c.reason}};
      if (c.check == "furnace") {
        cj["energy_loss_normal"] = 1 - c.e_normal;
        cj["energy_loss_grazing"] = 1 - c.e_grazing;
        cj["grazing_cos"] = c.grazing_cos;
      }
      mj["checks"].push_back(cj);
    }
    j["materials"].push_back(mj);
  }
  j["left_out"] = json::array();
  for (auto& lo : run.left_out)
    j["left_out"].push_back({{"check", lo.check},
                             {"models_run", lo.scene_combinations},
                             {"models_full", lo.full_combinations},
                             {"integrals_run", lo.scene_integrals},
                             {"integrals_full", lo.full_integrals},
                             {"integrals_skipped", lo.full_integrals - lo.scene_integrals},
                             {"samples_run", lo.scene_samples},
                             {"samples_full", lo.full_samples},
                             {"seconds_run", lo.scene_seconds},
                             {"seconds_full", lo.full_seconds}});
  j["kernel_builds"] = {{"run", run.scene_builds},
                        {"full", run.full_builds},
                        {"skipped", std::max(0, run.full_builds - run.scene_builds)}};
  j["seconds"] = {{"scene", run.seconds}, {"full_measured", run.full_measured}};
  if (run.full_measured) j["seconds"].update({{"full", run.full_seconds}, {"saved", run.full_seconds - run.seconds}});
  return j.dump();
}

// JUnit testcase names: the materials a group checks ("paint, car body"),
// not its parameter set.
static std::vector<std::string> scene_group_names(const SceneRun& run) {
  std::vector<std::string> names(run.rep.groups.size());
  for (size_t mi = 0; mi < run.material_groups.size(); ++mi)
    for (size_t gi : run.material_groups[mi])
      names[gi] += (names[gi].empty() ? "" : ", ") + run.scene.materials[mi].name;
  for (size_t gi = 0; gi < names.size(); ++gi)
    if (names[gi].empty()) names[gi] = run.rep.groups[gi].model;
  return names;
}

void write_scene_outputs(const SceneRun& run, const Runtime& rt, const SuiteOptions& opt, const std::string& dir) {
  auto files = suite_output_files(run.rep, rt, opt, dir);
  for (auto& [path, text] : files) {
    if (path == dir + "/junit.xml") {
      text = with_skipped_testcases(suite_junit(run.rep, opt, scene_group_names(run)), run.scene);
    } else if (path == dir + "/results.json") {
      json j = json::parse(text);
      j["scene"] = json::parse(scene_json(run));
      text = j.dump();
    } else if (path == dir + "/report.md") {
      const Scene& sc = run.scene;
      std::string md = fmt::format("\n## Scene {} ({})\n\n{} materials used ({} in the file).\n\n", sc.path, sc.format,
                                   sc.materials.size(), sc.materials_in_file);
      for (auto& w : sc.warnings) md += fmt::format("- warning: {}\n", w);
      for (size_t mi = 0; mi < sc.materials.size(); ++mi) {
        const SceneMaterial& m = sc.materials[mi];
        md +=
            fmt::format("### {} — {}\n\n{} ({})\n\n", m.name, material_verdict(run, mi), material_params(m), m.origin);
        for (auto& w : m.warnings) md += fmt::format("- warning: {}\n", w);
        for (auto& a : account_lines(m)) md += fmt::format("- account: {}\n", a);
        if (!m.not_checked.empty()) {
          md += "\n";
          continue;
        }
        md += "\n| verdict | check | result | parameter set | expected failure because |\n|---|---|---|---|---|\n";
        for (size_t gi : run.material_groups[mi]) {
          CheckLine c = check_line(run.rep, run.rep.groups[gi]);
          md += fmt::format("| {} | {} | {} | {} | {} |\n", c.verdict, c.check, c.text, c.set, c.reason);
        }
        md += "\n";
      }
      md +=
          "### Left out against the full catalog\n\n| check | models run/full | integrals run/full | samples run/full "
          "|\n"
          "|---|---:|---:|---:|\n";
      for (auto& lo : run.left_out)
        md += fmt::format("| {} | {}/{} | {}/{} | {}/{} |\n", lo.check, lo.scene_combinations, lo.full_combinations,
                          lo.scene_integrals, lo.full_integrals, lo.scene_samples, lo.full_samples);
      md += fmt::format("\nKernel builds: {} run, {} in a full run. {}.\n", run.scene_builds, run.full_builds,
                        time_text(run));
      text += md;
    }
  }
  write_files_atomically(files);
}

}  // namespace mfv
