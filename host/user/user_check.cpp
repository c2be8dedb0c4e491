#include "user/user_check.hpp"

#include "catalog/roughness.hpp"
#include "checks/stability.hpp"
#include "rng/philox.hpp"
#include "runtime/error.hpp"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace mfv {

const std::vector<std::string>& user_checks() {
  static const std::vector<std::string> c = {"d_norm", "masking", "furnace", "energy", "reciprocity", "finite", "agree"};
  return c;
}

SuiteOptions suite_options_of(const UserCheckOptions& o) {
  SuiteOptions s;
  s.seed = o.seed;
  s.scale = o.scale;
  s.family_alpha = o.family_alpha;
  s.checks = o.checks;
  s.reference_samples = 0;  // no double twin of user code; `agree` compares with a claimed model instead
  return s;
}

namespace {

using Values = std::vector<double>;  // one value per user parameter
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// ---- the program -------------------------------------------------------------

// integrate.cl with the user's file and the adapters after it: one build for
// every check. A compile error leads with its first line in the user's file.
cl::Program build_user_program(Runtime& rt, const UserBrdf& u) {
  std::vector<std::string> defines = {"MFV_USER_BRDF", fmt::format("MFV_USER_NPARAMS={}", u.params.size())};
  if (rt.device().fp64) defines.push_back("MFV_ACC_DOUBLE");
  if (u.has_d) defines.push_back("MFV_USER_HAS_D");
  if (u.has_g1) defines.push_back("MFV_USER_HAS_G1");
  try {
    // no catalog terms or models: the user's names must not clash with them
    std::vector<std::string> files = {"common.cl", "rng.cl", kDispatchBefore};
    for (auto& f : integration_files()) files.push_back(f);
    for (const char* f : {"user_guard.cl", "user_brdf.cl"}) files.push_back(f);
    return rt.build(files, defines,
                    generate_dispatch(TermSelection{}), kDispatchBefore, {{u.path, u.guarded_text, "user_brdf.cl"}});
  } catch (const Error& e) {
    std::string log = e.what(), first;
    size_t errors = 0;
    std::istringstream lines(log);
    // clang writes "FILE:L:C: error: what"; PoCL's log, "error: FILE:L:C: what"
    for (std::string line; std::getline(lines, line);) {
      bool pocl = line.rfind("error: ", 0) == 0;
      if (!pocl && line.find(": error: ") == std::string::npos) continue;
      ++errors;
      if (pocl) line = line.substr(7);
      if (first.empty() && line.rfind(u.path + ":", 0) == 0) first = line;
    }
    if (first.empty()) first = fmt::format("{} does not compile", u.path);
    throw Error(fmt::format("{} ({} error{}; the build log follows)\n{}", first, errors, errors == 1 ? "" : "s", log));
  }
}

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
  float* p[kUserMaxParams] = {&s.pd, &s.pg, &s.f0, &s.f1, &s.kd, &s.p5};
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

const char* kChannel = "rgb";

// ---- integrals -----------------------------------------------------------------

std::vector<Plan> make_plans(const UserBrdf& u, const UserCheckOptions& opt, const std::vector<std::string>& checks) {
  auto wanted = [&](const char* c) { return std::find(checks.begin(), checks.end(), c) != checks.end(); };
  std::vector<Plan> plans;
  auto add = [&](Plan& plan, IntegralKind kind, const Values& v, double co, int ch, bool upper) {
    plan.specs.push_back(user_spec(u, kind, v, co, ch));
    PointResult p = point_of(u, plan.check, v);
    if (kind != IntegralKind::DNorm) p.params["cos_o"] = co;
    if (ch >= 0 && kind == IntegralKind::Albedo) p.params["channel"] = ch;  // 0 r, 1 g, 2 b
    p.expected = 1.0;
    p.upper_only = upper;
    plan.points.push_back(p);
  };
  if (wanted("d_norm")) {
    Plan p = new_plan("d_norm", check_row("d_norm").base_samples, opt.scale);
    for (auto& v : roughness_grid(u, suite_norm_alphas(), 64)) add(p, IntegralKind::DNorm, v, 1.0, 0, false);
    plans.push_back(p);
  }
  if (wanted("masking")) {
    Plan p = new_plan("masking", check_row("masking").base_samples, opt.scale);
    for (auto& v : roughness_grid(u, suite_alphas(), 64))
      for (double co : view_cosines(32)) add(p, IntegralKind::Masking, v, co, 0, false);
    plans.push_back(p);
  }
  if (wanted("furnace")) {
    // The budget of the full width grid whatever the file declares: a BRDF
    // with fewer widths (none: Lambert) gets more samples per integral, so
    // that the pooled test finds a 1 % gain (docs/statistics.md).
    const auto grid = roughness_grid(u, suite_alphas(), 64);
    const double share = double(suite_alphas().size()) / double(std::max<size_t>(grid.size(), 1));
    Plan p = new_plan("furnace", uint64_t(double(check_row("furnace").base_samples) * std::max(1.0, share)), opt.scale);
    for (auto& v : grid)
      for (double co : view_cosines(32))
        for (int ch : opt.channels) add(p, IntegralKind::Albedo, v, co, ch, true);
    plans.push_back(p);
  }
  if (wanted("energy")) {
    Plan p = new_plan("energy", check_row("energy").base_samples, opt.scale);
    for (auto& r : roughness_grid(u, suite_alphas(), 6))
      for (auto& v : corners(u, r))
        for (double co : view_cosines(16))
          for (int ch : opt.channels) add(p, IntegralKind::Albedo, v, co, ch, true);
    plans.push_back(p);
  }
  return plans;
}

// Census and agreement inputs for kernels/user_brdf.cl user_eval.
constexpr int kIn = 16, kOut = 6;
struct Record {
  glm::dvec3 wi, wo, m;
  bool has_m = false;  // m is a half vector or a normal the D and G1 census may use
  std::string region;
  size_t setting = 0;  // index of its parameter values
};

std::vector<float> eval_records(Runtime& rt, const cl::Program& prog, const std::vector<Record>& recs,
                                const std::vector<Values>& settings) {
  std::vector<float> in(recs.size() * kIn, 0.0f), out(recs.size() * kOut);
  if (recs.empty()) return out;
  for (size_t i = 0; i < recs.size(); ++i) {
    float* r = &in[i * kIn];
    const Record& x = recs[i];
    double v[9] = {x.wi.x, x.wi.y, x.wi.z, x.wo.x, x.wo.y, x.wo.z, x.m.x, x.m.y, x.m.z};
    for (int k = 0; k < 9; ++k) r[k] = float(v[k]);
    const Values& s = settings[x.setting];
    for (size_t k = 0; k < s.size(); ++k) r[9 + k] = float(s[k]);
  }
  cl::Kernel k(prog, "user_eval");
  cl::Buffer ib(rt.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, in.size() * sizeof(float), in.data());
  cl::Buffer ob(rt.context(), CL_MEM_WRITE_ONLY, out.size() * sizeof(float));
  k.setArg(0, ib);
  k.setArg(1, ob);
  rt.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(recs.size()));
  rt.queue().enqueueReadBuffer(ob, CL_TRUE, 0, out.size() * sizeof(float), out.data());
  return out;
}

