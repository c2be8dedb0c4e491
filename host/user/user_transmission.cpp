// mfv check on a user's btdf or bsdf (docs/cli/check.md, "Transmission"):
// the registry's transmission kinds at the user's widths and indices. The
// integrals (bsdf_furnace, bsdf_avg_reciprocity, transmission_masking) are
// the catalog's integrands and estimators (kernels/transmission.cl), with the
// user's code behind the seams spec_bsdf_value, spec_D and spec_G1; the
// generalized reciprocity (bsdf_reciprocity) is evaluated pointwise here.
#include "user/user_detail.hpp"

#include "abi/integral.h"
#include "rng/philox.hpp"
#include "util/float_round.hpp"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace mfv::user_detail {
namespace {

// The catalog's widths for a BSDF (checks/suite_bsdf.cpp) but the smooth
// limit, which a float user lobe at alpha = 1e-4 leaves to the declared
// range's lower end (roughness_grid adds it where the range reaches below).
const std::vector<double> kUserBsdfAlphas = {0.05, 0.3, 0.8};

// bsdf_furnace's view cosines: checks/suite_bsdf.cpp's, 0.01 to 1, dense towards grazing.
std::vector<double> flux_views(int n) {
  std::vector<double> c;
  for (int i = 0; i < n; ++i) c.push_back(std::pow(10.0, -2.0 * double(n - 1 - i) / double(n - 1)));
  return c;
}

const char* kChannel = "rgb";

}  // namespace

void add_transmission(Plan& p, const CheckKind& k, const UserBrdf& u, const UserCheckOptions& opt) {
  const Shape shape = shape_of(k);
  for (auto& v : roughness_grid(u, kUserBsdfAlphas, 5)) {
    if (shape == Shape::MaskingT) {
      // the weak white furnace of D and G1 for o below: reads no eta, one channel
      for (double co : view_cosines(k.n_view)) {
        IntegralSpec s = user_spec(u, k.kind, v, co, 0);
        s.side = MFV_SIDE_BELOW;
        p.specs.push_back(s);
        PointResult r = point_of(u, k.check, v);
        r.params["cos_o"] = co;
        r.params["side"] = MFV_SIDE_BELOW;
        r.expected = k.expected;
        p.points.push_back(r);
      }
      continue;
    }
    for (double eta : u.eta_values()) {
      Values w = v;
      w[size_t(u.eta)] = eta;  // the user's eta and the estimator's are one value
      for (int ch : opt.channels) {
        if (shape == Shape::BsdfAvg) {
          IntegralSpec s = user_spec(u, k.kind, w, 1.0, ch);
          s.eta = float(eta);
          p.specs.push_back(s);
          PointResult r = point_of(u, k.check, w);
          r.params["channel"] = ch;
          r.expected = k.expected;  // 0: T_avg(1/eta) - T_avg(eta)/eta^2, two-sided
          p.points.push_back(r);
          continue;
        }
        // bsdf_furnace: E_R and E_T of the light from each side at each view,
        // two integrals side by side (merge_flux_points adds them)
        for (int side : {MFV_SIDE_ABOVE, MFV_SIDE_BELOW})
          for (double co : flux_views(k.n_view))
            for (uint32_t lobe : {MFV_LOBE_REFLECT, MFV_LOBE_TRANSMIT}) {
              IntegralSpec s = user_spec(u, k.kind, w, co, ch);
              s.eta = float(eta);
              s.side = side;
              s.lobe = lobe;
              p.specs.push_back(s);
              PointResult r = point_of(u, k.check, w);
              r.params["cos_i"] = co;
              r.params["side"] = side;
              r.params["channel"] = ch;
              r.params["lobe"] = lobe;
              r.expected = 1.0;
              r.upper_only = true;
              p.points.push_back(r);
            }
      }
    }
  }
}

