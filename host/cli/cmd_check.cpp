// mfv check --brdf FILE.cl: the conformance checks on a renderer's own BRDF
// code (contract in docs/cli/check.md); same verdicts, reports and exit
// codes as mfv run, so it drops into a CI job.
#include "cli/report_errors.hpp"
#include "cli/shared_options.hpp"
#include "report/suite_report.hpp"
#include "user/init_template.hpp"
#include "user/time_limit.hpp"
#include "user/user_check.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <cmath>

namespace mfv::cli {

// Seconds. Without --timeout, no limit on the whole check: each step has its
// own, derived from a calibration launch (user/user_check.hpp,
// kMinStepSeconds), which stops a BRDF that never returns within a minute.
// The maximum keeps an explicit limit a finite wait (a week).
constexpr double kMaxCheckTimeout = 7 * 86400, kDefaultCheckTimeout = kMaxCheckTimeout;

namespace {

// mfv check: its values, bound to its options, and its work.
struct CheckCommand : SharedValues {
  UserCheckOptions opt;
  std::string path;
  std::string as;
  UserParamArgs params;
  std::vector<std::string> map;
  std::vector<std::string> channels;
  std::string init;
  double timeout = kDefaultCheckTimeout;

  void add_options(CLI::App* cmd) {
    cmd->description(
        "check your own BRDF code (an OpenCL C file) with the suite's checks; exit 0 when every check passes, 1 when "
        "one fails, 2 on bad input");
    cmd->add_option("--brdf", path,
                    "file defining float3 brdf(float3 wi, float3 wo, const float* params) (optional D and G1; for "
                    "transmission btdf, or one bsdf for both hemispheres, with an eta parameter), in OpenCL C, GLSL or "
                    "HLSL (--dialect)");
    cmd->add_option("--dialect", params.dialect,
                    "glsl, hlsl or opencl (default: from the extension: .glsl .frag .fs glsl; .hlsl .fx hlsl; else "
                    "opencl)");
    cmd->add_option("--define", params.defines, "NAME=VALUE (or NAME) defined for the file, as -D");
    cmd->add_option("--include", params.includes,
                    "FILE read before --brdf, in the same dialect (an engine's shading file the adapter calls)");
    cmd->add_option("--init", init, "glsl or hlsl: print a commented adapter template to start from, and exit");
    cmd->add_option("--param", params.params,
                    "NAME=VALUE fixes a parameter, NAME=LO:HI narrows (or declares) its range");
    cmd->add_option("--roughness", params.roughness,
                    "the parameter that sets the estimators' width: NAME (alpha) or NAME^2 (perceptual roughness)");
    cmd->add_option("--eta", params.eta,
                    "the parameter that is a btdf's or bsdf's relative index eta = eta_below / eta_above: NAME");
    cmd->add_option("--as", as,
                    "claim the code implements a catalog model D/G/F (e.g. ggx/smith_ggx_correlated/schlick): adds "
                    "pointwise agreement with the double reference");
    cmd->add_option("--map", map,
                    "model parameter from yours: NAME=PARAM, NAME=PARAM^2 or NAME=NUMBER (e.g. alpha=r^2,f0=f0)");
    cmd->add_option("--check", opt.checks,
                    "only these checks (d_norm, masking, furnace, energy, reciprocity, finite, agree; with a btdf or "
                    "bsdf: bsdf_furnace, transmission_masking, bsdf_avg_reciprocity, bsdf_reciprocity)");
    cmd->add_option("--channel", channels, "only these RGB channels (r, g, b; default all three)");
    SharedOptions(cmd, *this)
        .seed(opt.seed)
        .budget(opt.scale, opt.family_alpha)
        .out("results.json, report.md and junit.xml");
    cmd->add_option("--timeout", timeout,
                    "stop the whole check after this many seconds, exit 2, in place of the per-step limits (default: "
                    "none; each step is stopped at 100x a calibration launch of the code, at least 30 s: user code may "
                    "never return, and an OpenCL kernel cannot be interrupted)");
  }

  int run(const Globals& g) {
    if (!init.empty()) {
      fmt::print("{}", init_template(init));
      return 0;
    }
    if (path.empty()) throw Error("mfv check needs --brdf FILE (or --init glsl|hlsl for a template)");
    if (!(timeout > 0 && timeout <= kMaxCheckTimeout))
      throw Error(fmt::format("--timeout {} must be in (0, {:g}] seconds", timeout, kMaxCheckTimeout));
    apply_samples(opt.scale);
    validate_scale(opt.scale);
    if (!channels.empty()) {
      opt.channels.clear();
      for (auto& c : channels) {
        if (c != "r" && c != "g" && c != "b") throw Error(fmt::format("--channel {}: name r, g or b", c));
        opt.channels.push_back(c == "r" ? 0 : c == "g" ? 1 : 2);
      }
    }
    if (!map.empty() && as.empty()) throw Error("--map needs --as D/G/F (the model the mapping is for)");
    UserBrdf u = load_user_brdf(path, params);
    std::optional<Claim> claim;
    if (!as.empty()) claim = parse_claim(as, map, u);
    prepare_out();
    // in a child process, killed after --timeout (user/time_limit.hpp); a
    // --timeout the user set replaces the per-step limits (on a slow device,
    // such as a simulator, a step may rightly take longer than 30 s)
    const bool step_limits = !(timeout < kMaxCheckTimeout);
    return run_with_time_limit(timeout, "mfv check --brdf " + path, [&] {
      return run_reporting_errors([&] {
        Runtime rt(g.device, g.kernel_dir);
        SuiteReport rep = run_user_check(rt, u, claim, opt);
        SuiteOptions sopt = suite_options_of(opt);
        print_suite_console(rep, rt, sopt);
        if (!out_dir.empty()) write_suite_outputs(rep, rt, sopt, out_dir);
        return rep.gate_ok() ? 0 : 1;
      });
    }, step_limits);
  }
};

}  // namespace

void add_check(CLI::App& app, Globals& g, int& rc) { add_command<CheckCommand>(app, g, rc, "check"); }

}  // namespace mfv::cli
