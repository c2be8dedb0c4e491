// mfv energy: energy-loss tables and Kulla-Conty compensation data.
#include "checks/energy.hpp"
#include "cli/commands.hpp"
#include "report/energy_report.hpp"
#include "scene/scene_filters.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <fstream>
#include <map>
#include <memory>
#include <sstream>

namespace mfv::cli {
namespace {

// "out/energy.json, report.md, csv/ (3 files)": what energy_outputs wrote, never a file it did not (issue 21).
std::string written_list(const std::vector<std::pair<std::string, std::string>>& files, const std::string& dir) {
  std::string top;
  std::map<std::string, size_t> folders;
  for (auto& [path, text] : files) {
    const std::string rel = path.substr(dir.size() + 1);
    const size_t slash = rel.find('/');
    if (slash == std::string::npos)
      top += (top.empty() ? dir + "/" : ", ") + rel;
    else
      ++folders[rel.substr(0, slash + 1)];
  }
  for (auto& [f, n] : folders) top += fmt::format(", {} ({} file{})", f, n, n == 1 ? "" : "s");
  return top;
}

}  // namespace

namespace {

// mfv energy's command-line values, bound to its options (Globals::command_values keeps them).
struct EnergyCommandOptions {
  EnergyOptions opt;
  std::string out_dir;
  std::string baseline;
  std::string grid;
  double alpha_fw = 1e-3;
  std::string scene_path;
};

}  // namespace

void add_energy(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand("energy",
                                 "energy-loss tables E(mu, alpha), split-sum A/B and E_avg(alpha) for "
                                 "D x G (F = none), and E(mu), E_avg of every whole model at its catalog "
                                 "cases: CSV, JSON, C header, report with plots");
  auto values = std::make_shared<EnergyCommandOptions>();  // the command's values
  g.command_values.push_back(values);
  cmd->add_option("--models", values->opt.models,
                  "only D/G combinations (d/g) and whole-model cases (model[case]) whose name "
                  "contains one of these, e.g. ggx/ or '[' for the whole models "
                  "(default: every D x G and every whole-model case)");
  cmd->add_option("--grid", values->grid,
                  "MUxALPHA cells, e.g. 32x32 (default): mu = (m+1/2)/MU, alpha log-spaced 1e-3..1");
  cmd->add_option("--target", values->opt.target,
                  "standard error per cell to reach (default 1e-4); cells above it get "
                  "more points, up to the cap");
  cmd->add_option("--seed", values->opt.seed, "Philox key");
  cmd->add_option("--replicates", values->opt.replicates, "independent randomizations per value (default 8)");
  cmd->add_option("--max-points", values->opt.max_points, "cap on points per replicate per value (default 16384)");
  cmd->add_option("--out", values->out_dir, "write energy.json, report.md, kulla_conty.h, csv/ and plots/ here");
  cmd->add_option("--baseline", values->baseline,
                  "earlier energy.json: exit 1 if a value moved beyond its combined "
                  "standard errors (Bonferroni over all values)");
  cmd->add_option("--alpha-fw", values->alpha_fw,
                  "family-wise false-alarm rate of the baseline comparison (default 1e-3)")
      ->check(CLI::Range(1e-300, 0.5));
  cmd->add_option("--scene", values->scene_path,
                  "only what the materials of this scene use (.gltf, .glb, material .json): "
                  "the glTF model at each material's parameters, the D x G tables of the "
                  "others; prints each material's energy loss");
  cmd->callback([&g, &rc, values] {
    Scene scene;
    if (!values->scene_path.empty()) {
      if (!values->opt.models.empty())
        throw Error("--models and --scene cannot be combined: the scene chooses the models");
      scene = load_scene(values->scene_path);
      scene_energy_options(scene, values->opt);
    }
    if (!values->grid.empty()) {
      int m = 0, a = 0;
      char x = 0, extra = 0;
      if (std::sscanf(values->grid.c_str(), "%d%c%d%c", &m, &x, &a, &extra) != 3 || (x != 'x' && x != 'X'))
        throw Error(fmt::format("--grid '{}': expected MUxALPHA, e.g. 32x32", values->grid));
      values->opt.n_mu = m;
      values->opt.n_alpha = a;
    }
    validate_energy_options(values->opt);
    const std::string base_text = values->baseline.empty() ? "" : read_text_file(values->baseline, "--baseline");
    if (!values->out_dir.empty()) prepare_output_dir(values->out_dir);
    Runtime rt(g.device, g.kernel_dir);
    EnergyReport rep = run_energy(rt, values->opt);
    print_energy_console(rep);
    if (!values->scene_path.empty()) print_scene_energy(scene, rep);
    BaselineDiff diff;
    if (!values->baseline.empty()) {
      diff = compare_energy_baseline(rep, base_text, values->alpha_fw);
      print_baseline_console(diff);
    }
    if (!values->out_dir.empty()) {
      const auto files = energy_outputs(rep, rt, values->out_dir, values->baseline.empty() ? nullptr : &diff);
      write_files_atomically(files);
      fmt::print("wrote {}\n", written_list(files, values->out_dir));
    }
    rc = (rep.reference_worst <= rep.reference_bound && diff.moved.empty()) ? 0 : 1;
  });
}

}  // namespace mfv::cli
