#include "checks/convergence.hpp"

#include "catalog/catalog.hpp"
#include "catalog/roughness.hpp"
#include "checks/chi_square.hpp"
#include "checks/integrate.hpp"
#include "numeric/hemisphere_quadrature.hpp"
#include "numeric/quadrature.hpp"
#include "reference/brdf.hpp"
#include "reference/estimators.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace mfv {
namespace {

const std::vector<std::string> kChecks = {"d_norm", "albedo", "furnace"};
const std::vector<std::string> kEstimators = {"uniform", "cosine", "mis", "dsample", "vndf", "rqmc", "quadrature"};
const double kTolerances[] = {1e-3, 1e-4, 1e-5};
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Below this the device's float evaluation (~1e-7 relative) and not the
// estimator sets the error, so slopes are fitted above it.
constexpr double kFloatFloor = 3e-7;

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// The BRDF of a case: GGX with the height-correlated Smith G (Heitz 2014
// eq. 99), Beckmann with its exact separable Smith G (the catalog has no
// correlated Beckmann G); Schlick F0 = 0.04, or F = 1 for the furnace.
IntegralSpec spec_of(const std::string& check, const ConvergenceCase& c) {
  const Term& d = find_term(c.d);
  const Term& g = find_term(c.d == "ggx" ? "smith_ggx_correlated" : "smith_beckmann");
  const Term& f = find_term(check == "furnace" ? "none" : "schlick");
  IntegralSpec s;
  s.check = static_cast<int32_t>(check == "d_norm" ? IntegralKind::DNorm : IntegralKind::Albedo);
  s.d = term_index(d);
  s.g = term_index(g);
  s.f = term_index(f);
  s.pd = float(native_from_alpha(d.roughness, c.alpha));
  s.pg = float(native_from_alpha(g.roughness, c.alpha));
  s.f0 = 0.04f;
  s.width = float(c.alpha);
  s.cos_o = float(c.cos_o);
  return s;
}

// The truth: d_norm = 1 by the normalization of GGX and Beckmann (Walter et
// al. 2007 eq. 4); the albedo by the product rule at two refinements, on the
// float parameters the device sees.
ConvergenceTruth truth_of(const std::string& check, const ConvergenceCase& c) {
  const ref::IntegralRef r = reference_of(spec_of(check, c));
  const ProductRule fine{16, 4, 8}, coarse{12, 3, 6};
  ConvergenceTruth t;
  if (check == "d_norm") {
    t.value = 1.0;
    t.method = "closed form (D is normalized)";
    t.quadrature_check =
        integrate_normals([&](const glm::dvec3& m) { return r.brdf.d->ref_d(m.z, r.brdf.pd) * m.z; }, fine).value;
    return t;
  }
  const glm::dvec3 o(std::sqrt((1.0 - r.cos_o) * (1.0 + r.cos_o)), 0.0, r.cos_o);
  auto f = [&](const glm::dvec3& i) { return ref::brdf(r.brdf, i, o) * i.z; };
  const double hi = integrate_reflected(f, o, fine).value, lo = integrate_reflected(f, o, coarse).value;
  t.value = hi;
  t.error = std::fabs(hi - lo);
  t.method =
      "product Gauss-Legendre over half vectors (order 16, 4 panels/decade, 8 phi panels; error vs "
      "order 12, 3/decade, 6 phi panels)";
  return t;
}

// Per-replicate estimates of one run each -> a level.
ConvergenceLevel level_of(uint64_t n, const std::vector<double>& est, const std::vector<double>& se, bool rqmc,
                          double truth, double seconds) {
  ConvergenceLevel l;
  l.n = n;
  l.seconds = seconds;
  const size_t R = est.size();
  double sum = 0, sq = 0, se2 = 0;
  for (size_t r = 0; r < R; ++r) {
    sum += est[r];
    sq += (est[r] - truth) * (est[r] - truth);
    se2 += se[r] * se[r];
  }
  l.mean = sum / R;
  l.rmse = std::sqrt(sq / R);
  if (rqmc) {
    double v = 0;
    for (double e : est) v += (e - l.mean) * (e - l.mean);
    l.est_se = R > 1 ? std::sqrt(v / (R - 1)) : kNaN;
  } else {
    l.est_se = std::sqrt(se2 / R);
  }
  return l;
}

void fit_slope(ConvergenceSeries& s, double floor) {
  const size_t L = s.levels.size();
  s.fit_from = L >= 6 ? L / 2 : 0;  // the upper half of the sweep: the asymptotic regime
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (size_t k = s.fit_from; k < L; ++k) {
    const auto& l = s.levels[k];
    if (!(l.rmse >= floor) || !std::isfinite(l.rmse)) continue;
    const double x = std::log(double(l.n)), y = std::log(l.rmse);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++n;
  }
  s.slope = n >= 2 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : kNaN;
}

void find_reach(ConvergenceSeries& s) {
  for (double tol : kTolerances) {
    ToleranceReach t{tol, kNaN, kNaN, false};
    // the first level from which every measured error stays at or below tol
    for (size_t k = s.levels.size(); k-- > 0;) {
      if (!(s.levels[k].rmse <= tol)) break;
      t.n = double(s.levels[k].n);
      t.seconds = s.levels[k].seconds;
    }
    // Extrapolated: error ≈ rmse_last (n / n_last)^slope, time proportional
    // to n. iid MC converges as n^-1/2 once the variance is finite (the CLT),
    // which a slope fitted on a few noisy points only approximates; RQMC at
    // its fitted slope but never slower than MC. Quadrature is not extrapolated.
    const double slope = s.estimator == "rqmc" ? std::min(s.slope, -0.5) : -0.5;
    if (std::isnan(t.n) && !s.levels.empty() && s.estimator != "quadrature" && std::isfinite(s.slope)) {
      const auto& last = s.levels.back();
      t.n = double(last.n) * std::pow(last.rmse / tol, -1.0 / slope);
      t.seconds = last.seconds * t.n / double(last.n);
      t.extrapolated = true;
    }
    s.reach.push_back(t);
  }
}

}  // namespace

