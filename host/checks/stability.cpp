#include "checks/stability.hpp"

#include "catalog/bsdfs.hpp"
#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "checks/pointwise_inputs.hpp"
#include "checks/stability_cases.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/integrator.hpp"
#include "runtime/work_group.hpp"
#include "util/error.hpp"
#include "util/math_constants.hpp"
#include "util/progress.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>

namespace mfv {

uint64_t StabilityCase::count(uint64_t RegionResult::*field, bool in_domain_only) const {
  uint64_t n = 0;
  for (auto& r : regions)
    if (r.in_domain || !in_domain_only) n += r.*field;
  return n;
}

double StabilityCase::max_ulps() const {
  double m = 0;
  for (auto& r : regions)
    if (r.in_domain) m = std::max(m, r.max_ulps);
  return m;
}

namespace {

using namespace stability_detail;

// ---- Evaluation ------------------------------------------------------------

// The first point of a region that shows a problem, as one line.
std::string point_line(const CaseDef& c, const In& in, double k, double ref) {
  return fmt::format("{} kernel={} reference={}", c.describe(in), hx(k), hx(ref));
}

// Finite kernel and reference: the error, the worst point, and whether it
// breaks (beyond kBreakUlps and the underflow floor, and beyond what the
// inputs' conditioning allows).
bool account_finite(RegionResult& R, const CaseDef& c, const In& in, double k, double ref, bool fp64) {
  const double big = fp64 ? std::numeric_limits<double>::max() : std::numeric_limits<float>::max();
  double diff = std::fabs(k - ref);
  // Results that are both below the smallest normal number (flushed or
  // gradual underflow) are not scored: ULPs of subnormals say nothing.
  bool subnormal = std::max(std::fabs(k), std::fabs(ref)) < min_normal(fp64);
  double ulps = subnormal ? 0.0 : diff / ulp_of(ref, fp64);
  double rel = subnormal || std::fabs(ref) < min_normal(fp64) ? 0.0 : diff / std::fabs(ref);
  R.max_rel = std::max(R.max_rel, rel);
  if (ulps > R.max_ulps || R.worst.empty()) {
    if (ulps > R.max_ulps) R.max_ulps = ulps;
    R.worst = point_line(c, in, k, ref);
  }
  if (!(ulps > kBreakUlps && diff > min_normal(fp64))) return false;
  // Conditioning allowance (checks/pointwise.hpp): each nonzero input moved
  // by one rounding; a reference beyond the format's range is skipped.
  auto moved = [&](int j, double b) {
    if (in[size_t(j)] == 0) return kNaN;
    In m = in;
    m[size_t(j)] *= 1.0 + b;
    double v = c.ref(m);
    return std::fabs(v) > big || !std::isfinite(v) ? kNaN : v;
  };
  return diff > 2.0 * input_sensitivity(kIn, 1.0, fp64, moved, ref);
}

// The prescribed value, negativity and G above 1: a value outside the
// domain where the reference stays inside.
void account_domain(RegionResult& R, const CaseDef& c, const In& in, double k, double ref) {
  bool wrong_value = false;
  if (!R.expect.empty()) {
    double e = R.expect == "1" ? 1.0 : 0.0;
    R.violations += !(k == e);
    R.ref_violations += !(ref == e);
    wrong_value = !(k == e) && ref == e;
  }
  const bool neg = k < 0 && ref >= 0;
  const bool is_g = c.mode == PW_G || c.mode == PW_G1;
  const bool above_one = is_g && k > 1 + kGOvershoot && !(ref > 1 + kGOvershoot);
  if (!std::isnan(k) && (wrong_value || neg || above_one)) {
    R.out_of_domain++;
    if (R.first_out_of_domain.empty())
      R.first_out_of_domain = point_line(c, in, k, ref) + (wrong_value ? " (expected " + R.expect + ")"
                                                           : neg       ? " (negative)"
                                                                       : " (G above 1)");
  }
}

void account(RegionResult& R, const CaseDef& c, const In& in, double k, double ref_exact, bool fp64) {
  R.points++;
  // A reference beyond the format's largest number is infinite in that format.
  const double big = fp64 ? std::numeric_limits<double>::max() : std::numeric_limits<float>::max();
  double ref =
      std::fabs(ref_exact) > big ? std::copysign(std::numeric_limits<double>::infinity(), ref_exact) : ref_exact;
  bool nan = std::isnan(k);
  bool inf = std::isinf(k) && std::isfinite(ref);
  bool neg = k < 0 && ref >= 0;
  R.nan += nan;
  R.inf += inf;
  R.negative += neg;
  bool inaccurate = false;
  if (std::isfinite(k) && std::isfinite(ref))
    inaccurate = account_finite(R, c, in, k, ref, fp64);
  else if (std::isinf(ref) && !nan && k != ref)
    inaccurate = true;  // the limit is infinite and the kernel is not
  account_domain(R, c, in, k, ref);
  if (nan || inf || neg || inaccurate) {
    R.breaks++;
    if (R.first_break.empty()) R.first_break = point_line(c, in, k, ref);
  }
}

// The records in the working precision T (pointwise layout, PW_VALUE
// pre-filled with NaN so an unwritten result cannot pass), evaluated by
// stability_eval; returns the values.
template <class T>
std::vector<double> run_kernel(Runtime& rt, cl::Kernel& kern, const CaseDef& c, const std::vector<In>& rounded) {
  // Launched in work-groups of one size (PoCL compiles a work-group function
  // per local size): 64, or what the device and kernel allow; the tail is
  // padded with zero records.
  const size_t kLocal = fit_local_size(kern, rt.device().device, 64);
  size_t n = (rounded.size() + kLocal - 1) / kLocal * kLocal;
  std::vector<T> rec(n * kIn, T(0));
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < kIn && i < rounded.size(); ++k) rec[i * kIn + k] = static_cast<T>(rounded[i][size_t(k)]);
    rec[i * kIn + PW_VALUE] = std::numeric_limits<T>::quiet_NaN();
  }
  cl::Buffer buf(rt.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, rec.size() * sizeof(T), rec.data());
  kern.setArg(0, static_cast<cl_int>(c.mode));
  kern.setArg(1, static_cast<cl_int>(c.model ? int(c.model->number()) : c.d ? term_index(*c.d) : 0));
  kern.setArg(2, static_cast<cl_int>(c.g ? term_index(*c.g) : 0));
  kern.setArg(3, static_cast<cl_int>(c.f_code >= 0 ? c.f_code : c.f ? term_index(*c.f) : 0));
  kern.setArg(4, static_cast<cl_int>(c.variant));
  kern.setArg(5, buf);
  rt.queue().enqueueNDRangeKernel(kern, cl::NullRange, cl::NDRange(n), cl::NDRange(kLocal));
  rt.queue().enqueueReadBuffer(buf, CL_TRUE, 0, rec.size() * sizeof(T), rec.data());
  std::vector<double> out(rounded.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = rec[i * kIn + PW_VALUE];
  return out;
}

std::vector<CaseDef> make_cases(const StabilityOptions& opt) {
  std::vector<CaseDef> cases;
  for (auto& t : catalog()) {
    cases.push_back(term_case(t, false, opt.fp64));
    if (!t.g1_kernel_fn.empty() && t.id != "smith_ggx_correlated")  // shares smith_ggx's G1
      cases.push_back(term_case(t, true, opt.fp64));
  }
  for (auto& v : variant_cases(opt.fp64)) cases.push_back(std::move(v));
  if (opt.combinations)
    for (auto* d : terms_of(Kind::D))
      for (auto* g : terms_of(Kind::G))
        for (auto* f : terms_of(Kind::F)) cases.push_back(brdf_case(*d, *g, *f, opt.fp64));
  // mfv stability --scene: the scene's models only (those with points), not
  // every model whose name the --only substrings happen to match
  auto scene_has = [&](const Model& m) {
    if (opt.model_points.empty()) return true;
    for (auto& [id, pts] : opt.model_points)
      if (id == m.id) return true;
    return false;
  };
  if (opt.models)
    for (auto& m : models())
      if (scene_has(m)) cases.push_back(model_case(m, opt));
  if (opt.combinations)
    for (auto& b : bsdfs()) {
      std::vector<std::array<double, 2>> pts;  // mfv stability --scene: the refracting materials' points
      for (auto& [id, p] : opt.bsdf_points)
        if (id == b.id) pts = p;
      cases.push_back(btdf_case(b, opt.fp64, pts));
    }
  if (!opt.only.empty()) {
    std::vector<CaseDef> kept;
    for (auto& c : cases)
      for (auto& o : opt.only)
        if (c.info.name.find(o) != std::string::npos) {
          kept.push_back(std::move(c));
          break;
        }
    if (kept.empty() && !opt.only_may_match_none)
      throw Error("--only matches no stability case (see 'mfv list'; variants are named 'variant ...')");
    cases = std::move(kept);
  }
  return cases;
}

// The program of the selected cases: only the terms they use (docs/design.md §5).
cl::Program build_stability_program(Runtime& rt, const std::vector<CaseDef>& cases, bool fp64) {
  TermSelection sel;
  auto add = [](std::vector<const Term*>& v, const Term* t) {
    if (t && std::find(v.begin(), v.end(), t) == v.end()) v.push_back(t);
  };
  for (auto& c : cases) {
    add(sel.d, c.d);
    add(sel.g, c.g);
    add(sel.f, c.f);
    if (c.model) sel.models.push_back(c.model);
  }
  sel.g1 = true;
  std::string dispatch = generate_dispatch(sel);
  bool any_smith = std::any_of(sel.g.begin(), sel.g.end(), [](const Term* t) { return !t->g1_kernel_fn.empty(); });
  if (!any_smith) dispatch += "static inline real eval_G1(int id, real NoV, real p) { return NAN; }\n";
  std::vector<std::string> defines;
  if (fp64) defines.push_back("MFV_DOUBLE");
  return rt.build(catalog_sources({"stability_variants.cl", "btdf.cl", "pointwise.cl", "stability.cl"}), defines, dispatch,
                  kDispatchBefore);
}

// The sweep's points rounded to the working precision; mode D's sin²θh is
// the caller's (1 - c)(1 + c) of the rounded cosine, in double, then rounded.
std::vector<In> rounded_points(const CaseDef& c, bool fp64) {
  std::vector<In> rounded(c.points.size());
  for (size_t i = 0; i < c.points.size(); ++i) {
    for (int k = 0; k < kIn; ++k) rounded[i][size_t(k)] = round_to(c.points[i].in[size_t(k)], fp64);
    if (c.mode == PW_D) {
      double cn = std::clamp(rounded[i][PW_NOH], -1.0, 1.0);
      rounded[i][PW_SIN2H] = round_to((1.0 - cn) * (1.0 + cn), fp64);
    }
  }
  return rounded;
}

// The gate: a case marked stable with NaN/Inf or out-of-domain values in an in-domain region.
void gate(const StabilityCase& sc, StabilityReport& rep) {
  if (!sc.stable) return;
  for (auto& r : sc.regions) {
    if (r.in_domain && (r.nan || r.inf))
      rep.gate_failures.push_back(
          fmt::format("{} is marked stable but gives {} NaN and {} Inf in region '{}'; first: {}", sc.name, r.nan,
                      r.inf, r.region, r.first_break));
    if (r.in_domain && r.out_of_domain)
      rep.gate_failures.push_back(
          fmt::format("{} is marked stable but gives {} of {} values outside the domain in "
                      "region '{}' where the reference stays inside; first: {}",
                      sc.name, r.out_of_domain, r.points, r.region, r.first_out_of_domain));
  }
}

// One case: its points on the device, then each against the reference.
void run_case(Runtime& rt, cl::Kernel& kern, const CaseDef& c, bool fp64, StabilityReport& rep) {
  std::vector<In> rounded = rounded_points(c, fp64);
  auto t0 = std::chrono::steady_clock::now();
  std::vector<double> values =
      fp64 ? run_kernel<cl_double>(rt, kern, c, rounded) : run_kernel<cl_float>(rt, kern, c, rounded);
  auto t1 = std::chrono::steady_clock::now();
  StabilityCase sc = c.info;
  for (auto& r : c.regions) {
    RegionResult rr;
    rr.region = r.name;
    rr.what = r.what;
    rr.in_domain = r.in_domain;
    rr.expect = r.expect;
    sc.regions.push_back(rr);
  }
  ScanSeries scan{sc.name, {}};
  for (size_t i = 0; i < c.points.size(); ++i) {
    double ref = c.ref(rounded[i]);
    account(sc.regions[size_t(c.points[i].region)], c, rounded[i], values[i], ref, fp64);
    if (!std::isnan(c.points[i].theta))
      scan.points.push_back({c.points[i].theta, c.points[i].alpha, sweep_ulps(values[i], ref, fp64)});
  }
  auto t2 = std::chrono::steady_clock::now();
  rep.kernel_seconds += std::chrono::duration<double>(t1 - t0).count();
  rep.reference_seconds += std::chrono::duration<double>(t2 - t1).count();
  rep.points += c.points.size();
  gate(sc, rep);
  if (!scan.points.empty()) rep.scans.push_back(std::move(scan));
  rep.cases.push_back(std::move(sc));
}

}  // namespace

