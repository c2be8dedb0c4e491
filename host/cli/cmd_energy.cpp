// mfv energy: energy-loss tables and Kulla-Conty compensation data.
#include "checks/energy.hpp"
#include "cli/shared_options.hpp"
#include "report/energy_report.hpp"
#include "scene/scene_filters.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

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

// mfv energy: its values, bound to its options, and its work.
struct EnergyCommand : SharedValues {
  EnergyOptions opt;
  std::string grid;
  double alpha_fw = 1e-3;

  void add_options(CLI::App* cmd) {
    cmd->description(
        "energy-loss tables E(mu, alpha), split-sum A/B and E_avg(alpha) for D x G (F = none), and E(mu), E_avg of "
        "every whole model at its catalog cases: CSV, JSON, C header, report with plots");
    cmd->add_option("--models", opt.models,
                    "only D/G combinations (d/g) and whole-model cases (model[case]) whose name contains one of "
                    "these, e.g. ggx/ or '[' for the whole models (default: every D x G and every whole-model case)");
    cmd->add_option("--grid", grid, "MUxALPHA cells, e.g. 32x32 (default): mu = (m+1/2)/MU, alpha log-spaced 1e-3..1");
    cmd->add_option("--target", opt.target,
                    "standard error per cell to reach (default 1e-4); cells above it get more points, up to the cap");
    cmd->add_option("--replicates", opt.replicates, "independent randomizations per value (default 8)");
    cmd->add_option("--max-points", opt.max_points, "cap on points per replicate per value (default 16384)");
    SharedOptions(cmd, *this)
        .seed(opt.seed)
        .out("energy.json, report.md, kulla_conty.h, csv/ and plots/")
        .baseline(
            "earlier energy.json: exit 1 if a value moved beyond its combined standard errors (Bonferroni over all "
            "values)",
            "--alpha-fw", alpha_fw)
        .scene(
            "only what the materials of this scene use (.gltf, .glb, material .json): the glTF model at each "
            "material's parameters, the D x G tables of the others; prints each material's energy loss");
  }

  int run(const Globals& g) {
    const Scene scene = load_scene_instead_of(!opt.models.empty(), "--models", "models");
    if (!scene_path.empty()) scene_energy_options(scene, opt);
    if (!grid.empty()) std::tie(opt.n_mu, opt.n_alpha) = parse_cells("--grid", grid, "MUxALPHA", "32x32");
    validate_energy_options(opt);
    const std::string base_text = baseline.empty() ? "" : read_text_file(baseline, "--baseline");
    prepare_out();
    Runtime rt(g.device, g.kernel_dir);
    EnergyReport rep = run_energy(rt, opt);
    print_energy_console(rep);
    if (!scene_path.empty()) print_scene_energy(scene, rep);
    BaselineDiff diff;
    if (!baseline.empty()) {
      diff = compare_energy_baseline(rep, base_text, alpha_fw);
      print_baseline_console(diff);
    }
    if (!out_dir.empty()) {
      const auto files = energy_outputs(rep, rt, out_dir, baseline.empty() ? nullptr : &diff);
      write_files_atomically(files);
      fmt::print("wrote {}\n", written_list(files, out_dir));
    }
    return (rep.reference_worst <= rep.reference_bound && diff.moved.empty()) ? 0 : 1;
  }
};

}  // namespace

void add_energy(CLI::App& app, Globals& g, int& rc) { add_command<EnergyCommand>(app, g, rc, "energy"); }

}  // namespace mfv::cli