std::string ConvergenceCase::name() const { return fmt::format("{} a={:g} cos={:g}", d, alpha, cos_o); }

std::vector<ConvergenceCase> default_convergence_cases() {
  std::vector<ConvergenceCase> c;
  for (const char* d : {"ggx", "beckmann"})
    for (double a : {1e-3, 1e-2, 0.1, 0.5})
      for (double co : {1.0, 0.05}) c.push_back({d, a, co});
  return c;
}

ConvergenceCase parse_convergence_case(const std::string& text) {
  ConvergenceCase c;
  const size_t a = text.find(':'), b = a == std::string::npos ? a : text.find(':', a + 1);
  if (b == std::string::npos || text.find(':', b + 1) != std::string::npos)
    throw Error(fmt::format("--case '{}': expected D:ALPHA:COS, e.g. ggx:0.01:0.05", text));
  c.d = text.substr(0, a);
  auto number = [&](const std::string& s, const char* what) {
    size_t used = 0;
    double v = kNaN;
    try {
      v = std::stod(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != s.size() || s.empty()) throw Error(fmt::format("--case '{}': {} '{}' is not a number", text, what, s));
    return v;
  };
  c.alpha = number(text.substr(a + 1, b - a - 1), "alpha");
  c.cos_o = number(text.substr(b + 1), "cos");
  return c;
}

bool estimator_applies(const std::string& estimator, const std::string& check) {
  // Sampling by D or by visible normals makes D normalization a tautology:
  // the weight D c / (D c) is 1 for every sample (docs/design.md §3).
  return check != "d_norm" || (estimator != "dsample" && estimator != "vndf");
}

uint32_t estimator_id(const std::string& e, const ConvergenceCase& c) {
  using E = ref::Estimator;
  E id = E::Own;
  if (e == "uniform") id = E::Uniform;
  if (e == "cosine") id = E::Cosine;
  if (e == "dsample") id = c.d == "beckmann" ? E::DSampleBeckmann : E::DSampleGgx;
  if (e == "vndf") id = E::Vndf;
  if (e == "rqmc") id = E::Rqmc;
  return static_cast<uint32_t>(id);
}

void validate_convergence_options(const ConvergenceOptions& opt) {
  for (auto& c : opt.checks)
    if (!contains(kChecks, c))
      throw Error(fmt::format("unknown check '{}' (convergence checks: {})", c, join(kChecks)));
  for (auto& e : opt.estimators)
    if (!contains(kEstimators, e))
      throw Error(fmt::format("unknown estimator '{}' (estimators: {})", e, join(kEstimators)));
  for (auto& c : opt.cases) {
    if (c.d != "ggx" && c.d != "beckmann")
      throw Error(fmt::format("case '{}': unknown D '{}' (convergence cases use ggx or beckmann)", c.name(), c.d));
    if (!(c.alpha >= 1e-4 && c.alpha <= 1.0))
      throw Error(fmt::format("case '{}': alpha {} out of range [1e-4, 1]", c.name(), c.alpha));
    if (!(c.cos_o >= 1e-3 && c.cos_o <= 1.0))
      throw Error(fmt::format("case '{}': cos {} out of range [1e-3, 1]", c.name(), c.cos_o));
  }
  if (opt.min_log2 < 7 || opt.max_log2 > 26 || opt.min_log2 > opt.max_log2)
    throw Error(fmt::format("--min-log2 {} / --max-log2 {}: need 7 <= min <= max <= 26", opt.min_log2, opt.max_log2));
  if (opt.ref_max_log2 < 0 || opt.ref_max_log2 > 26)
    throw Error(fmt::format("--ref-max-log2 {}: must be 0..26", opt.ref_max_log2));
  if (opt.replicates < 2 || opt.replicates > 256)
    throw Error(fmt::format("--replicates {}: must be 2..256", opt.replicates));
  if (opt.quad_max_order < 2 || opt.quad_max_order > 64)
    throw Error(fmt::format("--quad-max-order {}: must be 2..64", opt.quad_max_order));
}

double t_two_sided_p(double t, int dof) {
  t = std::fabs(t);
  if (std::isnan(t)) return kNaN;
  if (dof <= 0) return std::erfc(t / std::sqrt(2.0));
  if (t == 0) return 1.0;
  // ∫_t^∞ c (1 + x²/ν)^(-(ν+1)/2) dx with x = t/u: smooth on u ∈ (0, 1] for ν >= 1
  const double nu = dof;
  const double c = std::exp(std::lgamma(0.5 * (nu + 1)) - std::lgamma(0.5 * nu)) / std::sqrt(nu * M_PI);
  static const GaussRule gl = gauss_legendre(64);
  double tail = 0;
  for (int p = 0; p < 8; ++p)  // 8 panels in u
    for (size_t i = 0; i < gl.x.size(); ++i) {
      const double u = (p + 0.5 * (gl.x[i] + 1.0)) / 8.0;
      const double x = t / u;
      tail += gl.w[i] / 16.0 * c * std::pow(1.0 + x * x / nu, -0.5 * (nu + 1)) * t / (u * u);
    }
  return std::min(1.0, 2.0 * tail);
}

namespace {

// Every check needs an estimator that applies to it.
void require_an_estimator(const std::vector<std::string>& checks, const std::vector<std::string>& ests) {
  for (auto& ch : checks) {
    bool any = false;
    for (auto& e : ests) any = any || estimator_applies(e, ch);
    if (!any)
      throw Error(
          fmt::format("no estimator of '{}' applies to {}: dsample and vndf sample by the D under test, which "
                      "makes D normalization a tautology",
                      join(ests), ch));
  }
}

// The terms of the convergence cases (GGX and Beckmann with their Smith G), built once.
TermSelection convergence_terms() {
  TermSelection sel;
  for (const char* id : {"ggx", "beckmann", "smith_ggx_correlated", "smith_beckmann", "schlick", "none"}) {
    const Term& t = find_term(id);
    (t.kind == Kind::D ? sel.d : t.kind == Kind::G ? sel.g : sel.f).push_back(&t);
  }
  return sel;
}

// One series per case of a check and estimator on one engine, no levels yet.
std::vector<ConvergenceSeries> empty_series(const std::string& ch, const std::string& est, const char* engine,
                                            size_t C) {
  std::vector<ConvergenceSeries> out(C);
  for (size_t k = 0; k < C; ++k) {
    out[k].check = ch;
    out[k].estimator = est;
    out[k].engine = engine;
    out[k].case_index = k;
  }
  return out;
}

// The deterministic quadrature "estimator": orders 2..quad_max_order of the
// product rule, 2 panels a decade, 4 φ panels; each level's est_se is its
// change from the previous order.
void quadrature_levels(const ConvergenceReport& rep, size_t ci, std::vector<ConvergenceSeries>& ref) {
  const std::string& ch = rep.checks[ci];
  for (size_t k = 0; k < rep.cases.size(); ++k) {
    const ref::IntegralRef r = reference_of(spec_of(ch, rep.cases[k]));
    const glm::dvec3 o(std::sqrt((1.0 - r.cos_o) * (1.0 + r.cos_o)), 0.0, r.cos_o);
    double prev = kNaN;
    for (int q = 2; q <= rep.opt.quad_max_order; q += q < 6 ? 1 : 2) {
      const double t0 = now();
      const ProductRule rule{q, 2, 4};
      const QuadratureResult qr =
          ch == "d_norm"
              ? integrate_normals([&](const glm::dvec3& m) { return r.brdf.d->ref_d(m.z, r.brdf.pd) * m.z; }, rule)
              : integrate_reflected([&](const glm::dvec3& i) { return ref::brdf(r.brdf, i, o) * i.z; }, o, rule);
      ConvergenceLevel l;
      l.n = uint64_t(qr.evaluations);
      l.seconds = now() - t0;
      l.mean = qr.value;
      l.rmse = std::fabs(qr.value - rep.truth[ci][k].value);
      l.est_se = std::fabs(qr.value - prev);
      prev = qr.value;
      ref[k].levels.push_back(l);
    }
  }
}

// The double reference's level for case k on the same `used` samples of the
// same R integrals as the device's (specs, seed).
ConvergenceLevel reference_level(const ConvergenceReport& rep, size_t ci, size_t k,
                                 const std::vector<IntegralSpec>& specs, uint64_t used, uint64_t seed, bool rqmc) {
  const int R = rep.opt.replicates;
  std::vector<double> e(R), se(R);
  const double t1 = now();
  for (int r = 0; r < R; ++r) {
    const ref::IntegralRef rr = reference_of(specs[k * R + r]);
    double sum = 0, sq = 0;
    for (uint64_t j = 0; j < used; j += (rr.strata ? 2 : 1)) {
      const double v = ref::sample_value(rr, seed, j);
      if (rr.strata) {  // neighbouring strata in pairs, as the kernel
        const double v1 = ref::sample_value(rr, seed, j + 1);
        sum += v + v1;
        sq += (v - v1) * (v - v1);
      } else {
        sum += v;
        sq += v * v;
      }
    }
    e[r] = sum / double(used);
    se[r] = rr.strata ? std::sqrt(sq) / double(used)
                      : std::sqrt(std::max(0.0, sq / double(used) - e[r] * e[r]) / double(used - 1));
  }
  return level_of(used, e, se, rqmc, rep.truth[ci][k].value, (now() - t1) / R);
}

// Slopes, tolerances, consistency (Sidak over every tested series, family-wise 1e-3).
void judge_series(ConvergenceReport& rep) {
  const int R = rep.opt.replicates;
  int tested = 0;
  for (auto& s : rep.series) tested += s.estimator != "quadrature" && !s.levels.empty();
  rep.level = sidak_level(1e-3, std::max(1, tested));
  for (auto& s : rep.series) {
    const size_t ci = size_t(std::find(rep.checks.begin(), rep.checks.end(), s.check) - rep.checks.begin());
    const ConvergenceTruth& tr = rep.truth[ci][s.case_index];
    fit_slope(s, s.estimator == "quadrature" ? 1e-13 : std::max(kFloatFloor * std::fabs(tr.value), 4 * tr.error));
    find_reach(s);
    if (s.estimator == "quadrature" || s.levels.empty()) {
      s.z = s.p = kNaN;
      continue;
    }
    const auto& l = s.levels.back();
    // the device's float evaluation biases by up to ~kFloatFloor relative,
    // which no sample spread shows: part of the allowed deviation there
    const double fl = s.engine == "device" ? kFloatFloor * std::fabs(tr.value) : 0.0;
    const double se = std::sqrt(l.est_se * l.est_se / R + tr.error * tr.error + fl * fl);
    s.z = se > 0 ? (l.mean - tr.value) / se : (l.mean == tr.value ? 0.0 : INFINITY);
    s.p = t_two_sided_p(s.z, s.estimator == "rqmc" ? R - 1 : 0);
    s.consistent = !(s.p < rep.level);
  }
}

// The target: GGX alpha = 0.01 at grazing view (cos 0.05), albedo, 1e-4 absolute, on the device.
void measure_target(ConvergenceReport& rep) {
  const size_t albedo = size_t(std::find(rep.checks.begin(), rep.checks.end(), "albedo") - rep.checks.begin());
  for (auto& s : rep.series) {
    const ConvergenceCase& c = rep.cases[s.case_index];
    if (s.check != "albedo" || s.engine != "device" || c.d != "ggx" || std::fabs(c.alpha - 0.01) > 1e-12 ||
        std::fabs(c.cos_o - 0.05) > 1e-12 || albedo >= rep.checks.size())
      continue;
    const ToleranceReach& t = s.reach[1];
    if (s.estimator == "uniform") {
      // the exact variance of the uniform estimator, 2π ∫ (f cos)² dω - E², by the truth's quadrature
      const ref::IntegralRef r = reference_of(spec_of("albedo", c));
      const glm::dvec3 o(std::sqrt((1.0 - r.cos_o) * (1.0 + r.cos_o)), 0.0, r.cos_o);
      const double m2 = integrate_reflected(
                            [&](const glm::dvec3& i) {
                              const double v = ref::brdf(r.brdf, i, o) * i.z;
                              return 2.0 * M_PI * v * v;
                            },
                            o, ProductRule{16, 4, 8})
                            .value;
      const double e = rep.truth[albedo][s.case_index].value;
      rep.target.uniform_variance = m2 - e * e;
      rep.target.uniform_n_variance = rep.target.uniform_variance / 1e-8;
      rep.target.uniform_n = t.n;
      rep.target.uniform_extrapolated = t.extrapolated;
      const auto& last = s.levels.back();  // CLT: se(n) = est_se (n_last / n)^(1/2)
      rep.target.uniform_n_clt = double(last.n) * (last.est_se / 1e-4) * (last.est_se / 1e-4);
    } else if (std::isfinite(t.n) && (rep.target.best.empty() || t.n < rep.target.best_n)) {
      rep.target.best = s.estimator;
      rep.target.best_n = t.n;
      rep.target.best_extrapolated = t.extrapolated;
    }
  }
  rep.target.measured = !rep.target.best.empty() && rep.target.uniform_n > 0;
  if (rep.target.measured) rep.target.ratio = rep.target.uniform_n_variance / rep.target.best_n;
}

}  // namespace

ConvergenceReport run_convergence(Runtime& rt, const ConvergenceOptions& opt_in) {
  validate_convergence_options(opt_in);
  const double t_start = now();
  ConvergenceReport rep;
  rep.opt = opt_in;
  const auto& opt = rep.opt;
  rep.cases = opt.cases.empty() ? default_convergence_cases() : opt.cases;
  rep.checks = opt.checks.empty() ? std::vector<std::string>{"d_norm", "albedo"} : opt.checks;
  const std::vector<std::string> ests = opt.estimators.empty() ? kEstimators : opt.estimators;
  require_an_estimator(rep.checks, ests);
  rep.device = rt.device().name;
  rep.platform = rt.device().platform;
  rep.date = utc_timestamp();
  const size_t C = rep.cases.size();
  const int R = opt.replicates;

  for (auto& ch : rep.checks) {
    std::vector<ConvergenceTruth> row;
    for (auto& c : rep.cases) row.push_back(truth_of(ch, c));
    rep.truth.push_back(row);
  }

  Integrator in(rt, convergence_terms());

  for (size_t ci = 0; ci < rep.checks.size(); ++ci) {
    const std::string& ch = rep.checks[ci];
    for (size_t ei = 0; ei < ests.size(); ++ei) {
      const std::string& est = ests[ei];
      if (!estimator_applies(est, ch)) continue;
      const bool rqmc = est == "rqmc";
      std::vector<ConvergenceSeries> dev = empty_series(ch, est, "device", C),
                                     ref = empty_series(ch, est, "reference", C);
      if (est == "quadrature") {
        quadrature_levels(rep, ci, ref);
        for (auto& s : ref) rep.series.push_back(s);
        continue;
      }
      for (int lg = opt.min_log2; lg <= opt.max_log2; ++lg) {
        const uint64_t n = uint64_t(1) << lg;
        const uint64_t seed = opt.seed + uint64_t(lg) * 0x9E3779B97F4A7C15ull;  // independent runs per level
        std::vector<IntegralSpec> specs;
        for (size_t k = 0; k < C; ++k)
          for (int r = 0; r < R; ++r) {
            IntegralSpec s = spec_of(ch, rep.cases[k]);
            s.estimator = estimator_id(est, rep.cases[k]);
            s.stream = uint32_t(((ci * kEstimators.size() + ei) * C + k) * R + r);
            specs.push_back(s);
          }
        const double t0 = now();
        const std::vector<Estimate> es = in.run(specs, n, seed);
        const double per_run = (now() - t0) / double(specs.size());
        const uint64_t used = es.front().samples;
        for (size_t k = 0; k < C; ++k) {
          std::vector<double> e(R), se(R);
          for (int r = 0; r < R; ++r) {
            e[r] = es[k * R + r].mean;
            se[r] = es[k * R + r].stderr_;
          }
          dev[k].levels.push_back(level_of(used, e, se, rqmc, rep.truth[ci][k].value, per_run));
        }
        if (!opt.reference || lg > opt.ref_max_log2) continue;
        in.stratify(specs, n);  // the own d_norm estimator is stratified over its n samples
        for (size_t k = 0; k < C; ++k) ref[k].levels.push_back(reference_level(rep, ci, k, specs, used, seed, rqmc));
      }
      for (auto& s : dev) rep.series.push_back(s);
      for (auto& s : ref)
        if (!s.levels.empty()) rep.series.push_back(s);  // none where ref_max_log2 < min_log2
    }
  }

  judge_series(rep);
  measure_target(rep);
  rep.seconds = now() - t_start;
  return rep;
}

std::string ConvergenceTarget::line() const {
  if (!measured)
    return "target (GGX alpha = 0.01, cos 0.05, albedo, 1e-4): not measured (needs that case with uniform and "
           "another estimator on the device)";
  return fmt::format(
      "target (GGX alpha = 0.01, cos 0.05, albedo, 1e-4 absolute RMS error): best estimator {} needs {:.3g} samples "
      "({}); uniform needs {:.3g} = variance {:.4g} / 1e-8 (the exact variance of the uniform estimator, by "
      "quadrature; extrapolating its last measured error at n^-1/2 gives {:.3g}, its estimated standard error "
      "{:.3g}: it has not found the lobe yet); ratio {:.3g}x ({} the 100x target)",
      best, best_n, best_extrapolated ? "extrapolated" : "measured", uniform_n_variance, uniform_variance, uniform_n,
      uniform_n_clt, ratio, ratio >= 100 ? "meets" : "misses");
}

}  // namespace mfv
