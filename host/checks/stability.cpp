#include "checks/stability.hpp"

#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "catalog/roughness.hpp"
#include "checks/agree.hpp"
#include "reference/brdf.hpp"
#include "reference/reference.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/error.hpp"
#include "util/math_constants.hpp"
#include "runtime/work_group.hpp"
#include "util/progress.hpp"

#include <fmt/format.h>
#include <glm/geometric.hpp>

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

enum Mode { kD = 0, kG = 1, kF = 2, kG1 = 3, kBrdf = 4, kVariant = 5, kModel = 6 };  // = STAB_* in stability.cl
constexpr int kIn = 13;                                                  // = STAB_IN
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using In = std::array<double, kIn>;

struct Point {
  In in{};
  int region = 0;
  double theta = kNaN, alpha = kNaN;  // scan points only: where they go on the plots
};

struct Region {
  std::string name, what;
  bool in_domain = true;
  std::string expect;
};

struct CaseDef {
  StabilityCase info;
  Mode mode = kD;
  const Term* d = nullptr;
  const Term* g = nullptr;
  const Term* f = nullptr;
  const Model* model = nullptr;  // kModel: the kernel's `d` argument carries its number
  int variant = -1;
  std::vector<Region> regions;
  std::vector<Point> points;
  std::function<double(const In&)> ref;       // the double reference on the rounded inputs
  std::function<std::string(const In&)> describe;
  int add_region(Region r) {
    regions.push_back(std::move(r));
    return static_cast<int>(regions.size()) - 1;
  }
};

// ---- Precision -------------------------------------------------------------

double rnd(double x, bool fp64) { return fp64 ? x : static_cast<double>(static_cast<float>(x)); }
double one_plus_ulps(int k, bool fp64) { return 1.0 + k * (fp64 ? 0x1p-52 : 0x1p-23); }
double one_minus_ulp(bool fp64) { return fp64 ? std::nextafter(1.0, 0.0) : std::nextafterf(1.0f, 0.0f); }
double min_normal(bool fp64) { return fp64 ? std::numeric_limits<double>::min() : std::numeric_limits<float>::min(); }

// ---- The cosine grid (issue 6, "Sweep") ------------------------------------
// cosθ ∈ {0, 1e-7, 1e-4, ..., 1 - 1e-7, 1, 1 + 1 ulp}, plus values whose
// square underflows (a unit vector can have such a z), and below the horizon.

// Cosines whose square underflows in float: the smallest subnormal 2^-149,
// 1e-30 and 1e-20 (a unit float vector can have such a z). Float64 kernels
// are swept on the same values: the corresponding double extremes (cos below
// ~1e-154) are beyond what the double reference itself can judge.
const double kTiny[3] = {0x1p-149, 1e-30, 1e-20};

}  // namespace

std::vector<CosClass> cos_classes(bool fp64) {
  return {
      {"grazing", "cos in {0, 2^-149, 1e-30, 1e-20, 1e-7, 1e-4, 1e-3, 1e-2}",
       {0.0, kTiny[0], kTiny[1], kTiny[2], 1e-7, 1e-4, 1e-3, 1e-2}},
      {"mid", "cos in {0.1, 0.3, 0.5, 0.7, 0.9}", {0.1, 0.3, 0.5, 0.7, 0.9}},
      {"normal", "cos in {1-1e-2, 1-1e-4, 1-1e-7, 1-1ulp, 1}", {1 - 1e-2, 1 - 1e-4, 1 - 1e-7, one_minus_ulp(fp64), 1.0}},
      {"tan_zero", "cos = 1 exactly: tan = 0, sin² = 0", {1.0}},
      {"above_one", "cos in {1+1ulp, 1+2ulp, 1+4ulp}: dot products that rounded above 1",
       {one_plus_ulps(1, fp64), one_plus_ulps(2, fp64), one_plus_ulps(4, fp64)}},
      {"below_horizon", "cos in {-2^-149, -1e-7, -0.5, -1}", {-kTiny[0], -1e-7, -0.5, -1.0}},
  };
}

