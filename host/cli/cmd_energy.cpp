// mfv energy: energy-loss tables and Kulla-Conty compensation data.
#include "checks/energy.hpp"
#include "checks/energy_layouts.hpp"
#include "cli/run_shard.hpp"
#include "cli/shared_options.hpp"
#include "checks/energy_compare.hpp"
#include "report/energy_layout_out.hpp"
#include "report/energy_report.hpp"
#include "report/energy_shard_file.hpp"
#include "runtime/provenance.hpp"
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
  std::string grid, mu, alpha, roughness = "alpha", layout, compare;
  CLI::Option* target_opt = nullptr;
  std::vector<std::string> at;
  double alpha_fw = 1e-3;

  void add_options(CLI::App* cmd) {
    cmd->description(
        "energy-loss tables E(mu, alpha), split-sum A/B and E_avg(alpha) for D x G (F = none), and E(mu), E_avg of "
        "every whole model at its catalog cases: CSV, JSON, C header, report with plots");
    cmd->add_option("--models", opt.models,
                    "only D/G combinations (d/g) and whole-model cases (model[case]) whose name contains one of "
                    "these, e.g. ggx/ or '[' for the whole models (default: every D x G and every whole-model case)");
    cmd->add_option("--grid", grid, "MUxALPHA cells, e.g. 32x32 (default): mu = (m+1/2)/MU, alpha log-spaced 1e-3..1");
    cmd->add_option("--mu", mu,
                    "view cosines, exactly these in this order: a list 0.1,0.5,1 or lin:A:B:N, log:A:B:N, centers:N ((i+1/2)/N), "
                    "edges:N (i/(N-1)); with --alpha, in place of --grid");
    cmd->add_option("--alpha", alpha,
                    "widths, as --mu (read as --roughness says); alpha = 0 (a mirror) is evaluated at the D's "
                    "smallest declared width");
    cmd->add_option("--roughness", roughness,
                    "how --alpha and --at read: alpha (the width, default) or r2 (perceptual roughness r, alpha = r^2)");
    cmd->add_option("--at", at, "one point MU,ALPHA (repeatable): E, A, B and E_avg there, nothing else");
    cmd->add_option("--layout", layout,
                    "an engine's table layout, NAME or NAME:N (default N = 32): kulla-conty, split-sum, sheen, glass, "
                    "glass-enter, glass-leave (docs/energy-layouts.md); sets the axes and, without --models, the D/G "
                    "(glass: the BSDF)");
    cmd->add_flag("--fp64", opt.fp64,
                  "the energy kernels in double (needs cl_khr_fp64; PoCL has it): no float32 rounding in the values");
    cmd->add_option("--compare", compare,
                    "a team's table (.csv, C/C++ array file, .png, .exr) in --layout's layout: each cell against mfv's in "
                    "units of total uncertainty, Holm over the cells; exit 0 pass, 1 a cell deviates, 2 bad input "
                    "(default --target 1e-5)");
    target_opt = cmd->add_option("--target", opt.target,
                    "standard error per cell to reach (default 1e-4); cells above it get more points, up to the cap");
    cmd->add_option("--replicates", opt.replicates, "independent randomizations per value (default 32)");
    cmd->add_option("--max-points", opt.max_points, "cap on points per replicate per value (default 16384)");
    SharedOptions(cmd, *this)
        .seed(opt.seed)
        .out("energy.json, report.md, kulla_conty.h, csv/ and plots/")
        .baseline(
            "earlier energy.json: exit 1 if a value moved beyond its combined standard errors (Bonferroni over all "
            "values); --alpha-fw is also --compare's family-wise rate",
            "--alpha-fw", alpha_fw)
        .scene(
            "only what the materials of this scene use (.gltf, .glb, material .json): the glTF model at each "
            "material's parameters, the D x G tables of the others; prints each material's energy loss")
        .shard("the table's cells", "energy_shard.json", "mfv energy --merge", "values, integrating nothing");
  }

  // --mu/--alpha, --at or --layout: one way of giving the cells, each without --grid.
  void set_axes() {
    const int ways = int(!mu.empty() || !alpha.empty()) + int(!at.empty()) + int(!layout.empty()) + int(!grid.empty());
    if (ways > 1) throw Error("give the cells one way: --grid, --mu with --alpha, --at, or --layout");
    const RoughnessAxis param = parse_roughness_axis(roughness);
    if (!layout.empty()) {
      if (roughness != "alpha") throw Error("--layout sets the roughness parametrization; leave out --roughness");
      apply_energy_layout(opt, parse_energy_layout(layout));
    } else if (!at.empty()) {
      std::vector<double> m, w;
      for (auto& p : at) {
        auto [pm, pw] = parse_energy_point(p);
        m.push_back(pm);
        w.push_back(pw);
      }
      set_energy_axes(opt, m, w, param, true);
    } else if (!mu.empty() || !alpha.empty()) {
      if (mu.empty() || alpha.empty()) throw Error("--mu and --alpha go together");
      set_energy_axes(opt, parse_energy_axis("--mu", mu), parse_energy_axis("--alpha", alpha), param, false);
    } else if (roughness != "alpha") {
      throw Error("--roughness r2 reads --alpha or --at values; give one of them");
    }
  }

  // mfv energy --shard K/N: the shard's units into out_dir/energy_shard.json, no verdict.
  int energy_shard(const Globals& g, const ShardSpec& s) {
    if (!compare.empty() || !baseline.empty())
      throw Error("--compare and --baseline apply to the merged run (mfv energy --merge), not to a shard");
    const EnergyPlanSummary plan = energy_plan_summary(opt);
    const auto run = [&](Runtime& rt, std::pair<size_t, size_t> units) {
      EnergyPart part;
      std::tie(part.lo, part.hi) = units;
      if (part.hi > part.lo) run_energy(rt, opt, &part);
      fmt::print("device: {}; {} samples, {:.1f} s\n", rt.device().name, part.samples, part.seconds);
      return energy_shard_json(part, opt, s, plan, rt.device().name, provenance_json());
    };
    return run_unit_shard(g, energy_unit_shard(plan, opt.seed), s, out_dir, run);
  }

  int run(const Globals& g) {
    const Scene scene = load_scene_instead_of(!opt.models.empty(), "--models", "models");
    if (!scene_path.empty()) scene_energy_options(scene, opt);
    if (!grid.empty()) std::tie(opt.n_mu, opt.n_alpha) = parse_cells("--grid", grid, "MUxALPHA", "32x32");
    set_axes();
    const LayoutChoice lay = layout.empty() ? LayoutChoice{} : parse_energy_layout(layout);
    if (!compare.empty() && lay.layout == nullptr) throw Error("--compare needs --layout NAME[:N] (its axes and order)");
    if (!compare.empty() && target_opt->count() == 0) opt.target = 1e-5;
    validate_energy_options(opt);
    // their table first: bad input stops before any work, never after a partial verdict
    const std::vector<TheirTable> theirs =
        compare.empty() ? std::vector<TheirTable>{}
                        : read_their_table(compare, *lay.layout, opt.mu_axis, opt.alpha_axis, opt.roughness, opt.eta);
    const std::string base_text = baseline.empty() ? "" : read_text_file(baseline, "--baseline");
    if (std::optional<ShardSpec> s = shard_to_run("energy_shard.json", "mfv energy --merge")) return energy_shard(g, *s);
    // every shard checked before any output
    const EnergyShards shards = merge.empty() ? EnergyShards{} : read_energy_shards(merge, opt);
    prepare_out();
    Runtime rt(g.device, g.kernel_dir);
    for (auto& line : shards.lines) fmt::print("{}\n", line);
    EnergyReport rep = merge.empty() ? run_energy(rt, opt) : merge_energy(opt, shards.device, shards.parts);
    rep.shards = shards.lines;
    if (!compare.empty() && rep.tables.size() != 1)
      throw Error(fmt::format("--compare: --models selects {} tables; name one (e.g. ggx/smith_ggx_correlated)",
                              rep.tables.size()));
    print_energy_console(rep);
    CompareResult cmp;
    if (!compare.empty()) {
      cmp = compare_their_table(rep, theirs, alpha_fw);
      print_compare_console(cmp);
    }
    if (!scene_path.empty()) print_scene_energy(scene, rep);
    BaselineDiff diff;
    if (!baseline.empty()) {
      diff = compare_energy_baseline(rep, base_text, alpha_fw);
      print_baseline_console(diff);
    }
    if (!out_dir.empty()) {
      auto files = energy_outputs(rep, rt, out_dir, baseline.empty() ? nullptr : &diff);
      if (lay.layout != nullptr)
        for (auto& f : energy_layout_files(rep, *lay.layout, out_dir)) files.push_back(f);
      if (!compare.empty())
        for (auto& f : compare_files(cmp, rep, out_dir)) files.push_back(f);
      write_files_atomically(files);
      fmt::print("wrote {}\n", written_list(files, out_dir));
    }
    return (rep.reference_worst <= rep.reference_bound && diff.moved.empty() && cmp.pass()) ? 0 : 1;
  }
};

}  // namespace

void add_energy(CLI::App& app, Globals& g, int& rc) { add_command<EnergyCommand>(app, g, rc, "energy"); }

}  // namespace mfv::cli
