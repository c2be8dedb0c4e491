// The conformance suite (mfv run): D normalisation, masking (weak white
// furnace), furnace albedo, energy with F (and with diffuse), reciprocity,
// over every catalog combination, with verdicts a CI can trust.
#pragma once

#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "checks/device_share.hpp"
#include "checks/reference_compare.hpp"
#include "checks/registry.hpp"
#include "checks/integrate.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/opencl.hpp"
#include "stats/verdict.hpp"

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mfv {

// Inconclusive (mfv check): no point failed, but at some point the estimator
// did not reach the integrand's mass (PointResult::inconclusive): neither
// pass nor fail; the gate does not pass it.
enum class Verdict { Pass, Fail, XFail, XPass, Inconclusive };
const char* verdict_name(Verdict v);

// What the catalog predicts for one point: Expect (catalog/models.hpp) says
// it must hold, it must fail (a known deficiency large enough to show at any
// seed), or it may fail (a deficiency whose size depends on F, so either
// outcome is accepted).

// One integral (or one reciprocity batch) at one parameter point.
struct PointResult {
  std::string check;
  const Term *d = nullptr, *g = nullptr, *f = nullptr;
  std::string model;  // a whole model ("phong_004[n=1]") or user code (mfv check); empty: the D/G/F ids
  std::map<std::string, double> params;  // alpha, native params, cos_o, kd...
  double estimate = 0, stderr_ = 0;
  double rounding_bound = 0;  // bias bound from float rounding where measured (0: judge derives one)
  double bias = 0;            // judge: the bias bound tested with (rounding + tolerance x |expected|)
  double z = 0;               // judge: deviation / total uncertainty (stderr_ + bias), stats/verdict.hpp
  uint32_t dof = 0;           // stderr_ from replicates: Student t with dof degrees of freedom (0: normal)
  double expected = 0;        // the value a correct model gives (d_norm, masking)
  // The integral's value where the catalog knows it though the test is an
  // upper limit (furnace: quadrature of the double reference,
  // checks/furnace_truth.hpp): the group's pooled test is then two-sided.
  bool known = false;
  double known_value = 0, known_error = 0;
  double bound = 0;         // the threshold the estimate was tested against
  bool upper_only = false;  // test is estimate <= expected (albedo) rather than ==
  uint64_t samples = 0;
  bool failed = false;   // deviation beyond noise and tolerance
  double deviation = 0;  // estimate - expected
  Expect expect = Expect::Hold;
  double tolerance = 0;  // documented approximation tolerance (relative)
  std::string reason;    // why the point is expected to (or may) fail
  // The registry's expectation of this point (checks/registry.hpp: expect()).
  void take(const Expectation& e) {
    expect = e.expect;
    reason = e.reason;
    tolerance = e.tolerance;
  }
  // A measured maximum tested against the fixed `bound` (reciprocity, the
  // finiteness census, pointwise agreement) rather than a z-test; `measure`
  // names it and `detail` gives the input where it was worst.
  bool bounded = false;
  std::string measure, detail;
  // The same-sample reference comparison (host/checks/reference_compare.hpp),
  // where this integral was compared (its rounding bound is rounding_bound
  // above), and a failure of the double twin against the reference, which
  // fails the group's verdict.
  bool reference_compared = false, reference_failed = false;
  // Set before judge() where the estimate rests on too few effective samples
  // to be tested (mfv check: user/user_power.hpp); `detail` says why. Such a
  // point neither passes nor fails, and stays out of the pooled test.
  bool inconclusive = false;
  std::string reference_detail;  // the comparison, its worst sample and its bound
};

// All points of one model under one check, with its expectation.
struct GroupResult {
  std::string check;
  std::string model;           // "ggx", "ggx/smith_ggx", "ggx/smith_ggx/schlick"
  bool expect_fail = false;    // some points must fail
  std::string reason;          // why failures are expected (catalog), empty if none
  double tolerance = 0;        // largest documented approximation tolerance applied
  std::vector<size_t> points;  // indices into SuiteReport::points
  size_t worst = 0;            // the point with the largest |deviation| / (noise + tolerance)
  size_t failures = 0;
  // The pooled test of the points that must hold (stats/verdict.hpp); n = 0: none.
  stats::Pooled pooled;
  Verdict verdict = Verdict::Pass;
};

struct CheckStats {
  std::string check;
  uint64_t integrals = 0, samples = 0;
  double seconds = 0;
};

// max(64, n * scale) samples for one integral; throws mfv::Error when that
// does not fit a 64-bit count (a double cast there would be undefined).
uint64_t scaled_samples(uint64_t n, double scale);

// --scale (or --samples / kSuiteBaseSamples) in (0, 2^26]: reciprocity runs
// 64 * scale pairs per work-item in a uint32 (record_reciprocity).
void validate_scale(double scale);

struct SuiteOptions {
  uint64_t seed = 1;
  double scale = 1.0;                // multiplies every check's sample count
  double family_alpha = 1e-6;        // family-wise false-alarm rate for the run
  std::vector<std::string> checks;   // empty: all
  std::vector<std::string> models;   // substrings of model names; empty: all
  uint32_t reference_samples = 256;  // same-sample comparison, first N samples
  // Compare every k-th integral of each model x check (its first, the
  // narrowest and most grazing, always); whole-model and d_norm integrals
  // are all compared (1 = all).
  uint32_t reference_every = 97;
  int density = 1;  // grid density: mfv run --profile (checks/profile.hpp)
};

struct SuiteReport {
  std::vector<PointResult> points;
  std::vector<GroupResult> groups;
  std::vector<CheckStats> stats;
  double z_threshold = 0;           // noise multiple a deviation must exceed
  size_t tests = 0;                 // statistical tests in the run (Bonferroni count)
  size_t pooled_tests = 0;          // pooled tests, one per group with points that must hold
  bool double_accumulation = true;  // every plan summed its samples in double (the rounding bound)
  double build_seconds = 0;
  double reference_worst = 0;  // worst relative kernel/reference disagreement
  std::string reference_worst_at;
  size_t reference_worst_point = 0;  // the index in points of reference_worst_at's integral
  uint64_t reference_compared = 0;
  // Kernel and reference means on identical samples, |k - r| / max(mean |r|, 1).
  // Float rounding of ill-conditioned samples (Kelemen's 1/(v.m)^2 at grazing
  // view, where v.m ~ 1e-3) reached 1.5e-3 over 40 seeds; a term off by 1 %
  // shows as 1e-2.
  // Where the device has fp64 the comparison is the double twin's
  // (reference_compare.hpp): reference_worst is then the worst ratio of a
  // formula gap to its derived bound, and reference_bound 1.
  double reference_bound = 5e-3;
  bool reference_twin = false;
  int reference_builds = 0;       // double-twin programs built for the comparison (not counted as the check's builds)
  std::string reference_note;     // replaces the reference line where no double twin runs (mfv check)
  std::string title = "mfv run";  // report heading and JUnit suite name
  bool list_passes = false;       // the console lists pass verdicts too (a handful of groups)
  std::vector<DeviceShare> device_shares;  // mfv run --device all: what each device integrated
  bool reference_ok() const;
  bool gate_ok() const;  // every verdict as expected and the reference agrees
  // One line per reason the gate failed: the comparison, its worst case and its bound.
  std::vector<std::string> gate_failures() const;
};

void validate_suite_options(const SuiteOptions& opt);  // throws mfv::Error naming the bad option
// `more`: other devices that share the integration of every plan with `rt`
// (mfv run --device all: checks/device_share.hpp); the reference comparison,
// reciprocity and the pointwise kinds run on `rt`.
SuiteReport run_suite(Runtime& rt, const SuiteOptions& opt, const std::vector<Runtime*>& more = {});
struct SuitePlans;
// The same over plans made by make_suite_plans(opt) (opt validated).
SuiteReport run_suite(Runtime& rt, const SuiteOptions& opt, SuitePlans sp, const std::vector<Runtime*>& more = {});


// ---- Pieces mfv check (host/user/) shares with mfv run --------------------

// One check's integrals, run through one program.
struct Plan {
  std::string check;
  std::vector<IntegralSpec> specs;
  std::vector<PointResult> points;
  uint64_t samples = 0;
  TermSelection terms;
  // Sharded runs (checks/shard.hpp): streams set (by identity) over the whole run
  // before the plan was cut, and the integrals the reference compares, picked
  // over the whole plan (positions in this plan); unset: run_plan numbers and picks.
  bool streams_set = false;
  std::optional<std::vector<size_t>> reference_pick;
};

// The run's plans (make_plans, reciprocity_plan where wanted) with every
// integral's stream numbered as run_suite numbers them; run_suite_plans runs
// them into `rep` without judging (mfv run --shard cuts them in between).
struct SuitePlans {
  std::vector<Plan> plans;
  Plan reciprocity;
};
SuitePlans make_suite_plans(const SuiteOptions& opt);
// The one integration program's terms for all of sp's plans (run_suite_plans);
// sets each plan's specialized pairs.
TermSelection suite_terms(SuitePlans& sp);
// The first plan's first integral (nullptr where the plans have none): the
// one a compile-ahead hand-over launches sample_values on (any integral
// compiles the same kernel; checks/compile_ahead.hpp).
const IntegralSpec* first_spec(const std::vector<Plan>& plans);
void run_suite_plans(Runtime& rt, SuitePlans& sp, const SuiteOptions& opt, SuiteReport& rep,
                     const std::vector<Runtime*>& more = {});
// Which integrals of a plan the reference compares: every whole-model and
// d_norm integral, and of each model x check its first and every k-th after it.
std::vector<size_t> reference_subset(const Plan& plan, uint32_t every);

// Widths and views of the grids (d_norm widths; combination widths; view
// cosines from 1e-4 to 1, dense towards grazing).
const std::vector<double>& suite_norm_alphas();
const std::vector<double>& suite_alphas();
std::vector<double> view_cosines(int n);
// An empty plan of `check` whose integrals take scaled_samples(base_samples, scale).
Plan new_plan(const std::string& check, uint64_t base_samples, double scale);

// Runs the plan's integrals (each on the stream of its identity,
// checks/streams.hpp), records estimates, timing and, when
// opt.reference_samples > 0, the same-sample reference comparison into `rep`.
// `others`: more devices sharing the integration (run_suite's `more`).
// `twin`: the double twin (checks/reference_compare.hpp) of a program with
// at least plan.terms, shared by the plans of a run (one build, and one
// compile of its sample_values, for the run); nullptr: one built here.
void run_plan(Integrator& in, Plan& plan, const SuiteOptions& opt, SuiteReport& rep,
              const std::vector<Integrator*>& others = {}, ReferenceTwin* twin = nullptr);
// The same through a program built here with plan.terms (its build time goes to rep.build_seconds).
void run_plan(Runtime& rt, Plan& plan, const SuiteOptions& opt, SuiteReport& rep);

// ---- Pieces mfv run --scene (host/scene/) shares with mfv run -------------

// expect(check, d, g, alpha, f0, kd): the registry's (checks/registry.hpp).
std::vector<Plan> make_plans(const SuiteOptions& opt);  // every integral check of the catalog, filtered by opt
// The batches of the pairs kind k (Shape::Pairs) of every source that takes it, filtered by opt.models.
Plan reciprocity_plan(const CheckKind& k, const SuiteOptions& opt);
// Builds the plan's program (terms without G1) and records one bounded point per batch.
void run_reciprocity(Runtime& rt, Plan& plan, const SuiteOptions& opt, SuiteReport& rep);
// The pointwise kinds (agree, stability) at mfv run's budget, one bounded
// point per case, filtered by opt.checks and opt.models (checks/suite_pointwise.cpp).
void run_pointwise_kinds(Runtime& rt, const SuiteOptions& opt, SuiteReport& rep);
// What the compile-ahead child (checks/compile_ahead.hpp) runs of them: each
// kernel launched as the run first launches it, with as little host work.
void compile_pointwise_kinds(Runtime& rt, const SuiteOptions& opt);

uint32_t reciprocity_pairs(double scale);  // pairs per reciprocity integral at --scale (record_reciprocity)
// Integrator::reciprocity over `specs`, 64 x per_item pairs each (per_item from the scale): one bounded point per spec
// (pts[i] describes spec i; estimate = worst asymmetry, with the pair index)
// and the check's timing since t0 go into `rep`.
void record_reciprocity(Integrator& in, std::vector<IntegralSpec> specs, std::vector<PointResult> pts, double bound,
                        double scale, uint64_t seed, std::chrono::steady_clock::time_point t0, SuiteReport& rep,
                        bool streams_set = false);  // true: keep the specs' streams
constexpr double kReciprocityBound = 1e-4;  // float rounding of the two evaluation orders stays below ~1e-6

// The option filters: is `check` selected; does `name` match the --model filter.
bool suite_check_wanted(const SuiteOptions& opt, const std::string& check);
bool suite_model_wanted(const std::vector<std::string>& filter, const std::string& name);

// ---- Point sources crossed with the registry (docs/adding-a-check.md step 6)

// A point source: the plans it builds for one kind that it takes
// (CheckKind::sources), read from the kind's shape (shape_of) and fields,
// never from its name. `add` returns false where the source has no points of
// that shape: the registry then names a source that cannot take the kind.
struct PointSource {
  Source source = kSourceGrid;
  const char* name = "";
  std::function<bool(const CheckKind&, std::vector<Plan>&)> add;
};
// The one place kinds meet sources: every kind of the registry that `wanted`
// selects, in registry order, at every source that takes it, in the order
// given. Throws mfv::Error naming the kind and the source where a source the
// registry names for a kind builds nothing for its shape.
std::vector<Plan> cross_sources(const std::vector<PointSource>& sources,
                                const std::function<bool(const CheckKind&)>& wanted);
// mfv run's sources: the D x G x F grid, whole models, the anisotropic pairs,
// the sheen lobes, the rough dielectric BSDFs.
std::vector<PointSource> suite_sources(const SuiteOptions& opt);

// The sheen lobes (Term::own_lobe, host/checks/suite_sheen.cpp): d_norm,
// masking and furnace of the Charlie D with its visibility; their names for
// the --model filter; the masking closed form G1(o)(1 + Λ_D(o)) with Λ_D by
// quadrature of the reference D.
PointSource sheen_source(const SuiteOptions& opt);
std::vector<std::string> sheen_model_names();
double sheen_masking_closed_form(const Term& d, const Term& g, double alpha, double cos_o);

// The anisotropic D and Smith G cases (host/checks/suite_aniso.cpp): d_norm,
// masking and furnace plans, and the model names they use.
PointSource aniso_source(const SuiteOptions& opt);
std::vector<std::string> aniso_model_names();
// The rough dielectric BSDFs (catalog/bsdfs.hpp) in every kind that takes
// them (kSourceBsdf, checks/suite_bsdf.cpp); their names for --model.
PointSource bsdf_source(const SuiteOptions& opt);
std::vector<std::string> bsdf_model_names();

// z-test verdicts for every point, then one verdict per model x check: a
// group fails on a point that must hold or on its pooled test (stats/).
void judge(SuiteReport& rep, const SuiteOptions& opt);
std::string model_name(const PointResult& p);

}  // namespace mfv
