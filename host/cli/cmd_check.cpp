// mfv check --brdf FILE.cl: the conformance checks on a renderer's own BRDF
// code (contract in docs/cli/check.md); same verdicts, reports and exit
// codes as mfv run, so it drops into a CI job.
#include "cli/commands.hpp"
#include "cli/report_errors.hpp"
#include "report/suite_report.hpp"
#include "user/time_limit.hpp"
#include "user/user_check.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <cmath>
#include <memory>

namespace mfv::cli {

// Seconds. The default check takes about a minute on 2 CPU cores with PoCL
// (README "mfv check"); ten times that is a hang, not a slow device. The
// maximum keeps the limit a finite wait (a week).
constexpr double kDefaultCheckTimeout = 600, kMaxCheckTimeout = 7 * 86400;

namespace {

// mfv check's command-line values, bound to its options (Globals::command_values keeps them).
struct CheckCommandOptions {
  std::string path;
  std::string as;
  UserParamArgs params;
  std::vector<std::string> map;
  std::vector<std::string> channels;
  UserCheckOptions opt;
  std::string out_dir;
  int64_t samples = 0;
  double timeout = kDefaultCheckTimeout;
};

}  // namespace

void add_check(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand("check",
                                 "check your own BRDF code (an OpenCL C file) with the suite's checks; exit 0 "
                                 "when every check passes, 1 when one fails, 2 on bad input");
  auto values = std::make_shared<CheckCommandOptions>();  // the command's values
  g.command_values.push_back(values);
  cmd->add_option("--brdf", values->path,
                  "OpenCL C file defining float3 brdf(float3 wi, float3 wo, const float* params) "
                  "(optional D and G1)")
      ->required();
  cmd->add_option("--param", values->params.params,
                  "NAME=VALUE fixes a parameter, NAME=LO:HI narrows (or declares) its range");
  cmd->add_option("--roughness", values->params.roughness,
                  "the parameter that sets the estimators' width: NAME (alpha) or NAME^2 (perceptual roughness)");
  cmd->add_option("--as", values->as,
                  "claim the code implements a catalog model D/G/F (e.g. ggx/smith_ggx_correlated/schlick): "
                  "adds pointwise agreement with the double reference");
  cmd->add_option("--map", values->map,
                  "model parameter from yours: NAME=PARAM, NAME=PARAM^2 or NAME=NUMBER (e.g. alpha=r^2,f0=f0)");
  cmd->add_option("--check", values->opt.checks,
                  "only these checks (d_norm, masking, furnace, energy, reciprocity, finite, agree)");
  cmd->add_option("--channel", values->channels, "only these RGB channels (r, g, b; default all three)");
  cmd->add_option("--seed", values->opt.seed, "Philox key");
  cmd->add_option("--scale", values->opt.scale, "multiply every check's samples");
  auto* samples_opt =
      cmd->add_option("--samples", values->samples, "samples per masking/furnace integral (default 4096)");
  cmd->add_option("--alpha-fw", values->opt.family_alpha, "family-wise false-alarm rate for the whole run")
      ->check(CLI::Range(1e-300, 0.5));
  cmd->add_option("--out", values->out_dir, "write results.json, report.md and junit.xml here");
  cmd->add_option("--timeout", values->timeout,
                  "stop the check after this many seconds, exit 2 (default 600): user code "
                  "may never return, and an OpenCL kernel cannot be interrupted");
  cmd->callback([&g, &rc, samples_opt, values] {
    if (!(values->timeout > 0 && values->timeout <= kMaxCheckTimeout))
      throw Error(fmt::format("--timeout {} must be in (0, {:g}] seconds", values->timeout, kMaxCheckTimeout));
    if (samples_opt->count() > 0) {
      if (values->samples <= 0) throw Error(fmt::format("--samples must be a positive count, not {}", values->samples));
      values->opt.scale = double(values->samples) / double(kSuiteBaseSamples);
    }
    validate_scale(values->opt.scale);
    if (!values->channels.empty()) {
      values->opt.channels.clear();
      for (auto& c : values->channels) {
        if (c != "r" && c != "g" && c != "b") throw Error(fmt::format("--channel {}: name r, g or b", c));
        values->opt.channels.push_back(c == "r" ? 0 : c == "g" ? 1 : 2);
      }
    }
    if (!values->map.empty() && values->as.empty())
      throw Error("--map needs --as D/G/F (the model the mapping is for)");
    UserBrdf u = load_user_brdf(values->path, values->params);
    std::optional<Claim> claim;
    if (!values->as.empty()) claim = parse_claim(values->as, values->map, u);
    if (!values->out_dir.empty()) prepare_output_dir(values->out_dir);
    // in a child process, killed after --timeout (user/time_limit.hpp)
    rc = run_with_time_limit(values->timeout, "mfv check --brdf " + values->path, [&] {
      return run_reporting_errors([&] {
        Runtime rt(g.device, g.kernel_dir);
        SuiteReport rep = run_user_check(rt, u, claim, values->opt);
        SuiteOptions sopt = suite_options_of(values->opt);
        print_suite_console(rep, rt, sopt);
        if (!values->out_dir.empty()) write_suite_outputs(rep, rt, sopt, values->out_dir);
        return rep.gate_ok() ? 0 : 1;
      });
    });
  });
}

}  // namespace mfv::cli
