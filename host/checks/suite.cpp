#include "checks/suite.hpp"

#include "catalog/roughness.hpp"
#include "checks/device_share.hpp"
#include "checks/energy.hpp"
#include "checks/furnace_truth.hpp"
#include "checks/integrate.hpp"
#include "checks/reference_compare.hpp"
#include "checks/streams.hpp"
#include "reference/estimators.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/specialize.hpp"
#include "stats/normal.hpp"
#include "stats/verdict.hpp"
#include "util/error.hpp"
#include "util/progress.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <limits>
#include <optional>
#include <thread>

namespace mfv {

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::Pass: return "pass";
    case Verdict::Fail: return "FAIL";
    case Verdict::XFail: return "xfail";
    case Verdict::XPass: return "XPASS";
    case Verdict::Inconclusive: return "INCONCLUSIVE";
  }
  return "?";
}

bool SuiteReport::reference_ok() const { return reference_worst <= reference_bound; }

bool SuiteReport::gate_ok() const {
  if (!reference_ok()) return false;
  for (auto& g : groups)
    if (g.verdict == Verdict::Fail || g.verdict == Verdict::XPass || g.verdict == Verdict::Inconclusive) return false;
  return true;
}

std::vector<size_t> reference_subset(const Plan& plan, uint32_t every) {
  std::vector<size_t> which;
  std::map<std::string, uint32_t> seen;  // points so far per model
  const CheckKind* kind = find_check_kind(plan.check);
  const bool all = kind && shape_of(*kind) == Shape::DNorm;
  for (size_t i = 0; i < plan.specs.size(); ++i) {
    const PointResult& p = plan.points[i];
    uint32_t& k = seen[model_name(p)];
    if (!p.model.empty() || all || k % std::max<uint32_t>(1, every) == 0) which.push_back(i);
    ++k;
  }
  return which;
}

namespace {

std::string params_text(const PointResult& p) {
  std::string ps;
  for (auto& [k, v] : p.params) ps += fmt::format(" {}={:g}", k, v);
  return ps;
}

// Without fp64: the float kernel against the reference, |k - r| / max(sum |r|, n)
// under the fixed reference_bound (SuiteReport).
void compare_float_only(Integrator& in, const std::vector<IntegralSpec>& subset, const std::vector<size_t>& which,
                        Plan& plan, const SuiteOptions& opt, SuiteReport& rep) {
  auto agree = mfv::compare_with_reference(in, subset, opt.reference_samples, opt.seed);
  for (size_t j = 0; j < agree.size(); ++j) {
    rep.reference_compared++;
    if (!rep.reference_worst_at.empty() && !(agree[j].disagreement > rep.reference_worst)) continue;
    rep.reference_worst = std::max(agree[j].disagreement, rep.reference_worst);
    rep.reference_worst_point = rep.points.size() + which[j];  // run_plan appends the plan's points next
    const PointResult& p = plan.points[which[j]];
    rep.reference_worst_at = fmt::format("{} {}{} (kernel mean {:.9g}, reference {:.9g})", p.check, model_name(p),
                                         params_text(p), agree[j].kernel_mean, agree[j].reference_mean);
  }
}

// The reference runs the same estimator on the identical samples of the
// subset: the float kernel, its double twin and the double reference
// (reference_compare.hpp). The twin must agree with the reference to the
// bound derived from the float rounding of the same samples; a point where it
// does not fails its model x check. kf - kd bounds the point's rounding bias.
void compare_plan_with_reference(Integrator& in, Plan& plan, const SuiteOptions& opt, SuiteReport& rep,
                                 ReferenceTwin* shared) {
  if (opt.reference_samples == 0) return;
  std::vector<size_t> which = plan.reference_pick ? *plan.reference_pick : reference_subset(plan, opt.reference_every);
  std::vector<IntegralSpec> subset;
  for (size_t i : which) subset.push_back(plan.specs[i]);
  std::optional<ReferenceTwin> own;
  if (!shared) own.emplace(in.runtime(), plan.terms);
  ReferenceTwin& twin = shared ? *shared : *own;
  if (!twin.available()) return compare_float_only(in, subset, which, plan, opt, rep);
  rep.reference_twin = true;
  rep.reference_bound = 1.0;
  const int builds0 = twin.builds();
  auto agree = twin.compare(in, subset, opt.reference_samples, opt.seed);
  rep.reference_builds += twin.builds() - builds0;
  for (size_t j = 0; j < agree.size(); ++j) {
    const TwinAgreement& a = agree[j];
    PointResult& p = plan.points[which[j]];
    rep.reference_compared++;
    p.reference_compared = true;
    p.rounding_bound = a.rounding_bound;
    p.reference_failed = !a.ok;
    p.reference_detail = fmt::format(
        "double twin vs reference on {} samples: mean |twin - reference| {:.3g} > derived bound {:.3g} (float "
        "rounding x 2^-19 + 2^-43 of the scale / mu + 2^-46 of the scale / (mu w) at a lobe of width w); worst "
        "sample {}: twin {:.12g}, reference {:.12g}",
        opt.reference_samples, a.formula_gap, a.formula_bound, a.worst_index, a.worst_twin, a.worst_reference);
    const double ratio = a.formula_bound > 0 ? a.formula_gap / a.formula_bound
                         : a.formula_gap > 0 ? std::numeric_limits<double>::infinity()
                                             : 0.0;
    if (!rep.reference_worst_at.empty() && !(ratio > rep.reference_worst)) continue;
    rep.reference_worst = ratio;
    rep.reference_worst_point = rep.points.size() + which[j];
    rep.reference_worst_at = fmt::format("{} {}{} (twin mean {:.12g}, reference {:.12g}, float kernel {:.9g})", p.check,
                                         model_name(p), params_text(p), a.double_mean, a.reference_mean, a.float_mean);
  }
}

}  // namespace

