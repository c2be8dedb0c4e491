// mfv check's pointwise checks on the user's code: the NaN/Inf census over
// the sweep's extreme inputs (checks/pointwise_inputs.hpp) and the
// agreement with a claimed catalog model, both on the records of
// kernels/abi/pointwise.h, with the conditioning allowance of
// checks/pointwise.hpp.
#include "user/user_detail.hpp"

#include "checks/pointwise.hpp"
#include "checks/pointwise_inputs.hpp"
#include "reference/estimators.hpp"
#include "rng/philox.hpp"
#include "util/float_round.hpp"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mfv::user_detail {
namespace {

using namespace pw;  // the record's named slots

const char* kChannel = "rgb";

// A census or agreement input: the directions, a microfacet normal and the
// index of its parameter values.
struct Input {
  glm::dvec3 wi, wo, m;
  bool has_m = false;  // m is a half vector or a normal the D and G1 census may use
  std::string region;
  size_t setting = 0;  // index of its parameter values
};

// The inputs as pointwise records (float, kernels/abi/pointwise.h) through
// kernels/user_brdf.cl user_eval; returns the records with their outputs
// (PW_BRDF_R..B, PW_USER_D, PW_USER_G1_WO, PW_USER_G1_WI; pre-filled with NaN).
std::vector<FloatRecord> eval_records(Runtime& rt, const cl::Program& prog, const std::vector<Input>& recs,
                                      const std::vector<Values>& settings) {
  std::vector<FloatRecord> rec(recs.size());
  if (recs.empty()) return rec;
  for (size_t i = 0; i < recs.size(); ++i) {
    FloatRecord& r = rec[i];
    r.fill(0.0f);
    const Input& x = recs[i];
    const glm::dvec3* v[3] = {&x.wi, &x.wo, &x.m};
    const int at[3] = {PW_WI_X, PW_WO_X, PW_M_X};
    for (int d = 0; d < 3; ++d)
      for (int k = 0; k < 3; ++k) r[size_t(at[d] + k)] = float((*v[d])[k]);
    const Values& s = settings[x.setting];
    for (size_t k = 0; k < s.size(); ++k) r[PW_P0 + k] = float(s[k]);
    for (int k = PW_VALUE; k < PW_RECORD; ++k) r[size_t(k)] = std::numeric_limits<float>::quiet_NaN();
  }
  cl::Kernel k(prog, "user_eval");
  const size_t bytes = rec.size() * sizeof(FloatRecord);
  cl::Buffer buf(rt.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, rec.data());
  k.setArg(0, buf);
  rt.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(recs.size()));
  rt.queue().enqueueReadBuffer(buf, CL_TRUE, 0, bytes, rec.data());
  return rec;
}

std::string vec_text(const glm::dvec3& v) {
  return fmt::format("({:.9g}, {:.9g}, {:.9g})", float(v.x), float(v.y), float(v.z));
}

// The half vector in double, where both directions are above the horizon and it exists.
bool half_vector(const glm::dvec3& wi, const glm::dvec3& wo, glm::dvec3& h) {
  glm::dvec3 s = wi + wo;
  double len = glm::length(s);
  if (!(wi.z > 0 && wo.z > 0 && len > 0)) return false;
  h = s / len;
  return true;
}

// ---- the NaN/Inf census over the stability sweep's extremes -----------------

}  // namespace

void describe_reciprocity(Runtime& rt, const cl::Program& prog, uint64_t seed, const std::vector<Values>& settings,
                          std::vector<PointResult*> pts) {
  std::vector<Input> recs;
  for (size_t i = 0; i < pts.size(); ++i) {
    glm::dvec3 a, b;
    ref::reciprocity_pair(seed, uint32_t(pts[i]->params.at("stream")), uint32_t(pts[i]->params.at("stream_hi")),
                          uint32_t(pts[i]->params.at("worst_pair")), a, b);
    recs.push_back({through_float(a), through_float(b), {0, 0, 1}, false, "", i});
    recs.push_back({through_float(b), through_float(a), {0, 0, 1}, false, "", i});
  }
  std::vector<FloatRecord> out = eval_records(rt, prog, recs, settings);
  for (size_t i = 0; i < pts.size(); ++i) {
    const size_t ch = size_t(pts[i]->params.at("channel"));
    pts[i]->params.erase("stream");
    pts[i]->params.erase("stream_hi");
    pts[i]->detail =
        fmt::format("brdf(wi={}, wo={}).{} = {:.9g}, brdf(wi={}, wo={}).{} = {:.9g}", vec_text(recs[2 * i].wi),
                    vec_text(recs[2 * i].wo), kChannel[ch], out[2 * i][PW_BRDF_R + ch], vec_text(recs[2 * i + 1].wi),
                    vec_text(recs[2 * i + 1].wo), kChannel[ch], out[2 * i + 1][PW_BRDF_R + ch]);
  }
}