void merge_flux_points(SuiteReport& rep, size_t first) {
  std::vector<PointResult> merged;
  for (size_t i = first; i + 1 < rep.points.size(); i += 2) {
    const PointResult &r = rep.points[i], &t = rep.points[i + 1];
    PointResult e = r;
    e.params.erase("lobe");
    e.estimate = r.estimate + t.estimate;
    e.stderr_ = std::hypot(r.stderr_, t.stderr_);
    e.dof = std::min(r.dof, t.dof);  // Student t with the fewer degrees of freedom: conservative
    e.rounding_bound = r.rounding_bound + t.rounding_bound;
    e.samples = std::min(r.samples, t.samples);
    e.params["E_R"] = r.estimate;
    e.params["E_T"] = t.estimate;
    e.params["E_R_se"] = r.stderr_;
    e.params["E_T_se"] = t.stderr_;
    e.expected = 1.0;
    e.upper_only = true;
    e.detail = fmt::format("E_R = {:.6g} ± {:.2g}, E_T = {:.6g} ± {:.2g}, loss 1 - E_R - E_T = {:.4g}", r.estimate,
                           r.stderr_, t.estimate, t.stderr_, 1.0 - r.estimate - t.estimate);
    merged.push_back(e);
  }
  rep.points.resize(first);
  rep.points.insert(rep.points.end(), merged.begin(), merged.end());
}

// ---- bsdf_reciprocity: f(i,o)/eta_o^2 = f(o,i)/eta_i^2 (radiance form) --------