glm::dvec3 as_float(const glm::dvec3& v) { return glm::dvec3(float(v.x), float(v.y), float(v.z)); }
std::string vec_text(const glm::dvec3& v) { return fmt::format("({:.9g}, {:.9g}, {:.9g})", float(v.x), float(v.y), float(v.z)); }

// The half vector in double, where both directions are above the horizon and it exists.
bool half_vector(const glm::dvec3& wi, const glm::dvec3& wo, glm::dvec3& h) {
  glm::dvec3 s = wi + wo;
  double len = glm::length(s);
  if (!(wi.z > 0 && wo.z > 0 && len > 0)) return false;
  h = s / len;
  return true;
}

// ---- the NaN/Inf census over the stability sweep's extremes -----------------

void run_census(Runtime& rt, const cl::Program& prog, const UserBrdf& u, const UserCheckOptions& opt, SuiteReport& rep) {
  auto t0 = Clock::now();
  // Widths from the sweep's extremes (alpha 1e-7 .. 2), the range ends, every other parameter at its ends.
  std::vector<Values> settings;
  for (auto& r : roughness_grid(u, {1e-7, 1e-4, 1e-2, 0.3, 1.0, 2.0}, 64)) {
    auto c = corners(u, r);
    settings.insert(settings.end(), c.begin(), c.end());
  }
  if (u.roughness >= 0 && !u.params[size_t(u.roughness)].fixed)
    for (double end : {u.params[size_t(u.roughness)].lo, u.params[size_t(u.roughness)].hi}) {
      Values b = u.defaults();
      b[size_t(u.roughness)] = end;
      auto c = corners(u, b);
      settings.insert(settings.end(), c.begin(), c.end());
    }
  std::vector<Record> base;
  for (auto& ps : pair_sets(false))
    for (auto& pr : ps.pairs) {
      Record r{pr.wi, pr.wo, {0, 0, 1}, false, ps.name, 0};
      r.has_m = half_vector(as_float(pr.wi), as_float(pr.wo), r.m);
      base.push_back(r);
    }
  // D and G1 at every cosine class: m at that angle (and v = m), and m = n.
  for (auto& cc : cos_classes(false))
    for (double c : cc.values) {
      double s = std::sqrt(std::max(0.0, (1.0 - c) * (1.0 + c)));
      glm::dvec3 d(s * std::cos(0.3), s * std::sin(0.3), c);
      base.push_back({d, d, d, true, "cos_" + cc.name, 0});
      base.push_back({d, d, {0, 0, 1}, true, "cos_" + cc.name, 0});
    }
  std::vector<Record> recs;
  for (size_t s = 0; s < settings.size(); ++s)
    for (auto r : base) {
      r.setting = s;
      recs.push_back(r);
    }
  std::vector<float> out = eval_records(rt, prog, recs, settings);

  // One point per function and region: the count of NaN, Inf and negative values.
  struct Tally {
    uint64_t evaluated = 0, bad = 0;
    std::string first;
  };
  std::map<std::pair<std::string, std::string>, Tally> tally;
  for (size_t i = 0; i < recs.size(); ++i) {
    const Record& r = recs[i];
    auto count = [&](const std::string& fn, float value, const std::string& call) {
      Tally& t = tally[{fn, r.region}];
      t.evaluated++;
      if (std::isfinite(value) && value >= 0) return;
      if (t.bad++ == 0)
        t.first = fmt::format("first {} = {:.9g} at {}", call, value, named_text(u, settings[r.setting]));
    };
    for (int ch : opt.channels)
      count("brdf", out[i * kOut + size_t(ch)],
            fmt::format("brdf(wi={}, wo={}).{}", vec_text(r.wi), vec_text(r.wo), kChannel[ch]));
    if (!r.has_m) continue;
    if (u.has_d) count("D", out[i * kOut + 3], fmt::format("D(m={})", vec_text(r.m)));
    if (u.has_g1) {
      count("G1", out[i * kOut + 4], fmt::format("G1(v={}, m={})", vec_text(r.wo), vec_text(r.m)));
      count("G1", out[i * kOut + 5], fmt::format("G1(v={}, m={})", vec_text(r.wi), vec_text(r.m)));
    }
  }
  for (auto& [key, t] : tally) {
    PointResult p = point_of(u, "finite", {});
    p.params.clear();
    p.bounded = true;
    p.bound = 0;
    p.estimate = double(t.bad);
    p.samples = t.evaluated;
    p.measure = "NaN/Inf/negative values";
    p.detail = fmt::format("{} in region {} ({} evaluated){}{}", key.first, key.second, t.evaluated,
                           t.first.empty() ? "" : ", ", t.first);
    rep.points.push_back(p);
  }
  rep.stats.push_back({"finite", tally.size(), recs.size(), since(t0)});
}