void run_reciprocity(Runtime& rt, Plan& plan, const SuiteOptions& opt, SuiteReport& rep) {
  if (plan.specs.empty()) return;
  auto t0 = std::chrono::steady_clock::now();
  double b0 = rt.build_stats().seconds;
  Integrator in(rt, plan.terms);
  rep.build_seconds += rt.build_stats().seconds - b0;
  record_reciprocity(in, plan.specs, plan.points, kReciprocityBound, opt.scale, opt.seed, t0, rep);
}

uint32_t reciprocity_pairs(double scale) { return 64 * std::max<uint32_t>(1, uint32_t(64 * scale)); }

void record_reciprocity(Integrator& in, std::vector<IntegralSpec> specs, std::vector<PointResult> pts, double bound,
                        double scale, uint64_t seed, std::chrono::steady_clock::time_point t0, SuiteReport& rep,
                        bool streams_set) {
  if (specs.empty()) return;
  if (!(64 * scale <= double(UINT32_MAX / 64)))
    throw Error(fmt::format("--samples/--scale ask for {:.3g} reciprocity pairs per integral: too many", 4096 * scale));
  const uint32_t pairs = reciprocity_pairs(scale);
  if (!streams_set) assign_streams("reciprocity", specs);  // by identity (checks/streams.hpp)
  const WorstPairs w = in.reciprocity(specs, pairs, seed);  // one pair per work-item
  for (size_t i = 0; i < specs.size(); ++i) {
    pts[i].estimate = w.worst[i];
    pts[i].samples = pairs;
    pts[i].bounded = true;
    pts[i].bound = bound;
    pts[i].measure = "max asymmetry";
    pts[i].params["worst_pair"] = w.at[i];
    rep.points.push_back(pts[i]);
  }
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  rep.stats.push_back({"reciprocity", specs.size(), specs.size() * uint64_t(pairs) * 2, secs});
}

void run_plan(Integrator& in, Plan& plan, const SuiteOptions& opt, SuiteReport& rep,
              const std::vector<Integrator*>& others, ReferenceTwin* twin) {
  if (plan.specs.empty()) return;
  if (!plan.streams_set) assign_streams(plan.check, plan.specs);  // by identity (checks/streams.hpp), not by place
  in.stratify(plan.specs, plan.samples);  // the reference must see the same samples
  auto t0 = std::chrono::steady_clock::now();
  std::vector<Integrator*> all{&in};
  all.insert(all.end(), others.begin(), others.end());
  std::vector<Estimate> est = others.empty() ? in.run(plan.specs, plan.samples, opt.seed)
                                             : run_shared(all, plan.specs, plan.samples, opt.seed, rep.device_shares);
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (size_t i = 0; i < est.size(); ++i) {
    plan.points[i].estimate = est[i].mean;
    plan.points[i].stderr_ = est[i].stderr_;
    plan.points[i].dof = est[i].dof;
    plan.points[i].samples = est[i].samples;
  }
  rep.stats.push_back({plan.check, plan.specs.size(), plan.specs.size() * in.samples_used(plan.samples), secs});
  rep.double_accumulation = rep.double_accumulation && in.runtime().device().fp64;  // integrate.cl: acc_t
  compare_plan_with_reference(in, plan, opt, rep, twin);
  rep.points.insert(rep.points.end(), plan.points.begin(), plan.points.end());
}