UnitPlan stability_plan(const StabilityOptions& opt) {
  UnitPlan plan;
  PlanDigest d;
  for (const CaseDef& c : make_cases(opt)) {
    const StabilityCase& i = c.info;
    d.text(i.name), d.text(i.group), d.text(i.family), d.text(i.formula), d.value(i.stable), d.value(i.is_default);
    d.value(int(c.mode)), d.value(c.variant), d.value(c.f_code);
    for (auto& r : c.regions) d.text(r.name), d.text(r.what), d.value(r.in_domain), d.text(r.expect);
    for (auto& p : c.points) d.value(p.in), d.value(p.region), d.value(p.theta), d.value(p.alpha);
    plan.cost.push_back(c.points.size());
  }
  d.value(opt.fp64);
  plan.hash = d.hex();
  return plan;
}

StabilityReport merge_stability(const std::vector<StabilityReport>& parts) {
  StabilityReport rep;
  if (parts.empty()) return rep;
  const StabilityReport& first = parts.front();
  rep.device = first.device, rep.platform = first.platform, rep.driver = first.driver;
  rep.precision = first.precision, rep.build_options = first.build_options;
  for (const StabilityReport& p : parts) {
    for (auto& c : p.cases) {
      gate(c, rep);
      rep.cases.push_back(c);
    }
    rep.scans.insert(rep.scans.end(), p.scans.begin(), p.scans.end());
    rep.points += p.points;
    rep.build_seconds += p.build_seconds, rep.kernel_seconds += p.kernel_seconds;
    rep.reference_seconds += p.reference_seconds, rep.total_seconds += p.total_seconds;
  }
  return rep;
}