// ---- reciprocity -------------------------------------------------------------

void run_user_reciprocity(Integrator& in, const UserBrdf& u, const UserCheckOptions& opt,
                          SuiteReport& rep) {
  auto t0 = Clock::now();
  std::vector<IntegralSpec> specs;
  std::vector<PointResult> pts;
  for (auto& r : roughness_grid(u, {1e-4, 1e-2, 0.1, 0.3, 1.0}, 64))
    for (auto& v : corners(u, r))
      for (int ch : opt.channels) {
        specs.push_back(user_spec(u, IntegralKind::Albedo, v, 1.0, ch));
        PointResult p = point_of(u, "reciprocity", v);
        p.params["channel"] = ch;
        pts.push_back(p);
      }
  record_reciprocity(in, specs, pts, kUserReciprocityBound, opt.scale, opt.seed, t0, rep);
}

// ---- pointwise agreement with a claimed model --------------------------------

// The cosines of a pair taken as given, not made unit (above the horizon).
ref::Shading raw_shading(const glm::dvec3& wi, const glm::dvec3& wo) {
  double len = glm::length(wi + wo);
  return {wi.z, wo.z, (wi.z + wo.z) / len, std::min(0.5 * len, 1.0)};
}

void run_agreement(Runtime& rt, const cl::Program& prog, const UserBrdf& u, const Claim& claim,
                   const UserCheckOptions& opt, SuiteReport& rep) {
  auto t0 = Clock::now();
  std::vector<Values> settings;
  for (auto& r : roughness_grid(u, suite_alphas(), 6)) {
    auto c = corners(u, r);
    settings.insert(settings.end(), c.begin(), c.end());
  }
  std::vector<ref::BrdfSpec> refs;
  for (auto& v : settings) refs.push_back(claim.at(v));  // throws when a mapped value leaves its term's range
  // Per setting: half the pairs uniform over the hemisphere, half around the
  // specular peak (wo reflected about an m of Cauchy slopes of the width).
  constexpr uint32_t kPairs = 2048;
  std::vector<Record> recs;
  for (size_t s = 0; s < settings.size(); ++s) {
    double w = u.width(settings[s]) > 0 ? u.width(settings[s]) : 0.3;
    for (uint32_t k = 0; k < kPairs; ++k) {
      auto r = philox(opt.seed, uint32_t(s), 7, k);
      auto dir = [](double c, double phi) {
        double st = std::sqrt(std::max(0.0, 1.0 - c * c));
        return glm::dvec3(st * std::cos(phi), st * std::sin(phi), c);
      };
      glm::dvec3 wo = dir(u01_open(r[0]), 2 * M_PI * u01_open(r[1]));
      glm::dvec3 wi = dir(u01_open(r[2]), 2 * M_PI * u01_open(r[3]));
      if (k % 2) {
        double t = w * std::sqrt(1.0 / ((1.0 - u01_open(r[2])) * (1.0 - u01_open(r[2]))) - 1.0);
        glm::dvec3 m = glm::normalize(glm::dvec3(t * std::cos(2 * M_PI * u01_open(r[3])), t * std::sin(2 * M_PI * u01_open(r[3])), 1.0));
        glm::dvec3 refl = 2.0 * glm::dot(wo, m) * m - wo;
        if (refl.z > 1e-4) wi = refl;
      }
      Record rec{as_float(wi), as_float(wo), {0, 0, 1}, false, "", s};
      rec.has_m = half_vector(rec.wi, rec.wo, rec.m);
      recs.push_back(rec);
    }
  }
  std::vector<float> out = eval_records(rt, prog, recs, settings);
  const double eps = 0x1p-23;
  for (size_t s = 0; s < settings.size(); ++s)
    for (int ch : opt.channels) {
      PointResult p = point_of(u, "agree", settings[s]);
      p.params["channel"] = ch;
      p.bounded = true;
      p.bound = kAgreeBound;
      p.measure = "max relative error vs " + claim.spec;
      p.samples = kPairs;
      double rmax = 0;
      std::vector<double> refv(kPairs);
      for (uint32_t k = 0; k < kPairs; ++k) {
        const Record& r = recs[s * kPairs + k];
        refv[k] = ref::brdf(refs[s], r.wi, r.wo);
        rmax = std::max(rmax, std::fabs(refv[k]));
      }
      double worst = -1;
      for (uint32_t k = 0; k < kPairs; ++k) {
        const Record& r = recs[s * kPairs + k];
        double uv = out[(s * kPairs + k) * kOut + size_t(ch)], rv = refv[k];
        // What the model itself moves when one direction component moves by
        // one float rounding: no float code can be closer than that.
        // The reference makes float directions unit in double first; code
        // that takes them as they are (|w| = 1 +- 1e-7) sees a half vector
        // that moves by that much over |wi + wo|, a lot for nearly opposite
        // directions: the model on the raw vectors bounds that too.
        double dev = std::fabs(ref::brdf(refs[s], raw_shading(r.wi, r.wo)) - rv);
        for (int c = 0; c < 6; ++c)
          for (double b : {eps, -eps}) {
            glm::dvec3 wi = r.wi, wo = r.wo;
            (c < 3 ? wi : wo)[c % 3] *= 1.0 + b;
            dev = std::max(dev, std::fabs(ref::brdf(refs[s], wi, wo) - rv));
          }
        double err = std::isfinite(uv) ? std::max(0.0, std::fabs(uv - rv) - 2 * dev) / std::max({std::fabs(rv), 1e-6 * rmax, 1e-30})
                                       : std::numeric_limits<double>::infinity();
        if (err > worst) {
          worst = err;
          p.detail = fmt::format("brdf(wi={}, wo={}).{} = {:.9g}, {} gives {:.9g}", vec_text(r.wi), vec_text(r.wo),
                                 kChannel[ch], uv, claim.spec, rv);
        }
      }
      p.estimate = worst;
      rep.points.push_back(p);
    }
  rep.stats.push_back({"agree", settings.size() * opt.channels.size(), recs.size(), since(t0)});
}

}  // namespace