void run_plan(Runtime& rt, Plan& plan, const SuiteOptions& opt, SuiteReport& rep) {
  if (plan.specs.empty()) return;
  double b0 = rt.build_stats().seconds;
  plan.terms.specialized = fast_path_pairs(plan.specs);  // kernels per term pair (runtime/specialize.hpp)
  Integrator in(rt, plan.terms);
  rep.build_seconds += rt.build_stats().seconds - b0;
  run_plan(in, plan, opt, rep);
}

void validate_suite_options(const SuiteOptions& opt) {
  for (auto& c : opt.checks)
    if (std::find(suite_checks().begin(), suite_checks().end(), c) == suite_checks().end())
      throw Error(fmt::format("unknown check '{}' (checks: {})", c, suite_check_list()));
  validate_scale(opt.scale);
  if (!(opt.family_alpha > 0 && opt.family_alpha < 1)) throw Error("--alpha-fw must be in (0, 1)");
  bool any = opt.models.empty();
  for (auto& m : models())
    for (auto& c : m.cases) any = any || suite_model_wanted(opt.models, model_case_name(m, c));
  for (auto* d : terms_of(Kind::D)) {
    any = any || suite_model_wanted(opt.models, d->id);
    for (auto* g : terms_of(Kind::G)) {
      any = any || suite_model_wanted(opt.models, d->id + "/" + g->id);
      for (auto* f : terms_of(Kind::F)) any = any || suite_model_wanted(opt.models, d->id + "/" + g->id + "/" + f->id);
    }
  }
  for (auto& name : aniso_model_names()) any = any || suite_model_wanted(opt.models, name);
  for (auto& name : sheen_model_names()) any = any || suite_model_wanted(opt.models, name);
  for (auto& name : bsdf_model_names()) any = any || suite_model_wanted(opt.models, name);
  if (!any) throw Error("no model matches the --model filter (names are D, D/G, D/G/F or model[case]: see 'mfv list')");
}

SuitePlans make_suite_plans(const SuiteOptions& opt) {
  SuitePlans sp;
  sp.plans = make_plans(opt);
  for (const CheckKind& k : check_kinds())  // the pairs kind (reciprocity): one plan of every source's batches
    if (shape_of(k) == Shape::Pairs && k.in_run && suite_check_wanted(opt, k.check))
      sp.reciprocity = reciprocity_plan(k, opt);
  // every integral's stream from its identity (checks/streams.hpp), before a shard cuts the plans
  for (auto& p : sp.plans) {
    assign_streams(p.check, p.specs);
    p.streams_set = true;
  }
  assign_streams("reciprocity", sp.reciprocity.specs);
  sp.reciprocity.streams_set = true;
  return sp;
}

TermSelection suite_terms(SuitePlans& sp) {
  // One program for every plan: the kernels specialized per term pair
  // (runtime/specialize.hpp) are shared by the plans that integrate the
  // same pair (furnace, energy, energy_diffuse), so each is compiled once.
  TermSelection terms = sp.reciprocity.terms;
  for (auto& p : sp.plans) {
    p.terms.specialized = fast_path_pairs(p.specs);
    terms.add(p.terms);
  }
  return terms;
}

const IntegralSpec* first_spec(const std::vector<Plan>& plans) {
  for (const Plan& p : plans)
    if (!p.specs.empty()) return &p.specs.front();
  return nullptr;
}

