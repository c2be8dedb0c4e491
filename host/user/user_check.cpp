#include "user/user_check.hpp"

#include "catalog/roughness.hpp"
#include "checks/streams.hpp"
#include "checks/stability.hpp"
#include "rng/philox.hpp"
#include "stats/verdict.hpp"
#include "user/time_limit.hpp"
#include "user/user_detail.hpp"
#include "user/user_power.hpp"
#include "user/user_twin.hpp"
#include "util/error.hpp"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <cmath>
#include <limits>
#include <sstream>

namespace mfv {

// The registry's kinds that the user source takes (CheckKind::sources), in registry order.
const std::vector<std::string>& user_checks() {
  static const std::vector<std::string> c = [] {
    std::vector<std::string> out;
    for (const CheckKind& k : check_kinds())
      if (k.sources & kSourceUser) out.push_back(k.check);
    return out;
  }();
  return c;
}

SuiteOptions suite_options_of(const UserCheckOptions& o) {
  SuiteOptions s;
  s.seed = o.seed;
  s.scale = o.scale;
  s.family_alpha = o.family_alpha;
  s.checks = o.checks;
  s.reference_samples = 0;  // no reference of user code: its double twin (user/user_twin.hpp) and `agree` instead
  return s;
}

namespace {

using namespace user_detail;

// ---- the program -------------------------------------------------------------

// integrate.cl with the user's file and the adapters after it: one build for
// every check. A compile error leads with its first line in the user's file.
// Where the device has fp64 the estimators run in double (MFV_DOUBLE) and
// hand the user's float code directions rounded once (no rounding of mfv's
// own); `twin` builds the user's code in double too (user/user_twin.hpp).
cl::Program build_user_program(Runtime& rt, const UserBrdf& u, bool twin = false) {
  std::vector<std::string> defines = {"MFV_USER_BRDF", fmt::format("MFV_USER_NPARAMS={}", u.params.size()),
                                      fmt::format("MFV_USER_DIALECT={}", int(u.dialect))};
  if (rt.device().fp64) {
    defines.push_back("MFV_ACC_DOUBLE");
    defines.push_back("MFV_DOUBLE");
  }
  if (twin) defines.push_back("MFV_USER_TWIN");
  if (u.has_brdf) defines.push_back("MFV_USER_HAS_BRDF");
  if (u.has_btdf) defines.push_back("MFV_USER_HAS_BTDF");
  if (u.has_bsdf) defines.push_back("MFV_USER_HAS_BSDF");
  if (u.has_d) defines.push_back("MFV_USER_HAS_D");
  if (u.has_g1) defines.push_back("MFV_USER_HAS_G1");
  try {
    // no catalog terms or models: the user's names must not clash with them
    std::vector<std::string> files = {"common.cl", "rng.cl", kDispatchBefore};
    for (auto& f : integration_files()) files.push_back(f);
    for (const char* f : {"user_guard.cl", "user_prelude.cl", "user_brdf.cl"}) files.push_back(f);
    std::vector<Runtime::ExtraSource> sources;
    for (auto& s : u.sources) sources.push_back({s.name, s.text, "user_brdf.cl"});
    return rt.build(files, defines, generate_dispatch(TermSelection{}), kDispatchBefore, sources);
  } catch (const Error& e) {
    std::string log = user_terms(e.what()), first;
    size_t errors = 0;
    std::istringstream lines(log);
    // clang writes "FILE:L:C: error: what"; PoCL's log, "error: FILE:L:C: what"
    for (std::string line; std::getline(lines, line);) {
      bool pocl = line.rfind("error: ", 0) == 0;
      if (!pocl && line.find(": error: ") == std::string::npos) continue;
      ++errors;
      if (pocl) line = line.substr(7);
      for (auto& s : u.sources)
        if (first.empty() && line.rfind(s.name + ":", 0) == 0) first = line;
    }
    if (errors == 0) {
      // no compile error at all: the build stopped before the source (a bad option)
      std::string cause = log.substr(log.find("build log:") == std::string::npos ? 0 : log.find("build log:") + 11);
      cause = cause.substr(0, cause.find('\n'));
      while (!cause.empty() && std::isspace(static_cast<unsigned char>(cause.back()))) cause.pop_back();
      throw Error(
          fmt::format("the OpenCL build of {} failed before compiling it: {} (build options '{}'; "
                      "MFV_CL_OPTIONS adds to them)\n{}",
                      u.path, cause.empty() ? "no reason given" : cause, rt.base_options(), log));
    }
    if (first.empty()) first = fmt::format("{} does not compile", u.path);
    throw Error(fmt::format("{} ({} error{}; the build log follows)\n{}", first, errors, errors == 1 ? "" : "s", log));
  }
}

}  // namespace

namespace user_detail {

// ---- parameter grids ---------------------------------------------------------

// The roughness values whose widths are `alphas` and lie in the declared
// range (evenly thinned to at most `most`); the defaults alone without a
// roughness or with a fixed one.
std::vector<Values> roughness_grid(const UserBrdf& u, const std::vector<double>& alphas, size_t most) {
  Values base = u.defaults();
  if (u.roughness < 0 || u.params[size_t(u.roughness)].fixed) return {base};
  const UserParam& p = u.params[size_t(u.roughness)];
  std::vector<double> vals;
  for (double a : alphas) {
    double v = native_from_alpha(p.role, a);
    if (v >= p.lo && v <= p.hi) vals.push_back(v);
  }
  if (vals.empty()) vals = {p.lo, p.value, p.hi};
  // the declared range's ends, where the suite's widths stop short of them
  // (a file declaring alpha down to 1e-4 is tested there, issue 28); kept
  // by the thinning below, which keeps the first and the last value
  std::sort(vals.begin(), vals.end());
  if (vals.front() > p.lo * 1.05) vals.insert(vals.begin(), p.lo);
  if (vals.back() < p.hi / 1.05) vals.push_back(p.hi);
  vals.erase(std::unique(vals.begin(), vals.end()), vals.end());
  std::vector<Values> out;
  for (size_t k = 0; k < std::min(most, vals.size()); ++k) {
    size_t i = most >= vals.size() ? k : (k * (vals.size() - 1)) / (most - 1);
    Values x = base;
    x[size_t(u.roughness)] = vals[i];
    out.push_back(x);
  }
  return out;
}

// Every other parameter at each end of its range (a product of corners).
std::vector<Values> corners(const UserBrdf& u, const Values& base) {
  std::vector<Values> out = {base};
  for (size_t i = 0; i < u.params.size(); ++i) {
    if (int(i) == u.roughness) continue;
    std::vector<Values> next;
    for (auto& v : out)
      for (double x : u.params[i].ends()) {
        Values w = v;
        w[i] = x;
        next.push_back(w);
      }
    out = next;
  }
  return out;
}

std::map<std::string, double> named(const UserBrdf& u, const Values& v) {
  std::map<std::string, double> m;
  for (size_t i = 0; i < v.size(); ++i) m[u.params[i].name] = v[i];
  return m;
}

std::string named_text(const UserBrdf& u, const Values& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += fmt::format("{}{}={:g}", s.empty() ? "" : " ", u.params[i].name, v[i]);
  return s;
}

IntegralSpec user_spec(const UserBrdf& u, IntegralKind kind, const Values& v, double cos_o, int channel) {
  IntegralSpec s;
  s.check = static_cast<int32_t>(kind);
  float* p[kUserMaxParams] = {&s.p[0], &s.p[1], &s.p[2], &s.p[3], &s.p[4], &s.p[5]};
  for (size_t i = 0; i < v.size(); ++i) *p[i] = float(v[i]);
  s.width = float(u.width(v));
  s.cos_o = float(cos_o);
  s.channel = uint32_t(channel);
  return s;
}

PointResult point_of(const UserBrdf& u, const std::string& check, const Values& v) {
  PointResult p;
  p.check = check;
  p.model = u.name;
  p.params = named(u, v);
  return p;
}

}  // namespace user_detail

namespace {

using namespace user_detail;

// ---- integrals -----------------------------------------------------------------

// The user's BRDF as a point source crossed with the registry (the kinds in
// `checks` that it takes). The albedo kinds integrate with their own
// estimator (AlbedoMis: kernels/albedo.cl albedo_mis_general) wherever the
// file gives a proposal width; a file that declares no roughness (width 0:
// no width to shape visible normals on) keeps the defensive mixture of
// widths (Albedo), as its d_norm and masking do (docs/cli/check.md).
std::vector<Plan> make_plans(const UserBrdf& u, const UserCheckOptions& opt, const std::vector<std::string>& checks) {
  auto add = [&](Plan& plan, IntegralKind kind, const Values& v, double co, int ch, bool upper) {
    if (kind == IntegralKind::AlbedoMis && !(u.width(v) > 0)) kind = IntegralKind::Albedo;
    plan.specs.push_back(user_spec(u, kind, v, co, ch));
    PointResult p = point_of(u, plan.check, v);
    if (kind != IntegralKind::DNorm) p.params["cos_o"] = co;
    if (ch >= 0 && kind != IntegralKind::DNorm && kind != IntegralKind::Masking) p.params["channel"] = ch;  // 0 r, 1 g, 2 b
    p.expected = 1.0;
    p.upper_only = upper;
    plan.points.push_back(p);
  };
  PointSource source{kSourceUser, "a user's BRDF", [&](const CheckKind& k, std::vector<Plan>& plans) {
                       Plan p = new_plan(k.check, k.base_samples, opt.scale);
                       switch (shape_of(k)) {
                         case Shape::DNorm:
                           for (auto& v : roughness_grid(u, suite_norm_alphas(), 64))
                             add(p, k.kind, v, 1.0, 0, k.upper_only);
                           break;
                         case Shape::Masking:
                           for (auto& v : roughness_grid(u, suite_alphas(), 64))
                             for (double co : view_cosines(32)) add(p, k.kind, v, co, 0, k.upper_only);
                           break;
                         case Shape::Furnace: {
                           // The budget of the full width grid whatever the file declares: a BRDF
                           // with fewer widths (none: Lambert) gets more samples per integral, so
                           // that the pooled test finds a 1 % gain (docs/statistics.md).
                           const auto grid = roughness_grid(u, suite_alphas(), 64);
                           const double share =
                               double(suite_alphas().size()) / double(std::max<size_t>(grid.size(), 1));
                           p = new_plan(k.check, uint64_t(double(k.base_samples) * std::max(1.0, share)), opt.scale);
                           for (auto& v : grid)
                             for (double co : view_cosines(32))
                               for (int ch : opt.channels) add(p, k.kind, v, co, ch, k.upper_only);
                           break;
                         }
                         case Shape::Energy:
                           for (auto& r : roughness_grid(u, suite_alphas(), 6))
                             for (auto& v : corners(u, r))
                               for (double co : view_cosines(16))
                                 for (int ch : opt.channels) add(p, k.kind, v, co, ch, k.upper_only);
                           break;
                         case Shape::BsdfFlux:
                         case Shape::BsdfAvg:
                         case Shape::MaskingT: add_transmission(p, k, u, opt); break;
                         default: return false;
                       }
                       plans.push_back(p);
                       return true;
                     }};
  return cross_sources({source}, [&](const CheckKind& k) {
    return k.runner == Runner::Integral && std::find(checks.begin(), checks.end(), k.check) != checks.end();
  });
}

// ---- reciprocity -------------------------------------------------------------

void run_user_reciprocity(Runtime& rt, const cl::Program& prog, Integrator& in, const UserBrdf& u,
                          const UserCheckOptions& opt, SuiteReport& rep) {
  auto t0 = Clock::now();
  std::vector<IntegralSpec> specs;
  std::vector<PointResult> pts;
  std::vector<Values> settings;
  for (auto& r : roughness_grid(u, {1e-4, 1e-2, 0.1, 0.3, 1.0}, 64))
    for (auto& v : corners(u, r))
      for (int ch : opt.channels) {
        specs.push_back(user_spec(u, IntegralKind::Albedo, v, 1.0, ch));
        PointResult p = point_of(u, "reciprocity", v);
        p.params["channel"] = ch;
        pts.push_back(p);
        settings.push_back(v);
      }
  const size_t first = rep.points.size();
  assign_streams("reciprocity", specs);  // by identity (checks/streams.hpp): kept for describe_reciprocity
  record_reciprocity(in, specs, pts, kUserReciprocityBound, opt.scale, opt.seed, t0, rep, true);
  // a failing point names its pair's directions and both values
  std::vector<PointResult*> failing;
  std::vector<Values> at;
  for (size_t i = first; i < rep.points.size(); ++i)
    if (!(rep.points[i].estimate <= rep.points[i].bound)) {
      rep.points[i].params["stream"] = double(specs[i - first].stream);  // the pair's Philox stream
      rep.points[i].params["stream_hi"] = double(specs[i - first].stream_hi);
      failing.push_back(&rep.points[i]);
      at.push_back(settings[i - first]);
    }
  if (!failing.empty()) describe_reciprocity(rt, prog, opt.seed, at, failing);
}

// Per-point sample sizing (user/user_power.hpp): the upper-limit points of
// `plan` (rep.points[first..]) whose pass lacks the power to detect a 5 %
// gain are extended with fresh samples (samples n .. n' - 1 of their own
// streams), grouped by n', and each estimate becomes the mean over all n'.
// Returns the evaluations it took.
double size_for_power(Integrator& in, const Plan& plan, SuiteReport& rep, size_t first, double z, uint64_t seed,
                      const std::function<void(double, const std::string&)>& arm) {
  std::map<uint64_t, std::vector<size_t>> by;
  for (size_t j = 0; j < plan.specs.size(); ++j) {
    const PointResult& p = rep.points[first + j];
    const uint64_t need = samples_for_power(p, z);
    if (need > p.samples) by[need].push_back(j);
  }
  double evals = 0;
  for (auto& [need, idx] : by) {
    std::vector<IntegralSpec> specs;
    for (size_t j : idx) specs.push_back(plan.specs[j]);
    const uint64_t n0 = rep.points[first + idx.front()].samples;  // one pass: every point has the same
    arm(double(need - n0) * double(specs.size()), "the " + plan.check + " integrals sized for power");
    const std::vector<Estimate> ext = in.run(specs, need - n0, seed, n0);
    for (size_t k = 0; k < idx.size(); ++k) {
      PointResult& p = rep.points[first + idx[k]];
      const double a = double(p.samples), b = double(ext[k].samples), n = a + b;
      p.estimate = (a * p.estimate + b * ext[k].mean) / n;
      p.stderr_ = std::sqrt(a * a * p.stderr_ * p.stderr_ + b * b * ext[k].stderr_ * ext[k].stderr_) / n;
      p.samples = p.samples + ext[k].samples;
    }
    evals += double(need - n0) * double(specs.size());
  }
  return evals;
}

// Seconds per evaluation of the user's brdf, from a small launch of the
// furnace integrand at the defaults (itself under the minimum step limit).
double calibrate(Integrator& in, const UserBrdf& u) {
  constexpr uint64_t kSamples = 4096;
  constexpr int kIntegrals = 8;
  std::vector<IntegralSpec> specs;
  for (int k = 0; k < kIntegrals; ++k) {
    specs.push_back(user_spec(u, IntegralKind::Albedo, u.defaults(), 0.125 * (k + 1), 0));
    specs.back().stream = uint32_t(k);
  }
  watchdog_arm(kMinStepSeconds, "a calibration launch of the BRDF");
  auto t0 = Clock::now();
  in.run(specs, kSamples, 1);
  return since(t0) / double(kSamples * kIntegrals);
}

}  // namespace

SuiteReport run_user_check(Runtime& rt, const UserBrdf& user, const std::optional<Claim>& claim,
                           const UserCheckOptions& opt) {
  // With --as, the estimators take the claimed model's own proposal width
  UserBrdf u = user;
  if (claim && claim->proposal(u.defaults()) > 0)
    u.claimed_width = [c = *claim](const std::vector<double>& v) { return c.proposal(v); };
  // Which checks: those asked for, each needing what it needs.
  std::vector<std::string> checks = opt.checks;
  const bool reflect = u.has_brdf || u.has_bsdf;
  auto available = [&](const std::string& c) -> std::string {
    const CheckKind& k = check_kind(c);
    // the transmission kinds: those of the catalog's BSDFs the D x G x F grid does not take (agree takes both)
    const bool transmission = (k.sources & kSourceBsdf) && !(k.sources & kSourceGrid);
    if (transmission) {
      if (!u.transmits()) return "needs 'float3 btdf(float3 wi, float3 wo, const float* params)' or a bsdf";
      if (c == "bsdf_furnace" && !u.reflects_both_sides())
        return "needs brdf too (E_R + E_T <= 1 reads the reflection on both sides): define brdf beside btdf, or "
               "one bsdf";
      if (c == "transmission_masking" && !(u.has_d && u.has_g1))
        return "needs D and 'float G1(float3 v, float3 m, const float* params)' (G1 asked for v below the surface)";
      if (k.runner == Runner::Integral && u.roughness < 0)
        return "needs a roughness parameter (the transmission estimators' proposal width)";
      return "";
    }
    if (!reflect && c != "d_norm" && c != "masking")
      return "needs 'float3 brdf(float3 wi, float3 wo, const float* params)' (the file defines btdf only)";
    if (c == "d_norm" && !u.has_d) return "needs 'float D(float3 m, const float* params)'";
    if (c == "masking" && !(u.has_d && u.has_g1))
      return "needs D and 'float G1(float3 v, float3 m, const float* params)'";
    if (c == "agree" && !claim) return "needs a claimed model (--as D/G/F)";
    if (c == "energy" && corners(u, u.defaults()).size() < 2) return "has no parameter besides the roughness to vary";
    return "";
  };
  if (checks.empty()) {
    for (auto& c : user_checks())
      if (available(c).empty()) checks.push_back(c);
  } else {
    for (auto& c : checks) {
      if (std::find(user_checks().begin(), user_checks().end(), c) == user_checks().end())
        throw Error(fmt::format("unknown check '{}' (mfv check runs: {})", c, fmt::join(user_checks(), ", ")));
      if (!available(c).empty()) throw Error(fmt::format("--check {}: {} {}", c, u.path, available(c)));
    }
  }
  if (opt.channels.empty()) throw Error("--channel: name at least one of r, g, b");
  SuiteOptions sopt = suite_options_of(opt);
  SuiteReport rep;
  rep.title = "mfv check " + u.path;
  rep.list_passes = true;
  double b0 = rt.build_stats().seconds;
  cl::Program prog = build_user_program(rt, u);
  // The double twin (user/user_twin.hpp): where the device has fp64 and the
  // file compiles in double; else the a-priori rounding bound alone.
  std::optional<cl::Program> twin;
  std::string twin_note = "no double twin (the device has no cl_khr_fp64)";
  if (rt.device().fp64) try {
      twin = build_user_program(rt, twin_of(u), true);
      twin_note = "double twin: the same code in double bounds each integral's float rounding (kf - kd)";
    } catch (const Error& e) {
      const std::string what = e.what();
      twin_note = "no double twin: the code does not compile in double (" + what.substr(0, what.find('\n')) + ")";
    }
  rep.reference_note =
      "reference: " + twin_note +
      (claim ? fmt::format("; check 'agree' compares it with {} ({}) pointwise", claim->spec, claim->mapping(u))
             : std::string("; claim a catalog model with --as D/G/F to compare pointwise"));
  if (u.claimed_width)
    rep.reference_note += "; the estimators take " + claim->d->id + "'s own proposal width (--as)";
  else if (u.roughness < 0)
    rep.reference_note += "; no roughness declared: the estimators use a mixture of widths 1, 1/4, ..., 1/256";
  rep.build_seconds = rt.build_stats().seconds - b0;
  Integrator in(rt, prog);
  // Each step's time limit (user/time_limit.hpp): 100x what a calibration
  // launch of the same code measures per evaluation, at least 30 s, so a
  // BRDF that never returns is stopped within a minute (docs/cli/check.md).
  const double per_eval = calibrate(in, u);
  auto arm = [&](double evals, const std::string& step) {
    watchdog_arm(std::max(kMinStepSeconds, 100.0 * per_eval * evals), step);
  };
  std::vector<Plan> plans = make_plans(u, opt, checks);
  // the per-integral threshold judge() will test at: the integrals are its tests
  size_t tests = 0;
  for (auto& plan : plans) tests += plan.specs.size();
  const double z = stats::per_integral_threshold(stats::split_family_alpha(sopt.family_alpha).per_integral, tests);
  for (auto& plan : plans) {
    arm(double(plan.samples) * double(plan.specs.size()), "the " + plan.check + " integrals");
    const size_t first = rep.points.size();
    run_plan(in, plan, sopt, rep);
    if (twin) {
      // kf - kd on the integrals' own first samples (streams set, stratified)
      std::vector<double> r = twin_rounding(rt, prog, *twin, plan.specs, kTwinSamples, opt.seed);
      for (size_t j = 0; j < r.size(); ++j) rep.points[first + j].rounding_bound = r[j];
    }
    // sized at the default sample count or above; fewer (--samples, --scale
    // below 1) asks for a quick look, each integral at that count
    if (check_kind(plan.check).upper_only && opt.scale >= 1.0) size_for_power(in, plan, rep, first, z, opt.seed, arm);
    if (shape_of(check_kind(plan.check)) == Shape::BsdfFlux) merge_flux_points(rep, first);
  }
  auto has = [&](const char* c) { return std::find(checks.begin(), checks.end(), c) != checks.end(); };
  // pointwise steps: a few thousand evaluations per setting (a bound of their count)
  const double settings = double(corners(u, u.defaults()).size()) * 16.0 * double(opt.channels.size());
  arm(settings * 4096 * 2, "the reciprocity pairs");
  if (has("reciprocity")) run_user_reciprocity(rt, prog, in, u, opt, rep);
  arm(settings * 4096 * 2, "the bsdf_reciprocity pairs");
  if (has("bsdf_reciprocity")) run_bsdf_reciprocity(rt, prog, u, opt, rep);
  arm(settings * 4096, "the finite census");
  if (has("finite")) run_census(rt, prog, u, opt, rep);
  arm(settings * 4096, "the agreement");
  if (has("agree")) run_agreement(rt, prog, twin ? &*twin : nullptr, u, *claim, opt, rep);
  watchdog_pause();
  mark_inconclusive(rep, 0);  // before the verdicts: neither pass nor fail (user/user_power.hpp)
  judge(rep, sopt);
  if (twin) explain_twin_verdicts(rep, rep.z_threshold);
  const std::string power = power_statement(rep);
  if (!power.empty()) rep.reference_note += "\n" + power;
  return rep;
}

}  // namespace mfv