namespace {

std::vector<double> all_cos(bool fp64) {
  std::vector<double> v;
  for (auto& c : cos_classes(fp64)) v.insert(v.end(), c.values.begin(), c.values.end());
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

// ---- Parameter grids -------------------------------------------------------
// α ∈ {0 where the model defines it, 1e-7, 1e-5, 1e-4, 1e-3, ..., 1, 2} and
// the catalog range's ends; the Phong exponent up to 1e6 and its end 1e7;
// η ∈ {1, 1 ± 1e-6, 1.5, 3, 1/1.5}; F0 ∈ {0, 1}.

struct ParamClass {
  std::string name, what;
  bool in_domain = true;
  std::vector<std::array<double, 2>> values;
};

// The classes of one term's parameters: "typical" first (used by the cosine
// regions), then the extremes (each swept over every cosine).
std::vector<ParamClass> param_classes(const Term& t) {
  std::vector<ParamClass> out;
  if (t.kind == Kind::F) {
    if (t.id == "schlick") {
      out.push_back({"typical", "f0 in {0.04, 0.5}", true, {{0.04, 0}, {0.5, 0}}});
      out.push_back({"f0_ends", "f0 in {0, 1}", true, {{0, 0}, {1, 0}}});
    } else if (t.id == "dielectric") {
      out.push_back({"typical", "eta in {1.5, 3}", true, {{1.5, 0}, {3, 0}}});
      out.push_back({"eta_near_1", "eta in {1, 1-1e-6, 1+1e-6}", true, {{1, 0}, {1 - 1e-6, 0}, {1 + 1e-6, 0}}});
      out.push_back({"tir", "eta in {1/1.5, 0.1}: total internal reflection", true, {{1 / 1.5, 0}, {0.1, 0}}});
      out.push_back({"eta_high", "eta = 10 (range end)", true, {{10, 0}}});
    } else if (t.id == "conductor") {
      out.push_back({"typical", "(n, k) in {(0.2, 3), (1.5, 1)}", true, {{0.2, 3}, {1.5, 1}}});
      out.push_back({"nk_extreme",
                     "(n, k) in {(1, 0), (1+1e-6, 0), (1, 1e-6), (0.01, 0), (0.01, 20), (10, 0), (10, 20)}",
                     true,
                     {{1, 0}, {1 + 1e-6, 0}, {1, 1e-6}, {0.01, 0}, {0.01, 20}, {10, 0}, {10, 20}}});
    } else {
      out.push_back({"typical", "no parameter", true, {{0, 0}}});
    }
    return out;
  }
  if (t.params.empty()) {
    out.push_back({"typical", "no parameter", true, {{0, 0}}});
    return out;
  }
  const Param& p = t.params[0];
  const bool phong = t.roughness == Roughness::PhongExponent;
  std::vector<double> cand = phong ? std::vector<double>{0, 1, 10, 100, 1e3, 1e4, 1e6, 1e7}
                                   : std::vector<double>{0, 1e-7, 1e-5, 1e-4, 1e-3, 1e-2, 0.1, 0.3, 0.5, 1, 2, 10};
  cand.push_back(p.lo);
  cand.push_back(p.hi);
  std::sort(cand.begin(), cand.end());
  cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
  ParamClass typical{"typical", phong ? "alpha_p in {10, 100, 1e3}" : "alpha in {1e-2, 0.1, 0.3, 0.5}", true, {}};
  ParamClass sharp{"sharp", phong ? "alpha_p in {1e4, 1e6, 1e7}" : "alpha in {0 where defined, 1e-7 .. 1e-3}", true, {}};
  ParamClass rough{"rough", phong ? "alpha_p in {0, 1}" : "alpha in {1, 2, 10} within the range", true, {}};
  for (double v : cand) {
    if (v < p.lo || v > p.hi) continue;
    ParamClass& c = phong ? (v >= 1e4 ? sharp : v <= 1 ? rough : typical) : (v <= 1e-3 ? sharp : v >= 1 ? rough : typical);
    c.values.push_back({v, 0});
  }
  for (auto* c : {&typical, &sharp, &rough})
    if (!c->values.empty()) out.push_back(*c);
  if (!phong && p.lo > 0)  // the catalog rejects 0: reported, not gated
    out.push_back({"zero_width", "alpha = 0, outside the catalog range (a delta; not a function)", false, {{0, 0}}});
  return out;
}

// ---- Geometry --------------------------------------------------------------

glm::dvec3 dir(double cos_theta, double phi) {
  double s = std::sqrt(std::max(0.0, (1.0 - cos_theta) * (1.0 + cos_theta)));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

// The cosines of a pair in the plane (φ = 0: same side, π: opposite sides),
// from the raw (possibly > 1 or < 0) cosines, in double.
std::array<double, 4> pair_cosines(double cl, double cv, double phi) {
  glm::dvec3 l = dir(std::min(cl, 1.0), 0.0), v = dir(std::min(cv, 1.0), phi);
  glm::dvec3 sum = l + v;
  double len = glm::length(sum);
  double NoH = len > 0 ? sum.z / len : 0.0, VoH = std::min(0.5 * len, 1.0);
  return {cl, cv, NoH, VoH};
}

std::string hx(double x) { return fmt::format("{:a}", x); }

const char* slot_name(int s) {
  static const char* n[] = {"pD", "pG", "f0", "f1", "kd"};
  return n[s];
}

std::string describe_params(const In& r, const Term* d, const Term* g, const Term* f) {
  std::string s;
  auto add = [&](const Term* t, size_t i, int slot) {
    if (t && i < t->params.size()) s += fmt::format(" {}={}", t->params[i].name, hx(r[6 + slot]));
  };
  add(d, 0, 0);
  add(g, 0, 1);
  add(f, 0, 2);
  add(f, 1, 3);
  if (!d && !g && !f) s += fmt::format(" {}={}", slot_name(0), hx(r[6]));
  return s;
}

// ---- Cases: single terms ---------------------------------------------------

// Regions of a term: every cosine class at the typical parameters, then every
// parameter extreme at every cosine; plus a dense θ x α scan for the plots.
template <class Fill>
void add_term_regions(CaseDef& c, const Term& t, bool fp64, bool g1, Fill fill) {
  auto pcs = param_classes(t);
  auto coss = cos_classes(fp64);
  for (auto& cc : coss) {
    std::string expect;
    if (cc.name == "below_horizon" && t.kind != Kind::F) expect = "0";
    if (g1 && (cc.name == "tan_zero" || cc.name == "above_one")) expect = "1";  // seed 000
    // F takes VoH = |l + v|/2 >= 0; below it the kernel uses |VoH| (seed 000,
    // c = |L.H|) and the reference clamps to 0: reported, not gated.
    bool in_domain = cc.in_domain && !(t.kind == Kind::F && cc.name == "below_horizon");
    int r = c.add_region({cc.name, cc.what + " x " + pcs[0].what, in_domain, expect});
    for (auto& p : pcs[0].values)
      for (double a : cc.values) fill(r, a, cc.values, p);
  }
  auto every = all_cos(fp64);
  if (t.kind == Kind::F) every.erase(std::remove_if(every.begin(), every.end(), [](double x) { return x < 0; }), every.end());
  for (size_t k = 1; k < pcs.size(); ++k) {
    int r = c.add_region({pcs[k].name, pcs[k].what + (t.kind == Kind::F ? " x every cos >= 0" : " x every cos"),
                          pcs[k].in_domain, ""});
    for (auto& p : pcs[k].values)
      for (double a : every) fill(r, a, every, p);
  }
}

// θ grid of the scans: near the normal θ = 10^(-8 + k/4) up to 1 rad, near
// grazing π/2 − θ = 10^(-8 + k/4) up to 0.5; cosθ formed without cancellation.
std::vector<std::pair<double, double>> scan_angles() {  // (theta, cos theta)
  std::vector<std::pair<double, double>> out;
  for (int k = 0; k <= 32; ++k) {
    double th = std::pow(10.0, -8.0 + 0.25 * k);
    out.push_back({th, std::cos(th)});
  }
  for (int k = 30; k >= 0; --k) {
    double d = std::pow(10.0, -8.0 + 0.25 * k);
    out.push_back({kPi / 2 - d, std::sin(d)});
  }
  return out;
}
const std::vector<double> kScanAlphas = {1e-4, 1e-3, 1e-2, 0.1, 0.3, 1.0};

CaseDef term_case(const Term& t, bool g1, bool fp64) {
  CaseDef c;
  c.info.group = "term";
  c.info.family = g1 ? "G1" : kind_name(t.kind);
  c.info.name = fmt::format("{} {}", c.info.family, t.id);
  c.info.formula = g1 ? t.g1_kernel_fn : t.formula;
  c.info.stable = t.stable;
  if (g1) {
    c.mode = kG1;
    c.g = &t;
    auto ref = t.ref_g1;
    c.ref = [ref](const In& r) { return ref(r[1], r[7]); };
    c.describe = [&t](const In& r) { return fmt::format("NoV={}", hx(r[1])) + describe_params(r, nullptr, &t, nullptr); };
    add_term_regions(c, t, fp64, true, [&](int reg, double a, const std::vector<double>&, std::array<double, 2> p) {
      Point pt;
      pt.region = reg;
      pt.in[1] = a;
      pt.in[7] = p[0];
      c.points.push_back(pt);
    });
  } else if (t.kind == Kind::D) {
    c.mode = kD;
    c.d = &t;
    auto ref = t.ref_d;
    c.ref = [ref](const In& r) { return ref(r[2], r[6]); };
    c.describe = [&t](const In& r) {
      return fmt::format("NoH={} sin2H={}", hx(r[2]), hx(r[4])) + describe_params(r, &t, nullptr, nullptr);
    };
    add_term_regions(c, t, fp64, false, [&](int reg, double a, const std::vector<double>&, std::array<double, 2> p) {
      Point pt;
      pt.region = reg;
      pt.in[2] = a;
      pt.in[6] = p[0];
      c.points.push_back(pt);
    });
  } else if (t.kind == Kind::G) {
    c.mode = kG;
    c.g = &t;
    auto ref = t.ref_g;
    c.ref = [ref](const In& r) { return ref(r[0], r[1], r[2], r[3], r[7]); };
    c.describe = [&t](const In& r) {
      return fmt::format("NoL={} NoV={} NoH={} VoH={}", hx(r[0]), hx(r[1]), hx(r[2]), hx(r[3])) +
             describe_params(r, nullptr, &t, nullptr);
    };
    // Pairs: one cosine from the region, the other from the region or 0.5,
    // light and view on the same side (φ = 0) or on opposite sides (φ = π).
    add_term_regions(c, t, fp64, false, [&](int reg, double a, const std::vector<double>& cls, std::array<double, 2> p) {
      std::vector<double> others = cls;
      others.push_back(0.5);
      for (double b : others)
        for (double phi : {0.0, kPi})
          for (int swap = 0; swap < 2; ++swap) {
            if (swap && a == b) continue;
            auto cs = swap ? pair_cosines(b, a, phi) : pair_cosines(a, b, phi);
            Point pt;
            pt.region = reg;
            for (int k = 0; k < 4; ++k) pt.in[k] = cs[k];
            pt.in[7] = p[0];
            c.points.push_back(pt);
          }
    });
  } else {
    c.mode = kF;
    c.f = &t;
    auto ref = t.ref_f;
    c.ref = [ref](const In& r) { return ref(r[3], r[8], r[9]); };
    c.describe = [&t](const In& r) { return fmt::format("VoH={}", hx(r[3])) + describe_params(r, nullptr, nullptr, &t); };
    add_term_regions(c, t, fp64, false, [&](int reg, double a, const std::vector<double>&, std::array<double, 2> p) {
      Point pt;
      pt.region = reg;
      pt.in[3] = a;
      pt.in[8] = p[0];
      pt.in[9] = p[1];
      c.points.push_back(pt);
    });
  }
  // Scan for the plots: D and G1 over θ (their one angle) at each alpha.
  if ((c.mode == kD || c.mode == kG1) && t.roughness != Roughness::None) {
    int r = c.add_region({"scan", "dense theta x alpha in {1e-4 .. 1} (plots)", true, ""});
    for (double alpha : kScanAlphas) {
      double native = native_from_alpha(t.roughness, alpha);
      if (native < t.params[0].lo || native > t.params[0].hi) continue;
      for (auto [th, cth] : scan_angles()) {
        Point pt;
        pt.region = r;
        pt.theta = th;
        pt.alpha = alpha;
        pt.in[c.mode == kD ? 2 : 1] = cth;
        pt.in[c.mode == kD ? 6 : 7] = native;
        c.points.push_back(pt);
      }
    }
  }
  return c;
}

// ---- Cases: assembled BRDFs -------------------------------------------------

glm::dvec3 mirror(const glm::dvec3& w) { return {-w.x, -w.y, w.z}; }
glm::dvec3 rot_z(const glm::dvec3& w, double a) {
  return {w.x * std::cos(a) - w.y * std::sin(a), w.x * std::sin(a) + w.y * std::cos(a), w.z};
}

// Direction pairs of the BRDF sweep (wi = light, wo = view, n = +z). Mirror
// pairs put h on the normal exactly (the peak of every D, the place a double
// reference resolves exactly); the rest keep θh >= ~1e-4 or on the normal.
}  // namespace

std::vector<PairSet> pair_sets(bool fp64) {
  const double az = 0.3;  // view azimuth: off the axes so x and y both round
  std::vector<PairSet> out;
  {
    PairSet s{"mirror", "wi = mirror of wo, cos in {1e-4, 0.1, 0.5, 0.9, 1-1e-4, 1}: h = n", "", {}};
    for (double c : {1e-4, 0.1, 0.5, 0.9, 1 - 1e-4, 1.0}) {
      glm::dvec3 wo = dir(c, az);
      s.pairs.push_back({mirror(wo), wo});
    }
    out.push_back(s);
  }
  {
    PairSet s{"near_mirror", "mirror turned by 1e-3 or 0.1 rad about n", "", {}};
    for (double c : {1e-4, 0.1, 0.5, 0.9, 1 - 1e-4})
      for (double d : {1e-3, 0.1}) {
        glm::dvec3 wo = dir(c, az);
        s.pairs.push_back({rot_z(mirror(wo), d), wo});
      }
    out.push_back(s);
  }
  {
    PairSet s{"grazing", "cos in {1e-20, 1e-7, 1e-4, 1e-2} with itself or 0.5, azimuth 0, pi/2, pi", "", {}};
    std::vector<double> cs = {kTiny[2], 1e-7, 1e-4, 1e-2};
    for (double a : cs)
      for (double b : {a, 0.5})
        for (double phi : {0.0, kPi / 2, kPi}) s.pairs.push_back({dir(a, az + phi), dir(b, az)});
    out.push_back(s);
  }
  {
    PairSet s{"normal", "cos in {1, 1-1ulp, 1-1e-7, 1-1e-4} pairwise, azimuth 0 or pi", "", {}};
    std::vector<double> cs = {1.0, one_minus_ulp(fp64), 1 - 1e-7, 1 - 1e-4};
    for (double a : cs)
      for (double b : cs)
        for (double phi : {0.0, kPi}) s.pairs.push_back({dir(a, az + phi), dir(b, az)});
    out.push_back(s);
  }
  {
    PairSet s{"mid", "cos in {0.2, 0.5, 0.8} pairwise, azimuth 0, pi/2, pi", "", {}};
    for (double a : {0.2, 0.5, 0.8})
      for (double b : {0.2, 0.5, 0.8})
        for (double phi : {0.0, kPi / 2, kPi}) s.pairs.push_back({dir(a, az + phi), dir(b, az)});
    out.push_back(s);
  }
  {
    PairSet s{"opposite", "wi ~ -wo along the horizon, z in {0, 2^-149, 1e-30, 1e-20, 1e-7, 1e-4}: h ~ 0/0", "", {}};
    for (double z : {0.0, kTiny[0], kTiny[1], kTiny[2], 1e-7, 1e-4}) {
      glm::dvec3 wo = dir(z, az);
      s.pairs.push_back({glm::dvec3(-wo.x, -wo.y, z), wo});
      s.pairs.push_back({rot_z(glm::dvec3(-wo.x, -wo.y, z), 1e-7), wo});
    }
    out.push_back(s);
  }
  {
    PairSet s{"below_horizon", "wi or wo (or both) below the horizon, and wi = -wo through the surface", "0", {}};
    glm::dvec3 up = dir(0.5, az);
    for (double z : {-kTiny[0], -1e-7, -0.5}) {
      s.pairs.push_back({dir(z, az + kPi), up});
      s.pairs.push_back({up, dir(z, az + kPi)});
      s.pairs.push_back({dir(z, az + kPi), dir(z, az)});
    }
    s.pairs.push_back({{0, 0, -1}, {0, 0, 1}});
    s.pairs.push_back({{0, 0, 1}, {0, 0, -1}});
    out.push_back(s);
  }
  {
    PairSet s{"non_unit", "mirror and mid pairs scaled by 1 -+ 8 ulp, and z = 1 + 1 ulp", "", {}};
    double e = 8 * (fp64 ? 0x1p-52 : 0x1p-23);
    for (double c : {0.2, 0.9, 1.0})
      for (double k : {1 - e, 1 + e}) {
        glm::dvec3 wo = dir(c, az);
        s.pairs.push_back({mirror(wo) * k, wo * k});
        s.pairs.push_back({dir(0.5, az + 2.0) * k, wo});
      }
    s.pairs.push_back({dir(0.6, 1.0), {0, 0, one_plus_ulps(1, fp64)}});
    s.pairs.push_back({{0, 0, one_plus_ulps(1, fp64)}, {0, 0, one_plus_ulps(1, fp64)}});
    out.push_back(s);
  }
  return out;
}

namespace {

// F parameters of the BRDF sweep (η = 1 and friends are swept on F alone).
std::vector<std::array<double, 2>> brdf_f_params(const Term& f) {
  if (f.id == "schlick") return {{0.04, 0}, {1, 0}};
  if (f.id == "dielectric") return {{1.5, 0}, {1 / 1.5, 0}};
  if (f.id == "conductor") return {{0.2, 3}};
  return {{0, 0}};
}

CaseDef brdf_case(const Term& d, const Term& g, const Term& f, bool fp64) {
  CaseDef c;
  c.info.group = "brdf";
  c.info.family = "BRDF";
  c.info.name = fmt::format("BRDF {}/{}/{}", d.id, g.id, f.id);
  c.info.formula = "D F G / (4 (n.l)(n.v))";
  c.info.stable = d.stable && g.stable && f.stable;
  c.mode = kBrdf;
  c.d = &d;
  c.g = &g;
  c.f = &f;
  const Term *pd = &d, *pg = &g, *pf = &f;
  c.ref = [pd, pg, pf](const In& r) {
    ref::BrdfSpec s{pd, pg, pf, r[6], r[7], r[8], r[9], r[10]};
    return ref::brdf(s, glm::dvec3(r[0], r[1], r[2]), glm::dvec3(r[3], r[4], r[5]));
  };
  c.describe = [pd, pg, pf](const In& r) {
    return fmt::format("wi=({}, {}, {}) wo=({}, {}, {})", hx(r[0]), hx(r[1]), hx(r[2]), hx(r[3]), hx(r[4]), hx(r[5])) +
           describe_params(r, pd, pg, pf);
  };
  // Shared width α, converted to each term's parameter; values outside a
  // term's range are skipped for that combination.
  std::vector<std::array<double, 2>> widths;  // (pd, pg)
  for (double a : {1e-7, 1e-4, 1e-2, 0.3, 1.0, 2.0}) {
    double nd = native_from_alpha(d.roughness, a), ng = g.params.empty() ? 0.0 : native_from_alpha(g.roughness, a);
    if (nd < d.params[0].lo || nd > d.params[0].hi) continue;
    if (!g.params.empty() && (ng < g.params[0].lo || ng > g.params[0].hi)) continue;
    widths.push_back({nd, ng});
  }
  auto fps = brdf_f_params(f);
  for (auto& ps : pair_sets(fp64)) {
    int r = c.add_region({ps.name, ps.what + "; alpha in {1e-7, 1e-4, 1e-2, 0.3, 1, 2} within range", true, ps.expect});
    for (auto& pr : ps.pairs)
      for (auto& w : widths)
        for (auto& fp : fps) {
          Point pt;
          pt.region = r;
          pt.in = {pr.wi.x, pr.wi.y, pr.wi.z, pr.wo.x, pr.wo.y, pr.wo.z, w[0], w[1], fp[0], fp[1], 0.0, 0.0};
          c.points.push_back(pt);
        }
  }
  return c;
}

// ---- Cases: whole models (catalog/models.hpp) --------------------------------

// A whole model's parameter points: its catalog cases (or the points a scene
// gives, --scene), then each parameter at the ends of its range with the
// others at their defaults.
std::vector<ModelParams> model_points(const Model& m, const StabilityOptions& opt) {
  std::vector<ModelParams> out;
  auto given = std::find_if(opt.model_points.begin(), opt.model_points.end(), [&](auto& e) { return e.first == m.id; });
  if (given != opt.model_points.end()) out = given->second;
  else for (auto& c : m.cases) out.push_back(c.p);
  for (size_t i = 0; i < m.params.size(); ++i)
    for (double v : {m.params[i].lo, m.params[i].hi}) {
      ModelParams p = model_defaults(m);
      p[i] = v;
      out.push_back(p);
    }
  return out;
}

CaseDef model_case(const Model& m, const StabilityOptions& opt) {
  const bool fp64 = opt.fp64;
  CaseDef c;
  c.info.group = "model";
  c.info.family = "MODEL";
  c.info.name = "MODEL " + m.id;
  // gated unless the catalog records (measured) where its kernel is not finite
  c.info.formula = m.formula + (m.unstable.empty() ? "" : " (not gated: " + m.unstable + ")");
  c.info.stable = m.unstable.empty();
  c.mode = kModel;
  c.model = &m;
  const Model* pm = &m;
  c.ref = [pm](const In& r) { return pm->ref(glm::dvec3(r[0], r[1], r[2]), glm::dvec3(r[3], r[4], r[5]), &r[6]); };
  c.describe = [pm](const In& r) {
    std::string s = fmt::format("wi=({}, {}, {}) wo=({}, {}, {})", hx(r[0]), hx(r[1]), hx(r[2]), hx(r[3]), hx(r[4]),
                                hx(r[5]));
    for (size_t i = 0; i < pm->params.size(); ++i) s += fmt::format(" {}={}", pm->params[i].name, hx(r[6 + i]));
    return s;
  };
  const std::vector<ModelParams> points = model_points(m, opt);
  auto add = [&](int region, const glm::dvec3& wi, const glm::dvec3& wo) {
    for (auto& p : points) {
      Point pt;
      pt.region = region;
      pt.in = {wi.x, wi.y, wi.z, wo.x, wo.y, wo.z, p[0], p[1], p[2], p[3], p[4], p[5], p[6]};
      c.points.push_back(pt);
    }
  };
  const std::string params = opt.model_points.empty() ? "; the model's catalog cases and each parameter at its range ends"
                                                       : "; the scene's parameter points and each parameter at its range ends";
  for (auto& ps : pair_sets(fp64)) {
    int r = c.add_region({ps.name, ps.what + params, true, ps.expect});
    for (auto& pr : ps.pairs) add(r, pr.wi, pr.wo);
  }
  // Each cosine class as the light's and as the view's cosine, against a mid
  // direction, retro-reflected and mirrored (a whole model need not be
  // symmetric, so both roles are swept).
  const double az = 0.3;
  const glm::dvec3 mid = dir(0.5, az + 2.0);
  for (auto& cc : cos_classes(fp64)) {
    int r = c.add_region({"cos_" + cc.name, cc.what + " as n.l and as n.v" + params, cc.in_domain,
                          cc.name == "below_horizon" ? "0" : ""});
    for (double v : cc.values) {
      // a raw cosine (above 1 or below 0 included) with the x, y of a unit vector at min(|c|, 1)
      glm::dvec3 d = dir(std::min(std::fabs(v), 1.0), az);
      d.z = v;
      add(r, d, mid);
      add(r, mid, d);
      add(r, d, d);
      if (v > 0) add(r, mirror(d), d);
    }
  }
  return c;
}

// ---- Cases: alternative formulations -----------------------------------------

enum Variant {  // = VAR_* in stability_variants.cl
  kDggxTan2, kDggxCos, kDggxSin2, kLambdaTan2, kLambdaCos, kLambdaDefault,
  kG1Lambda, kG1Closed, kVohDot, kVohHalfLength, kSin2hFromCos, kSin2hCross
};

struct VariantDef {
  Variant id;
  std::string family, form, formula;
  bool is_default;
};

const std::vector<VariantDef>& variant_table() {
  static const std::vector<VariantDef> t = {
      {kDggxTan2, "D_ggx", "via tan2", "a^2 / (pi c^4 (a^2 + tan^2)^2), tan^2 = (1-c^2)/c^2 (seed 000 form 1)", false},
      {kDggxCos, "D_ggx", "via (n.h)^2(a^2-1)+1", "a^2 / (pi (c^2 (a^2-1) + 1)^2) (seed 000 form 2)", false},
      {kDggxSin2, "D_ggx", "via |n x h|^2", "1 / (pi a^2 (c^2 + s^2/a^2)^2), s^2 = h.x^2+h.y^2 (kernel D_ggx)", true},
      {kLambdaTan2, "Lambda_ggx", "via tan2", "(-1 + sqrt(1 + a^2 tan^2)) / 2, tan^2 = (1-c^2)/c^2 (Heitz 2014 eq. 72)",
       false},
      {kLambdaCos, "Lambda_ggx", "via cos", "(sqrt(a^2 + (1-a^2) c^2) / c - 1) / 2", false},
      {kLambdaDefault, "Lambda_ggx", "via x/(2(1+sqrt(1+x)))",
       "x / (2 (1 + sqrt(1 + x))), x = a^2 (1-c)(1+c)/c^2 (kernel Lambda_ggx)", true},
      {kG1Lambda, "G1_smith_ggx", "via Lambda", "1 / (1 + Lambda) (kernel G1_smith_ggx)", true},
      {kG1Closed, "G1_smith_ggx", "closed form", "2 / (1 + sqrt(1 + a^2 tan^2)) (seed 000)", false},
      {kVohDot, "VoH", "dot(v, normalize(l+v))", "v . (l+v)/|l+v| (seed 000 H)", false},
      {kVohHalfLength, "VoH", "|l+v|/2", "|l + v| / 2 for unit l, v (brdf.cl)", true},
      {kSin2hFromCos, "sin2H", "from n.h", "(1 - n.h)(1 + n.h), n.h = normalize(l+v).z", false},
      {kSin2hCross, "sin2H", "|n x h|^2", "h.x^2 + h.y^2, h = (l+v)/|l+v| (brdf.cl)", true},
  };
  return t;
}

CaseDef variant_case(const VariantDef& v, bool fp64) {
  CaseDef c;
  c.info.group = "variant";
  c.info.family = v.family;
  c.info.name = fmt::format("variant {} {}", v.family, v.form);
  c.info.formula = v.formula;
  c.info.is_default = v.is_default;
  c.mode = kVariant;
  c.variant = v.id;
  const std::vector<double> alphas = {1e-7, 1e-5, 1e-4, 1e-3, 1e-2, 0.1, 0.3, 1, 2, 10};
  if (v.family == "D_ggx") {
    // Inputs: the half vector's components h = (r0, 0, r2); the reference
    // takes cos² and sin² from those components (Walter et al. 2007, eq. 33).
    c.ref = [](const In& r) {
      double x2 = r[0] * r[0], z2 = r[2] * r[2], n2 = x2 + z2;
      return r[2] <= 0 ? 0.0 : ref::D_ggx_cs(z2 / n2, x2 / n2, r[6]);
    };
    c.describe = [](const In& r) { return fmt::format("h=({}, 0, {}) alpha={}", hx(r[0]), hx(r[2]), hx(r[6])); };
    auto add = [&](int reg, double hxv, double hzv, double a, double theta) {
      Point pt;
      pt.region = reg;
      pt.in[0] = hxv;
      pt.in[2] = hzv;
      pt.in[6] = a;
      pt.theta = theta;
      pt.alpha = a;
      c.points.push_back(pt);
    };
    int rn = c.add_region({"normal", "theta_h in {0, 1e-8 .. 1e-2} x alpha in {1e-7 .. 10}", true, ""});
    int rm = c.add_region({"mid", "theta_h in {0.1, 0.5, 1, 1.4} x alpha", true, ""});
    int rg = c.add_region({"grazing", "cos theta_h in {2^-149, 1e-30, 1e-20, 1e-7, 1e-4, 1e-2} x alpha", true, ""});
    for (double a : alphas) {
      for (double th : {0.0, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2}) add(rn, std::sin(th), std::cos(th), a, NAN);
      for (double th : {0.1, 0.5, 1.0, 1.4}) add(rm, std::sin(th), std::cos(th), a, NAN);
      for (double z : {kTiny[0], kTiny[1], kTiny[2], 1e-7, 1e-4, 1e-2})
        add(rg, std::sqrt((1 - z) * (1 + z)), z, a, NAN);
    }
    int rs = c.add_region({"scan", "dense theta x alpha in {1e-4 .. 1} (plots)", true, ""});
    for (double a : kScanAlphas)
      for (auto [th, cth] : scan_angles()) add(rs, th < 1 ? std::sin(th) : std::cos(kPi / 2 - th), cth, a, th);
  } else if (v.family == "Lambda_ggx" || v.family == "G1_smith_ggx") {
    bool lambda = v.family == "Lambda_ggx";
    if (lambda)
      c.ref = [](const In& r) { return ref::Lambda_ggx(r[1], r[7]); };
    else
      c.ref = [](const In& r) { return ref::G1_smith_ggx(r[1], r[7]); };
    c.describe = [](const In& r) { return fmt::format("NoV={} alpha={}", hx(r[1]), hx(r[7])); };
    for (auto& cc : cos_classes(fp64)) {
      std::string expect;
      if (cc.name == "tan_zero" || cc.name == "above_one") expect = lambda ? "0" : "1";
      if (cc.name == "below_horizon" && !lambda) expect = "0";
      int r = c.add_region({cc.name, cc.what + " x alpha in {1e-7 .. 10}", cc.in_domain, expect});
      for (double a : alphas)
        for (double cv : cc.values) {
          Point pt;
          pt.region = r;
          pt.in[1] = cv;
          pt.in[7] = a;
          c.points.push_back(pt);
        }
    }
    int rs = c.add_region({"scan", "dense theta x alpha in {1e-4 .. 1} (plots)", true, ""});
    for (double a : kScanAlphas)
      for (auto [th, cth] : scan_angles()) {
        Point pt;
        pt.region = rs;
        pt.in[1] = cth;
        pt.in[7] = a;
        pt.theta = th;
        pt.alpha = a;
        c.points.push_back(pt);
      }
  } else {  // half vector
    bool voh = v.family == "VoH";
    c.ref = [voh](const In& r) {
      // seed 000: H = (L + V)/|L + V| of the directions made unit in double
      glm::dvec3 wi = glm::normalize(glm::dvec3(r[0], r[1], r[2])), wo = glm::normalize(glm::dvec3(r[3], r[4], r[5]));
      if (voh) return ref::shading_from(wi, wo).VoH;
      glm::dvec3 h = glm::normalize(wi + wo);
      return h.x * h.x + h.y * h.y;
    };
    c.describe = [](const In& r) {
      return fmt::format("wi=({}, {}, {}) wo=({}, {}, {})", hx(r[0]), hx(r[1]), hx(r[2]), hx(r[3]), hx(r[4]), hx(r[5]));
    };
    for (auto& ps : pair_sets(fp64)) {
      if (ps.name == "below_horizon") continue;  // no half vector is formed there
      int r = c.add_region({ps.name, ps.what, true, ""});
      for (auto& pr : ps.pairs) {
        if (pr.wi.z <= 0 || pr.wo.z <= 0) continue;  // brdf_eval returns before forming h
        Point pt;
        pt.region = r;
        pt.in = {pr.wi.x, pr.wi.y, pr.wi.z, pr.wo.x, pr.wo.y, pr.wo.z, 0, 0, 0, 0, 0, 0};
        c.points.push_back(pt);
      }
    }
  }
  return c;
}

// ---- Evaluation ------------------------------------------------------------

void account(RegionResult& R, const CaseDef& c, const In& in, double k, double ref_exact, bool fp64) {
  R.points++;
  // A reference beyond the format's largest number is infinite in that format.
  const double big = fp64 ? std::numeric_limits<double>::max() : std::numeric_limits<float>::max();
  double ref = std::fabs(ref_exact) > big ? std::copysign(std::numeric_limits<double>::infinity(), ref_exact) : ref_exact;
  bool nan = std::isnan(k);
  bool inf = std::isinf(k) && std::isfinite(ref);
  bool neg = k < 0 && ref >= 0;
  R.nan += nan;
  R.inf += inf;
  R.negative += neg;
  bool inaccurate = false;
  if (std::isfinite(k) && std::isfinite(ref)) {
    double diff = std::fabs(k - ref);
    // Results that are both below the smallest normal number (flushed or
    // gradual underflow) are not scored: ULPs of subnormals say nothing.
    bool subnormal = std::max(std::fabs(k), std::fabs(ref)) < min_normal(fp64);
    double ulps = subnormal ? 0.0 : diff / ulp_of(ref, fp64);
    double rel = subnormal || std::fabs(ref) < min_normal(fp64) ? 0.0 : diff / std::fabs(ref);
    // Beyond kBreakUlps, except where both are within the underflow floor of 0.
    inaccurate = ulps > kBreakUlps && diff > min_normal(fp64);
    R.max_rel = std::max(R.max_rel, rel);
    if (ulps > R.max_ulps || R.worst.empty()) {
      if (ulps > R.max_ulps) R.max_ulps = ulps;
      R.worst = fmt::format("{} kernel={} reference={}", c.describe(in), hx(k), hx(ref));
    }
    // Conditioning allowance (as in mfv agree): no format can do better than
    // what the exact function does when one input moves by one rounding, so
    // an error within twice that is the input's, not the formula's.
    if (inaccurate) {
      const double eps = fp64 ? 0x1p-52 : 0x1p-23;
      double dev = 0;
      for (int j = 0; j < kIn; ++j)
        for (double b : {eps, -eps}) {
          if (in[j] == 0) continue;
          In moved = in;
          moved[j] *= 1.0 + b;
          double v = c.ref(moved);
          if (std::fabs(v) > big) continue;
          if (std::isfinite(v)) dev = std::max(dev, std::fabs(v - ref));
        }
      inaccurate = diff > 2.0 * dev;
    }
  } else if (std::isinf(ref) && !nan && k != ref) {
    inaccurate = true;  // the limit is infinite and the kernel is not
  }
  bool wrong_value = false;
  if (!R.expect.empty()) {
    double e = R.expect == "1" ? 1.0 : 0.0;
    R.violations += !(k == e);
    R.ref_violations += !(ref == e);
    wrong_value = !(k == e) && ref == e;
  }
  const bool is_g = c.mode == kG || c.mode == kG1;
  const bool above_one = is_g && k > 1 + kGOvershoot && !(ref > 1 + kGOvershoot);
  if (!nan && (wrong_value || neg || above_one)) {
    R.out_of_domain++;
    if (R.first_out_of_domain.empty())
      R.first_out_of_domain = fmt::format("{} kernel={} reference={}{}", c.describe(in), hx(k), hx(ref),
                                          wrong_value ? " (expected " + R.expect + ")"
                                          : neg       ? " (negative)"
                                                      : " (G above 1)");
  }
  if (nan || inf || neg || inaccurate) {
    R.breaks++;
    if (R.first_break.empty())
      R.first_break = fmt::format("{} kernel={} reference={}", c.describe(in), hx(k), hx(ref));
  }
}

template <class T>
std::vector<double> run_kernel(Runtime& rt, cl::Kernel& kern, const CaseDef& c, const std::vector<In>& rounded) {
  // Launched in work-groups of one size (PoCL compiles a work-group function
  // per local size): 64, or what the device and kernel allow; the tail is
  // padded with zero records.
  const size_t kLocal = fit_local_size(kern, rt.device().device, 64);
  size_t n = (rounded.size() + kLocal - 1) / kLocal * kLocal;
  std::vector<T> in(n * kIn, T(0)), out(n);
  for (size_t i = 0; i < rounded.size(); ++i)
    for (int k = 0; k < kIn; ++k) in[i * kIn + k] = static_cast<T>(rounded[i][k]);
  cl::Buffer in_buf(rt.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, in.size() * sizeof(T), in.data());
  cl::Buffer out_buf(rt.context(), CL_MEM_WRITE_ONLY, n * sizeof(T));
  // Sentinel: a result the kernel did not write reads as NaN and cannot pass.
  rt.queue().enqueueFillBuffer(out_buf, std::numeric_limits<T>::quiet_NaN(), 0, n * sizeof(T));
  kern.setArg(0, static_cast<cl_int>(c.mode));
  kern.setArg(1, static_cast<cl_int>(c.model ? int(c.model->number()) : c.d ? term_index(*c.d) : 0));
  kern.setArg(2, static_cast<cl_int>(c.g ? term_index(*c.g) : 0));
  kern.setArg(3, static_cast<cl_int>(c.f ? term_index(*c.f) : 0));
  kern.setArg(4, static_cast<cl_int>(c.variant));
  kern.setArg(5, in_buf);
  kern.setArg(6, out_buf);
  rt.queue().enqueueNDRangeKernel(kern, cl::NullRange, cl::NDRange(n), cl::NDRange(kLocal));
  rt.queue().enqueueReadBuffer(out_buf, CL_TRUE, 0, n * sizeof(T), out.data());
  return std::vector<double>(out.begin(), out.begin() + rounded.size());
}

std::vector<CaseDef> make_cases(const StabilityOptions& opt) {
  std::vector<CaseDef> cases;
  for (auto& t : catalog()) {
    cases.push_back(term_case(t, false, opt.fp64));
    if (!t.g1_kernel_fn.empty() && t.id != "smith_ggx_correlated")  // shares smith_ggx's G1
      cases.push_back(term_case(t, true, opt.fp64));
  }
  for (auto& v : variant_table()) cases.push_back(variant_case(v, opt.fp64));
  if (opt.combinations)
    for (auto* d : terms_of(Kind::D))
      for (auto* g : terms_of(Kind::G))
        for (auto* f : terms_of(Kind::F)) cases.push_back(brdf_case(*d, *g, *f, opt.fp64));
  if (opt.models)
    for (auto& m : models()) cases.push_back(model_case(m, opt));
  if (!opt.only.empty()) {
    std::vector<CaseDef> kept;
    for (auto& c : cases)
      for (auto& o : opt.only)
        if (c.info.name.find(o) != std::string::npos) {
          kept.push_back(std::move(c));
          break;
        }
    if (kept.empty()) throw Error("--only matches no stability case (see 'mfv list'; variants are named 'variant ...')");
    cases = std::move(kept);
  }
  return cases;
}

}  // namespace

StabilityReport run_stability(Runtime& rt, const StabilityOptions& opt) {
  auto t_start = std::chrono::steady_clock::now();
  if (opt.fp64 && !rt.device().fp64)
    throw Error(fmt::format("device '{}' has no cl_khr_fp64; run without --fp64", rt.device().name));
  auto cases = make_cases(opt);

  // Compile only the terms the selected cases use (docs/design.md §5).
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
  if (opt.fp64) defines.push_back("MFV_DOUBLE");

  StabilityReport rep;
  rep.device = rt.device().name;
  rep.platform = rt.device().platform;
  rep.driver = rt.device().driver;
  rep.precision = opt.fp64 ? "float64" : "float32";
  rep.build_options = rt.base_options() + (opt.fp64 ? " -DMFV_DOUBLE" : "");
  auto build0 = rt.build_stats().seconds;
  cl::Program prog = rt.build({"common.cl", "terms_d.cl", "terms_g.cl", "terms_f.cl", "models.cl", "model_gltf.cl",
                               "brdf.cl", "stability_variants.cl", "stability.cl"},
                              defines, dispatch, "brdf.cl");
  rep.build_seconds = rt.build_stats().seconds - build0;
  cl::Kernel kern(prog, "stability_eval");

  progress::Task task("stability: cases", cases.size());
  for (auto& c : cases) {
    task.advance(1);
    std::vector<In> rounded(c.points.size());
    for (size_t i = 0; i < c.points.size(); ++i) {
      for (int k = 0; k < kIn; ++k) rounded[i][k] = rnd(c.points[i].in[k], opt.fp64);
      // D: the caller's sin²θh = (1 - c)(1 + c) of the rounded cosine, in double, then rounded.
      if (c.mode == kD) {
        double cn = std::clamp(rounded[i][2], -1.0, 1.0);
        rounded[i][4] = rnd((1.0 - cn) * (1.0 + cn), opt.fp64);
      }
    }
    auto t0 = std::chrono::steady_clock::now();
    std::vector<double> values = opt.fp64 ? run_kernel<cl_double>(rt, kern, c, rounded)
                                          : run_kernel<cl_float>(rt, kern, c, rounded);
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
      RegionResult& rr = sc.regions[c.points[i].region];
      account(rr, c, rounded[i], values[i], ref, opt.fp64);
      if (!std::isnan(c.points[i].theta)) {
        double k = values[i];
        double u = std::isfinite(k) && std::isfinite(ref) ? std::fabs(k - ref) / ulp_of(ref, opt.fp64)
                   : (k == ref) ? 0.0 : std::numeric_limits<double>::infinity();
        if (k < 0 && ref >= 0) u = std::numeric_limits<double>::infinity();
        scan.points.push_back({c.points[i].theta, c.points[i].alpha, u});
      }
    }
    auto t2 = std::chrono::steady_clock::now();
    rep.kernel_seconds += std::chrono::duration<double>(t1 - t0).count();
    rep.reference_seconds += std::chrono::duration<double>(t2 - t1).count();
    rep.points += c.points.size();
    if (sc.stable)
      for (auto& r : sc.regions) {
        if (r.in_domain && (r.nan || r.inf))
          rep.gate_failures.push_back(fmt::format("{} is marked stable but gives {} NaN and {} Inf in region '{}'; first: {}",
                                                  sc.name, r.nan, r.inf, r.region, r.first_break));
        if (r.in_domain && r.out_of_domain)
          rep.gate_failures.push_back(fmt::format("{} is marked stable but gives {} of {} values outside the domain in "
                                                  "region '{}' where the reference stays inside; first: {}",
                                                  sc.name, r.out_of_domain, r.points, r.region, r.first_out_of_domain));
      }
    if (!scan.points.empty()) rep.scans.push_back(std::move(scan));
    rep.cases.push_back(std::move(sc));
  }
  rep.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return rep;
}

}  // namespace mfv