namespace {

// One record of kernels/user_brdf.cl user_bsdf_pairs (MFV_PAIR_*).
constexpr size_t kPairRecord = 18, kPairP0 = 6, kPairFwd = 12, kPairRev = 15;

glm::dvec3 on_side(double cos_t, double phi, double side) {
  const double s = std::sqrt(std::max(0.0, (1.0 - cos_t) * (1.0 + cos_t)));
  return {s * std::cos(phi), s * std::sin(phi), side * cos_t};
}

// Walter et al. 2007 eq. 40: i refracted through facet m (i.m > 0) with
// relative index k = eta_i / eta_o; false under total internal reflection.
bool refract(const glm::dvec3& i, const glm::dvec3& m, double k, glm::dvec3& o) {
  const double c = glm::dot(i, m), t2 = 1.0 - k * k * (1.0 - c * c);
  if (!(c > 0) || !(t2 > 0)) return false;
  o = glm::normalize((k * c - std::sqrt(t2)) * m - k * i);
  return true;
}

struct Pair {
  glm::dvec3 wi, wo;
  const char* region;
};

// Pair k of a setting (width alpha, index eta): i above for even k, below
// for odd; then by k/2 mod 4 o uniform on the other side, i grazing
// (n.i < 1e-3), i just inside the critical angle on the dense side (its
// cosine 1e-1 ... 1e-4 of the way from the critical one to 1, through the
// normal facet, so that o grazes), o refracted through a facet tilted up to
// 2 alpha. Rounded to float, as the code sees them.
Pair make_pair(uint64_t seed, uint32_t stream, uint32_t k, double alpha, double eta) {
  const auto r = philox(seed, stream, 0x7b5df, k);
  const double u0 = u01_open(r[0]), u1 = u01_open(r[1]), u2 = u01_open(r[2]), u3 = u01_open(r[3]);
  const double two_pi = 2.0 * M_PI;
  double side = (k % 2 == 0) ? 1.0 : -1.0;
  const uint32_t cls = (k / 2) % 4;
  Pair p{};
  auto uniform_other = [&] { p.wo = on_side(u2, two_pi * u3, -side); };
  switch (cls) {
    case 0:
      p.region = "uniform";
      p.wi = on_side(u0, two_pi * u1, side);
      uniform_other();
      break;
    case 1:
      p.region = "grazing";
      p.wi = on_side(1e-3 * u0, two_pi * u1, side);
      uniform_other();
      break;
    case 2: {
      p.region = "near-critical";
      side = eta > 1 ? -1.0 : 1.0;  // the dense side
      const double rel = eta > 1 ? 1.0 / eta : eta;  // eta_o / eta_i < 1 seen from the dense side
      const double cc = std::sqrt((1.0 - rel) * (1.0 + rel));  // the critical cosine
      p.wi = on_side(cc + (1.0 - cc) * std::pow(10.0, -1.0 - 3.0 * u0), two_pi * u1, side);
      glm::dvec3 o;
      const glm::dvec3 n(0, 0, side);
      if (refract(p.wi, n, 1.0 / rel, o)) p.wo = o;
      else uniform_other();
      break;
    }
    default: {
      p.region = "refracted";
      p.wi = on_side(u0, two_pi * u1, side);
      const double t = std::atan(2.0 * alpha * u2), ph = two_pi * u3;
      const glm::dvec3 m(std::sin(t) * std::cos(ph) * side, std::sin(t) * std::sin(ph) * side, std::cos(t) * side);
      const double eta_i = side > 0 ? 1.0 : eta, eta_o = side > 0 ? eta : 1.0;
      glm::dvec3 o;
      if (refract(p.wi, m, eta_i / eta_o, o) && o.z * side < 0) p.wo = o;
      else uniform_other();
      break;
    }
  }
  p.wi = through_float(glm::normalize(p.wi));
  p.wo = through_float(glm::normalize(p.wo));
  return p;
}

// What float rounding alone may make of f(i,o)/eta_o^2 - f(o,i)/eta_i^2,
// relative, at a transmitted pair: 1 - F near the critical angle. With
// c = |w.h| on the rare side, g^2 = n^2 - 1 + c'^2 of the dense side (c' its
// cosine, n = eta_rare / eta_dense) is (c / eta_max)^2, eta_max = max(eta,
// 1/eta), and 1 - F is proportional to g there. g^2 moves by about 11
// roundings of 1 (2^-24 each): 4 from the float directions (each component
// rounded: sin^2 of each side by 2 2^-24 relative), 3 in n^2 - 1 + c'^2, 4
// from c' of a half vector formed in float; so 1 - F moves by 11 2^-24 /
// (2 g^2) relative, each of the two values: 11 2^-24 eta_max^2 / c^2 for
// their difference, taken as 16. Far from the critical angle this is below
// 1e-5; at a grazing light entering glass (c = 1.4e-3, eta 2.5) it is 2.9:
// the measured asymmetry of a correct float BTDF there was 0.10
// (tests/data/btdf/walter_ggx.cl).
double near_critical_rounding(const Pair& p, double eta) {
  if (!(p.wi.z * p.wo.z < 0)) return 0.0;
  const double ei = p.wi.z > 0 ? 1.0 : eta, eo = p.wi.z > 0 ? eta : 1.0;
  const glm::dvec3 s = ei * p.wi + eo * p.wo;
  const double len = glm::length(s);
  if (!(len > 0)) return 0.0;
  const glm::dvec3 h = s / len;
  const glm::dvec3& rare = ei < eo ? p.wi : p.wo;
  const double c = std::fabs(glm::dot(rare, h)), em = std::max(eta, 1.0 / eta);
  return 16.0 * 0x1p-24 * em * em / std::max(c * c, 1e-300);
}

std::string vec_text(const glm::dvec3& v) { return fmt::format("({:.9g}, {:.9g}, {:.9g})", v.x, v.y, v.z); }

}  // namespace