void run_census(Runtime& rt, const cl::Program& prog, const UserBrdf& u, const UserCheckOptions& opt,
                SuiteReport& rep) {
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
  std::vector<Input> base;
  for (auto& ps : pair_sets(false))
    for (auto& pr : ps.pairs) {
      Input r{pr.wi, pr.wo, {0, 0, 1}, false, ps.name, 0};
      r.has_m = half_vector(through_float(pr.wi), through_float(pr.wo), r.m);
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
  std::vector<Input> recs;
  for (size_t s = 0; s < settings.size(); ++s)
    for (auto r : base) {
      r.setting = s;
      recs.push_back(r);
    }
  std::vector<FloatRecord> out = eval_records(rt, prog, recs, settings);

  // One point per function and region: the count of NaN, Inf and negative values.
  struct Tally {
    uint64_t evaluated = 0, bad = 0;
    std::string first;
  };
  std::map<std::pair<std::string, std::string>, Tally> tally;
  for (size_t i = 0; i < recs.size(); ++i) {
    const Input& r = recs[i];
    auto count = [&](const std::string& fn, float value, const std::string& call) {
      Tally& t = tally[{fn, r.region}];
      t.evaluated++;
      if (std::isfinite(value) && value >= 0) return;
      if (t.bad++ == 0)
        t.first = fmt::format("first {} = {:.9g} at {}", call, value, named_text(u, settings[r.setting]));
    };
    for (int ch : opt.channels)
      count("brdf", out[i][PW_BRDF_R + size_t(ch)],
            fmt::format("brdf(wi={}, wo={}).{}", vec_text(r.wi), vec_text(r.wo), kChannel[ch]));
    if (!r.has_m) continue;
    if (u.has_d) count("D", out[i][PW_USER_D], fmt::format("D(m={})", vec_text(r.m)));
    if (u.has_g1) {
      count("G1", out[i][PW_USER_G1_WO], fmt::format("G1(v={}, m={})", vec_text(r.wo), vec_text(r.m)));
      count("G1", out[i][PW_USER_G1_WI], fmt::format("G1(v={}, m={})", vec_text(r.wi), vec_text(r.m)));
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

// ---- pointwise agreement with a claimed model --------------------------------

namespace {

// The cosines of a pair taken as given, not made unit (above the horizon),
// in each of the ways code forms v.h from them: |wi + wo| / 2, wo.h or wi.h
// with h = (wi + wo) / |wi + wo| (they differ by |wo| - |wi|, up to 1e-7,
// which is much of 1 - v.h near the specular peak, and Schlick's (1 - v.h)^5
// raises it to the fifth).
std::vector<ref::Shading> raw_shadings(const glm::dvec3& wi, const glm::dvec3& wo) {
  const glm::dvec3 s = wi + wo;
  const double len = glm::length(s), nh = (wi.z + wo.z) / len;
  return {{wi.z, wo.z, nh, std::min(0.5 * len, 1.0)},
          {wi.z, wo.z, nh, std::min(glm::dot(wo, s) / len, 1.0)},
          {wi.z, wo.z, nh, std::min(glm::dot(wi, s) / len, 1.0)}};
}

}  // namespace

// Near 0 a relative measure alone reads rounding as error (a reference of
// 1e-9 where the float code's terms are of order 1 and round by 6e-8), and
// a floor scaled by hand hides formula errors in a narrow lobe's tails
// (10^-6 of a GGX peak at alpha 1e-3 is 0.3 absolute). So the absolute
// part is what the value's own rounding is at that input, measured: the
// float record's half ulp, and the float code's kf - kd there (a formula
// difference below the float code's own rounding is invisible in the value
// it ships); the relative part's scale stops at FLT_MIN, below which float
// holds an absolute 2^-150, not a relative 2^-24 (docs/cli/check.md, agree).
double agree_error(double v, double rv, double dev, double rounding) {
  if (!std::isfinite(v)) return std::numeric_limits<double>::infinity();
  return std::max(0.0, std::fabs(v - rv) - 2 * dev - rounding) /
         std::max(std::fabs(rv), double(std::numeric_limits<float>::min()));
}

double rounding_at(double v, double kf) {
  const float f = std::fabs(float(v));
  double r = std::isfinite(f) ? 0.5 * (double(std::nextafter(f, std::numeric_limits<float>::infinity())) - double(f)) : 0;
  if (std::isfinite(kf) && std::isfinite(v)) r += std::fabs(kf - v);
  return r;
}

void run_agreement(Runtime& rt, const cl::Program& prog, const cl::Program* twin, const UserBrdf& u, const Claim& claim,
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
  std::vector<Input> recs;
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
        glm::dvec3 m = glm::normalize(
            glm::dvec3(t * std::cos(2 * M_PI * u01_open(r[3])), t * std::sin(2 * M_PI * u01_open(r[3])), 1.0));
        glm::dvec3 refl = 2.0 * glm::dot(wo, m) * m - wo;
        if (refl.z > 1e-4) wi = refl;
      }
      Input rec{through_float(wi), through_float(wo), {0, 0, 1}, false, "", s};
      rec.has_m = half_vector(rec.wi, rec.wo, rec.m);
      recs.push_back(rec);
    }
  }
  std::vector<FloatRecord> out = eval_records(rt, prog, recs, settings);
  // the twin's values (double, rounded to float: 6e-8 relative)
  std::vector<FloatRecord> outd = twin ? eval_records(rt, *twin, recs, settings) : std::vector<FloatRecord>{};
  for (size_t s = 0; s < settings.size(); ++s)
    for (int ch : opt.channels) {
      PointResult p = point_of(u, "agree", settings[s]);
      p.params["channel"] = ch;
      p.bounded = true;
      p.bound = kAgreeBound;
      p.measure = (twin ? "max relative error of the double twin vs " : "max relative error vs ") + claim.spec;
      p.samples = kPairs;
      std::vector<double> refv(kPairs);
      for (uint32_t k = 0; k < kPairs; ++k) refv[k] = ref::brdf(refs[s], recs[s * kPairs + k].wi, recs[s * kPairs + k].wo);
      double worst = -1, worst_float = -1;
      std::string float_at;
      for (uint32_t k = 0; k < kPairs; ++k) {
        const Input& r = recs[s * kPairs + k];
        double uv = out[s * kPairs + k][PW_BRDF_R + size_t(ch)], rv = refv[k];
        // What the model itself moves when one direction component moves by
        // one float rounding: no float code can be closer than that.
        // The reference makes float directions unit in double first; code
        // that takes them as they are (|w| = 1 +- 1e-7) sees a half vector
        // that moves by that much over |wi + wo|, a lot for nearly opposite
        // directions: the model on the raw vectors bounds that too.
        auto moved = [&](int c, double b) {
          glm::dvec3 wi = r.wi, wo = r.wo;
          (c < 3 ? wi : wo)[c % 3] *= 1.0 + b;
          return ref::brdf(refs[s], wi, wo);
        };
        double dev = input_sensitivity(6, 1.0, false, moved, rv);
        for (const ref::Shading& c : raw_shadings(r.wi, r.wo)) dev = std::max(dev, std::fabs(ref::brdf(refs[s], c) - rv));
        const std::string at = fmt::format("brdf(wi={}, wo={}).{} = {:.9g}", vec_text(r.wi), vec_text(r.wo), kChannel[ch], uv);
        // without the twin the float code is judged with its record's rounding alone
        double err = agree_error(uv, rv, dev, rounding_at(uv, std::numeric_limits<double>::quiet_NaN()));
        if (twin) {
          if (err > worst_float) {
            worst_float = err;
            float_at = fmt::format("{}, {} gives {:.9g}", at, claim.spec, rv);
          }
          const double dv = outd[s * kPairs + k][PW_BRDF_R + size_t(ch)];
          err = agree_error(dv, rv, dev, rounding_at(dv, uv));
          if (err > worst)
            p.detail = fmt::format("formula error: {}, its double twin {:.9g}, {} gives {:.9g}", at, dv, claim.spec, rv);
        } else if (err > worst) {
          p.detail = fmt::format("{}, {} gives {:.9g}", at, claim.spec, rv);
        }
        worst = std::max(worst, err);
      }
      p.estimate = worst;
      // the twin agrees: what the float code adds is float conditioning
      if (twin && worst <= kAgreeBound)
        p.detail = fmt::format(
            "the double twin agrees; float conditioning (within the derived bound): the float code is off by "
            "{:.3g} relative at {}",
            worst_float, float_at);
      rep.points.push_back(p);
    }
  rep.stats.push_back({"agree", settings.size() * opt.channels.size(), recs.size(), since(t0)});
}

}  // namespace mfv::user_detail
