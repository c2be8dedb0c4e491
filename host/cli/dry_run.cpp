// mfv run --dry-run: the plan's size and its integration time on this device,
// estimated from a short calibration launch of every plan (docs/scale.md).
#include "checks/profile.hpp"
#include "cli/run_shard.hpp"
#include "runtime/opencl.hpp"
#include "util/progress.hpp"

#include <fmt/format.h>

#include <chrono>

namespace mfv::cli {

namespace {

// Seconds of integration per plan (run_suite_plans' rows: one per non-empty
// plan, reciprocity last), by plan index.
std::vector<double> plan_seconds(const SuitePlans& sp, const SuiteReport& rep) {
  std::vector<double> out(sp.plans.size() + 1, 0.0);
  size_t row = 0;
  for (size_t i = 0; i <= sp.plans.size(); ++i) {
    const Plan& p = i < sp.plans.size() ? sp.plans[i] : sp.reciprocity;
    if (!p.specs.empty() && row < rep.stats.size()) out[i] = rep.stats[row++].seconds;
  }
  return out;
}

}  // namespace

int dry_run(const Globals& g, const SuiteOptions& opt, const std::optional<ShardSpec>& shard) {
  SuitePlans sp = make_suite_plans(opt);
  const size_t whole = plan_integrals(sp);
  if (shard) cut_to_shard(sp, opt, *shard);
  uint64_t samples = 0;
  for (auto& p : sp.plans) samples += p.specs.size() * integral_cost(p, opt.scale);
  samples += sp.reciprocity.specs.size() * integral_cost(sp.reciprocity, opt.scale);
  // Calibration: kCalibration integrals of every plan, run twice: the first
  // launch of a kernel compiles it (PoCL), the second pass is timed.
  constexpr size_t kCalibration = 256;
  SuiteOptions quiet = opt;
  quiet.reference_samples = 0;
  Runtime rt(g.device, g.kernel_dir);
  const auto t0 = std::chrono::steady_clock::now();
  SuitePlans warm = sample_plans(sp, kCalibration), timed = warm;
  SuiteReport warm_rep, rep;
  if (plan_integrals(warm) > 0) {
    progress::Task task("calibration", 0);
    run_suite_plans(rt, warm, quiet, warm_rep);
    run_suite_plans(rt, timed, quiet, rep);
  }
  const double calib = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::vector<double> secs = plan_seconds(timed, rep);
  double estimate = 0;
  for (size_t i = 0; i <= sp.plans.size(); ++i) {
    const Plan &p = i < sp.plans.size() ? sp.plans[i] : sp.reciprocity,
               &q = i < sp.plans.size() ? timed.plans[i] : timed.reciprocity;
    if (!q.specs.empty()) estimate += secs[i] * double(p.specs.size()) / double(q.specs.size());
  }
  fmt::print("{}{} integrals, {} samples, estimated time on this device: {:.0f} s of integration\n",
             shard ? fmt::format("shard {}/{}: ", shard->index + 1, shard->count) : "", plan_integrals(sp), samples,
             estimate);
  fmt::print(
      "  ({} integrals in the whole run; calibrated on up to {} integrals per plan in {:.1f} s on {}, kernel builds "
      "{:.2f} s; the estimate leaves out kernel builds, the reference comparison, judging and writing)\n",
      whole, kCalibration, calib, rt.device().name, warm_rep.build_seconds + rep.build_seconds);
  return 0;
}

}  // namespace mfv::cli