SuiteReport run_user_check(Runtime& rt, const UserBrdf& u, const std::optional<Claim>& claim,
                           const UserCheckOptions& opt) {
  // Which checks: those asked for, each needing what it needs.
  std::vector<std::string> checks = opt.checks;
  auto available = [&](const std::string& c) -> std::string {
    if (c == "d_norm" && !u.has_d) return "needs 'float D(float3 m, const float* params)'";
    if (c == "masking" && !(u.has_d && u.has_g1)) return "needs D and 'float G1(float3 v, float3 m, const float* params)'";
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
        throw Error(fmt::format("unknown check '{}' (mfv check runs: d_norm, masking, furnace, energy, reciprocity, "
                                "finite, agree)",
                                c));
      if (!available(c).empty()) throw Error(fmt::format("--check {}: {} {}", c, u.path, available(c)));
    }
  }
  if (opt.channels.empty()) throw Error("--channel: name at least one of r, g, b");
  SuiteOptions sopt = suite_options_of(opt);
  SuiteReport rep;
  rep.title = "mfv check " + u.path;
  rep.list_passes = true;
  rep.reference_note =
      claim ? fmt::format("reference: no double twin of user code; check 'agree' compares it with {} ({}) pointwise",
                          claim->spec, claim->mapping(u))
            : "reference: no double twin of user code (claim a catalog model with --as D/G/F to compare pointwise)";
  if (u.roughness < 0)
    rep.reference_note += "; no roughness declared: the estimators use a mixture of widths 1, 1/4, ..., 1/256";
  double b0 = rt.build_stats().seconds;
  cl::Program prog = build_user_program(rt, u);
  rep.build_seconds = rt.build_stats().seconds - b0;
  Integrator in(rt, prog);
  uint32_t stream = 0;
  for (auto& plan : make_plans(u, opt, checks)) run_plan(in, plan, sopt, stream, rep);
  auto has = [&](const char* c) { return std::find(checks.begin(), checks.end(), c) != checks.end(); };
  if (has("reciprocity")) run_user_reciprocity(in, u, opt, rep);
  if (has("finite")) run_census(rt, prog, u, opt, rep);
  if (has("agree")) run_agreement(rt, prog, u, *claim, opt, rep);
  judge(rep, sopt);
  return rep;
}

}  // namespace mfv