namespace {

// This thread's CPU seconds (PoCL builds a program in the calling thread).
double thread_cpu_seconds() {
  timespec t{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// The double twin built from source takes ~0.7 s of CPU or more; read from
// PoCL's cache, with its sample_values, ~0.05 s.
constexpr double kSourceBuildCpuSeconds = 0.3;

// Where a plan that takes the furnace truth left its points in rep.points,
// and its specs as they were before run_plan (which stratifies them): those
// FurnaceTruthAhead computes the truths of.
struct TruthPoints {
  std::vector<IntegralSpec> specs;
  size_t first = 0;
};

// run_suite_plans less the truths: it lists where they go.
std::vector<TruthPoints> run_plans(Runtime& rt, SuitePlans& sp, const SuiteOptions& opt, SuiteReport& rep,
                                   const std::vector<Runtime*>& more) {
  std::vector<TruthPoints> truth_at;
  std::vector<Plan>& plans = sp.plans;
  Plan& rp = sp.reciprocity;
  const TermSelection terms = suite_terms(sp);
  const double b0 = rt.build_stats().seconds;
  PendingIntegrators pending = integrators_beside(more, terms);  // the other devices' builds beside this one
  // One double twin for every plan's reference comparison, as one program integrates them
  std::optional<ReferenceTwin> twin;
  if (opt.reference_samples > 0) twin.emplace(rt, terms);
  // Where a compile-ahead child builds the integration program (checks/compile_ahead.hpp):
  // the twin meanwhile, then the program from PoCL's cache once the child has built it
  if (rt.hand_over()) {
    const double c0 = thread_cpu_seconds();
    if (twin)
      if (const IntegralSpec* first = first_spec(plans)) rep.reference_builds += twin->build_ahead(*first, opt.seed);
    // a twin read from PoCL's cache (a warm run) means the program is there too: no wait for the child
    if (thread_cpu_seconds() - c0 >= kSourceBuildCpuSeconds) rt.await(HandOver::IntegrationProgram);
  }
  Integrator in(rt, terms);
  const std::vector<std::unique_ptr<Integrator>> others = integrators_ready(pending, rt, more, rep.device_shares);
  std::vector<Integrator*> other;
  for (auto& o : others) other.push_back(o.get());
  rep.build_seconds += rt.build_stats().seconds - b0;
  for (size_t i = 0; i < plans.size(); ++i) {
    progress::Task task(fmt::format("{} ({} of {} plans)", plans[i].check, i + 1, plans.size()), 0);
    // its pooled test is two-sided, against the truth attach_truths sets on its points (the last recorded)
    const bool truth = check_kind(plans[i].check).truth && !plans[i].specs.empty();
    std::vector<IntegralSpec> specs = truth ? plans[i].specs : std::vector<IntegralSpec>();
    run_plan(in, plans[i], opt, rep, other, twin ? &*twin : nullptr);
    if (truth) truth_at.push_back({std::move(specs), rep.points.size() - plans[i].points.size()});
  }
  if (!rp.specs.empty()) {
    progress::Task task("reciprocity", 0);
    record_reciprocity(in, rp.specs, rp.points, kReciprocityBound, opt.scale, opt.seed,
                       std::chrono::steady_clock::now(), rep, rp.streams_set);
  }
  return truth_at;
}

// The furnace truths (checks/furnace_truth.hpp) on the points run_plans recorded.
void attach_truths(SuiteReport& rep, const std::vector<TruthPoints>& truth_at) {
  for (const TruthPoints& t : truth_at) attach_furnace_truth(t.specs, &rep.points[t.first]);
}

}  // namespace

void run_suite_plans(Runtime& rt, SuitePlans& sp, const SuiteOptions& opt, SuiteReport& rep,
                     const std::vector<Runtime*>& more) {
  const FurnaceTruthAhead truth(sp.plans);  // beside the builds and the integration; joined by attach_truths
  const std::vector<TruthPoints> truth_at = run_plans(rt, sp, opt, rep, more);
  attach_truths(rep, truth_at);
}

SuiteReport run_suite(Runtime& rt, const SuiteOptions& opt, const std::vector<Runtime*>& more) {
  validate_suite_options(opt);
  return run_suite(rt, opt, make_suite_plans(opt), more);
}

SuiteReport run_suite(Runtime& rt, const SuiteOptions& opt, SuitePlans sp, const std::vector<Runtime*>& more) {
  SuiteReport rep;
  // the furnace truths beside the whole run (issue 30): joined where the verdicts need them
  const FurnaceTruthAhead truth(sp.plans);
  const std::vector<TruthPoints> truth_at = run_plans(rt, sp, opt, rep, more);
  // the pointwise kinds (agree, stability) run whole, never in a shard (docs/scale.md)
  run_pointwise_kinds(rt, opt, rep);
  attach_truths(rep, truth_at);
  if (rep.points.empty()) throw Error("no model matches the --model filter");
  judge(rep, opt);
  return rep;
}

}  // namespace mfv