StabilityReport run_stability(Runtime& rt, const StabilityOptions& opt, std::pair<size_t, size_t> part) {
  auto t_start = std::chrono::steady_clock::now();
  if (opt.fp64 && !rt.device().fp64)
    throw Error(fmt::format("device '{}' has no cl_khr_fp64; run without --fp64", rt.device().name));
  auto cases = make_cases(opt);
  StabilityReport rep;
  if (cases.empty()) return rep;  // only_may_match_none
  rep.device = rt.device().name;
  rep.platform = rt.device().platform;
  rep.driver = rt.device().driver;
  rep.precision = opt.fp64 ? "float64" : "float32";
  rep.build_options = rt.base_options() + (opt.fp64 ? " -DMFV_DOUBLE" : "");
  auto build0 = rt.build_stats().seconds;
  cl::Program prog = build_stability_program(rt, cases, opt.fp64);
  rep.build_seconds = rt.build_stats().seconds - build0;
  cl::Kernel kern(prog, "stability_eval");
  const size_t hi = std::min(part.second, cases.size()), lo = std::min(part.first, hi);
  progress::Task task("stability: cases", hi - lo);
  for (size_t i = lo; i < hi; ++i) {
    task.advance(1);
    run_case(rt, kern, cases[i], opt.fp64, rep);
  }
  rep.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return rep;
}

}  // namespace mfv