void run_bsdf_reciprocity(Runtime& rt, const cl::Program& prog, const UserBrdf& u, const UserCheckOptions& opt,
                          SuiteReport& rep) {
  auto t0 = Clock::now();
  const CheckKind& kind = check_kind("bsdf_reciprocity");
  const uint32_t n = uint32_t(std::max(64.0, std::round(double(kind.base_samples) * opt.scale)));
  std::vector<Values> settings;
  for (auto& v : roughness_grid(u, {0.05, 0.3, 1.0}, 5))
    for (double eta : u.eta_values()) {
      Values w = v;
      w[size_t(u.eta)] = eta;
      settings.push_back(w);
    }
  std::vector<float> rec(settings.size() * n * kPairRecord, std::numeric_limits<float>::quiet_NaN());
  std::vector<Pair> pairs(settings.size() * n);
  for (size_t s = 0; s < settings.size(); ++s) {
    const double alpha = u.width(settings[s]) > 0 ? u.width(settings[s]) : 0.3;
    const double eta = settings[s][size_t(u.eta)];
    for (uint32_t k = 0; k < n; ++k) {
      const size_t j = s * n + k;
      pairs[j] = make_pair(opt.seed, uint32_t(s), k, alpha, eta);
      float* r = &rec[j * kPairRecord];
      for (int d = 0; d < 3; ++d) r[d] = float(pairs[j].wi[d]), r[3 + d] = float(pairs[j].wo[d]);
      for (size_t q = 0; q < 6; ++q) r[kPairP0 + q] = q < settings[s].size() ? float(settings[s][q]) : 0.0f;
    }
  }
  cl::Kernel kern(prog, "user_bsdf_pairs");
  const size_t bytes = rec.size() * sizeof(float);
  cl::Buffer buf(rt.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, rec.data());
  kern.setArg(0, buf);
  rt.queue().enqueueNDRangeKernel(kern, cl::NullRange, cl::NDRange(pairs.size()));
  rt.queue().enqueueReadBuffer(buf, CL_TRUE, 0, bytes, rec.data());

  for (size_t s = 0; s < settings.size(); ++s) {
    const double eta = settings[s][size_t(u.eta)];
    for (int ch : opt.channels) {
      PointResult p = point_of(u, kind.check, settings[s]);
      p.params["channel"] = ch;
      double worst = 0;
      size_t at = s * n, failing = 0;
      for (uint32_t k = 0; k < n; ++k) {
        const size_t j = s * n + k;
        const float* r = &rec[j * kPairRecord];
        // radiance form: f(i,o) carries eta_o^2, so f(i,o)/eta_o^2 is symmetric
        const double eta_i = pairs[j].wi.z > 0 ? 1.0 : eta, eta_o = pairs[j].wo.z > 0 ? 1.0 : eta;
        const double a = double(r[kPairFwd + ch]) / (eta_o * eta_o), b = double(r[kPairRev + ch]) / (eta_i * eta_i);
        double err = std::fabs(a - b) / std::max({std::fabs(a), std::fabs(b), 1e-4});
        err = std::max(0.0, err - near_critical_rounding(pairs[j], eta));
        // a value that is NaN, infinite or negative is no BSDF's: the pair fails whatever the other value
        if (!std::isfinite(err) || !(a >= 0) || !(b >= 0) || !std::isfinite(a) || !std::isfinite(b))
          err = std::numeric_limits<double>::infinity();
        if (err > kUserReciprocityBound) ++failing;
        if (err > worst) worst = err, at = j;
      }
      const float* r = &rec[at * kPairRecord];
      p.estimate = worst;
      p.samples = n;
      p.bounded = true;
      p.bound = kUserReciprocityBound;
      p.expected = 0.0;
      p.measure = "max |f(i,o)/eta_o^2 - f(o,i)/eta_i^2| / max beyond rounding";
      p.params["failing_pairs"] = double(failing);
      p.detail = fmt::format("{} pair: f(wi={}, wo={}).{} = {:.9g}, f(wi={}, wo={}).{} = {:.9g} (eta = {:g})",
                             pairs[at].region, vec_text(pairs[at].wi), vec_text(pairs[at].wo), kChannel[ch],
                             r[kPairFwd + ch], vec_text(pairs[at].wo), vec_text(pairs[at].wi), kChannel[ch],
                             r[kPairRev + ch], eta);
      rep.points.push_back(p);
    }
  }
  rep.stats.push_back({kind.check, settings.size() * opt.channels.size(), uint64_t(pairs.size()) * 2, since(t0)});
}

}  // namespace mfv::user_detail
