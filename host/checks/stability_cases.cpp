// mfv stability's cases of single terms, assembled BRDFs and whole models:
// the regions of the sweep and their points (issue 6, "Sweep").
#include "checks/stability_cases.hpp"

#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "catalog/roughness.hpp"
#include "checks/pointwise_inputs.hpp"
#include "reference/brdf.hpp"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace mfv::stability_detail {

std::string hx(double x) { return fmt::format("{:a}", x); }

namespace {

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
  ParamClass sharp{
      "sharp", phong ? "alpha_p in {1e4, 1e6, 1e7}" : "alpha in {0 where defined, 1e-7 .. 1e-3}", true, {}};
  ParamClass rough{"rough", phong ? "alpha_p in {0, 1}" : "alpha in {1, 2, 10} within the range", true, {}};
  for (double v : cand) {
    if (v < p.lo || v > p.hi) continue;
    ParamClass& c = phong ? (v >= 1e4 ? sharp
                             : v <= 1 ? rough
                                      : typical)
                          : (v <= 1e-3 ? sharp
                             : v >= 1  ? rough
                                       : typical);
    c.values.push_back({v, 0});
  }
  for (auto* c : {&typical, &sharp, &rough})
    if (!c->values.empty()) out.push_back(*c);
  if (!phong && p.lo > 0)  // the catalog rejects 0: reported, not gated
    out.push_back({"zero_width", "alpha = 0, outside the catalog range (a delta; not a function)", false, {{0, 0}}});
  return out;
}

// ---- Geometry --------------------------------------------------------------

std::array<double, 4> pair_cosines(double cl, double cv, double phi) {
  glm::dvec3 l = dir(std::min(cl, 1.0), 0.0), v = dir(std::min(cv, 1.0), phi);
  glm::dvec3 sum = l + v;
  double len = glm::length(sum);
  double NoH = len > 0 ? sum.z / len : 0.0, VoH = std::min(0.5 * len, 1.0);
  return {cl, cv, NoH, VoH};
}

const char* slot_name(int s) {
  static const char* n[] = {"pD", "pG", "f0", "f1", "kd"};
  return n[s];
}

std::string describe_params(const In& r, const Term* d, const Term* g, const Term* f) {
  std::string s;
  auto add = [&](const Term* t, size_t i, int slot) {
    if (t && i < t->params.size()) s += fmt::format(" {}={}", t->params[i].name, hx(r[PW_P0 + slot]));
  };
  add(d, 0, 0);
  add(g, 0, 1);
  add(f, 0, 2);
  add(f, 1, 3);
  if (!d && !g && !f) s += fmt::format(" {}={}", slot_name(0), hx(r[PW_P0]));
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
    // seed 000 (G1 = 1 where tan = 0), unless the catalog says the term's Λ is a fit that is not 0 there
    if (g1 && t.g1_not_one_at_normal.empty() && (cc.name == "tan_zero" || cc.name == "above_one")) expect = "1";
    // F takes VoH = |l + v|/2 >= 0; below it the kernel uses |VoH| (seed 000,
    // c = |L.H|) and the reference clamps to 0: reported, not gated.
    bool in_domain = cc.in_domain && !(t.kind == Kind::F && cc.name == "below_horizon");
    int r = c.add_region({cc.name, cc.what + " x " + pcs[0].what, in_domain, expect});
    for (auto& p : pcs[0].values)
      for (double a : cc.values) fill(r, a, cc.values, p);
  }
  auto every = all_cos(fp64);
  if (t.kind == Kind::F)
    every.erase(std::remove_if(every.begin(), every.end(), [](double x) { return x < 0; }), every.end());
  for (size_t k = 1; k < pcs.size(); ++k) {
    int r = c.add_region(
        {pcs[k].name, pcs[k].what + (t.kind == Kind::F ? " x every cos >= 0" : " x every cos"), pcs[k].in_domain, ""});
    for (auto& p : pcs[k].values)
      for (double a : every) fill(r, a, every, p);
  }
}

}  // namespace

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
    out.push_back({M_PI / 2 - d, std::sin(d)});
  }
  return out;
}
const std::vector<double> kScanAlphas = {1e-4, 1e-3, 1e-2, 0.1, 0.3, 1.0};

namespace {

// Scan for the plots: D and G1 over θ (their one angle) at each alpha.
void add_scan(CaseDef& c, const Term& t) {
  if ((c.mode == PW_D || c.mode == PW_G1) && t.roughness != Roughness::None) {
    int r = c.add_region({"scan", "dense theta x alpha in {1e-4 .. 1} (plots)", true, ""});
    for (double alpha : kScanAlphas) {
      double native = native_from_alpha(t.roughness, alpha);
      if (native < t.params[0].lo || native > t.params[0].hi) continue;
      for (auto [th, cth] : scan_angles()) {
        Point pt;
        pt.region = r;
        pt.theta = th;
        pt.alpha = alpha;
        pt.in[c.mode == PW_D ? PW_NOH : PW_NOV] = cth;
        pt.in[c.mode == PW_D ? PW_PD : PW_PG] = native;
        c.points.push_back(pt);
      }
    }
  }
}

// A G2 term: pairs of cosines, one from the region, the other from the
// region or 0.5, light and view on the same side (φ = 0) or on opposite
// sides (φ = π).
void g_term(CaseDef& c, const Term& t, bool fp64) {
  c.mode = PW_G;
  c.g = &t;
  auto ref = t.ref_g;
  c.ref = [ref](const In& r) { return ref(r[PW_NOL], r[PW_NOV], r[PW_NOH], r[PW_VOH], r[PW_PG]); };
  c.describe = [&t](const In& r) {
    return fmt::format("NoL={} NoV={} NoH={} VoH={}", hx(r[PW_NOL]), hx(r[PW_NOV]), hx(r[PW_NOH]), hx(r[PW_VOH])) +
           describe_params(r, nullptr, &t, nullptr);
  };
  // Pairs: one cosine from the region, the other from the region or 0.5,
  // light and view on the same side (φ = 0) or on opposite sides (φ = π).
  add_term_regions(c, t, fp64, false, [&](int reg, double a, const std::vector<double>& cls, std::array<double, 2> p) {
    std::vector<double> others = cls;
    others.push_back(0.5);
    for (double b : others)
      for (double phi : {0.0, M_PI})
        for (int swap = 0; swap < 2; ++swap) {
          if (swap && a == b) continue;
          auto cs = swap ? pair_cosines(b, a, phi) : pair_cosines(a, b, phi);
          Point pt;
          pt.region = reg;
          for (int k = 0; k < 4; ++k) pt.in[size_t(PW_NOL + k)] = cs[size_t(k)];
          pt.in[PW_PG] = p[0];
          c.points.push_back(pt);
        }
  });
}

// The region sweep of a term of one input: the swept value at slot `input`,
// the region's parameters at the slots `params` (in the term's order).
void add_input_points(CaseDef& c, const Term& t, bool fp64, bool g1, int input, std::vector<int> params) {
  add_term_regions(c, t, fp64, g1, [&](int reg, double a, const std::vector<double>&, std::array<double, 2> p) {
    Point pt;
    pt.region = reg;
    pt.in[size_t(input)] = a;
    for (size_t k = 0; k < params.size(); ++k) pt.in[size_t(params[k])] = p[k];
    c.points.push_back(pt);
  });
}

}  // namespace

CaseDef term_case(const Term& t, bool g1, bool fp64) {
  CaseDef c;
  c.info.group = "term";
  c.info.family = g1 ? "G1" : kind_name(t.kind);
  c.info.name = fmt::format("{} {}", c.info.family, t.id);
  c.info.formula = g1 ? t.g1_kernel_fn : t.formula;
  c.info.stable = t.stable;
  if (g1) {
    c.mode = PW_G1;
    c.g = &t;
    auto ref = t.ref_g1;
    c.ref = [ref](const In& r) { return ref(r[PW_NOV], r[PW_PG]); };
    c.describe = [&t](const In& r) {
      return fmt::format("NoV={}", hx(r[PW_NOV])) + describe_params(r, nullptr, &t, nullptr);
    };
    add_input_points(c, t, fp64, true, PW_NOV, {PW_PG});
  } else if (t.kind == Kind::D) {
    c.mode = PW_D;
    c.d = &t;
    auto ref = t.ref_d;
    c.ref = [ref](const In& r) { return ref(r[PW_NOH], r[PW_PD]); };
    c.describe = [&t](const In& r) {
      return fmt::format("NoH={} sin2H={}", hx(r[PW_NOH]), hx(r[PW_SIN2H])) + describe_params(r, &t, nullptr, nullptr);
    };
    add_input_points(c, t, fp64, false, PW_NOH, {PW_PD});
  } else if (t.kind == Kind::G) {
    g_term(c, t, fp64);
  } else {
    c.mode = PW_F;
    c.f = &t;
    auto ref = t.ref_f;
    c.ref = [ref](const In& r) { return ref(r[PW_VOH], r[PW_F0], r[PW_F1]); };
    c.describe = [&t](const In& r) {
      return fmt::format("VoH={}", hx(r[PW_VOH])) + describe_params(r, nullptr, nullptr, &t);
    };
    add_input_points(c, t, fp64, false, PW_VOH, {PW_F0, PW_F1});
  }
  add_scan(c, t);
  return c;
}

namespace {

// F parameters of the BRDF sweep (η = 1 and friends are swept on F alone).
std::vector<std::array<double, 2>> brdf_f_params(const Term& f) {
  if (f.id == "schlick") return {{0.04, 0}, {1, 0}};
  if (f.id == "dielectric") return {{1.5, 0}, {1 / 1.5, 0}};
  if (f.id == "conductor") return {{0.2, 3}};
  return {{0, 0}};
}

}  // namespace

CaseDef brdf_case(const Term& d, const Term& g, const Term& f, bool fp64) {
  CaseDef c;
  c.info.group = "brdf";
  c.info.family = "BRDF";
  c.info.name = fmt::format("BRDF {}/{}/{}", d.id, g.id, f.id);
  c.info.formula = "D F G / (4 (n.l)(n.v))";
  c.info.stable = d.stable && g.stable && f.stable;
  c.mode = PW_BRDF;
  c.d = &d;
  c.g = &g;
  c.f = &f;
  const Term *pd = &d, *pg = &g, *pf = &f;
  c.ref = [pd, pg, pf](const In& r) {
    ref::BrdfSpec s{pd, pg, pf, r[PW_PD], r[PW_PG], r[PW_F0], r[PW_F1], r[PW_KD]};
    return ref::brdf(s, wi_of(r), wo_of(r));
  };
  c.describe = [pd, pg, pf](const In& r) {
    return fmt::format("wi=({}, {}, {}) wo=({}, {}, {})", hx(r[PW_WI_X]), hx(r[PW_WI_Y]), hx(r[PW_WI_Z]),
                       hx(r[PW_WO_X]), hx(r[PW_WO_Y]), hx(r[PW_WO_Z])) +
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
          pt.in = record(pr.wi, pr.wo, {w[0], w[1], fp[0], fp[1]});
          c.points.push_back(pt);
        }
  }
  return c;
}

// ---- Cases: whole models (catalog/models.hpp) --------------------------------

namespace {

// A whole model's parameter points: its catalog cases (or the points a scene
// gives, --scene), then each parameter at the ends of its range with the
// others at their defaults.
std::vector<ModelParams> model_points(const Model& m, const StabilityOptions& opt) {
  std::vector<ModelParams> out;
  auto given = std::find_if(opt.model_points.begin(), opt.model_points.end(), [&](auto& e) { return e.first == m.id; });
  if (given != opt.model_points.end())
    out = given->second;
  else
    for (auto& c : m.cases) out.push_back(c.p);
  for (size_t i = 0; i < m.params.size(); ++i)
    for (double v : {m.params[i].lo, m.params[i].hi}) {
      ModelParams p = model_defaults(m);
      p[i] = v;
      out.push_back(p);
    }
  return out;
}

}  // namespace

CaseDef model_case(const Model& m, const StabilityOptions& opt) {
  const bool fp64 = opt.fp64;
  CaseDef c;
  c.info.group = "model";
  c.info.family = "MODEL";
  c.info.name = "MODEL " + m.id;
  // gated unless the catalog records (measured) where its kernel is not finite
  c.info.formula = m.formula + (m.unstable.empty() ? "" : " (not gated: " + m.unstable + ")");
  c.info.stable = m.unstable.empty();
  c.mode = PW_MODEL;
  c.model = &m;
  const Model* pm = &m;
  c.ref = [pm](const In& r) { return pm->ref(wi_of(r), wo_of(r), &r[PW_P0]); };
  c.describe = [pm](const In& r) {
    std::string s = fmt::format("wi=({}, {}, {}) wo=({}, {}, {})", hx(r[PW_WI_X]), hx(r[PW_WI_Y]), hx(r[PW_WI_Z]),
                                hx(r[PW_WO_X]), hx(r[PW_WO_Y]), hx(r[PW_WO_Z]));
    for (size_t i = 0; i < pm->params.size(); ++i) s += fmt::format(" {}={}", pm->params[i].name, hx(r[PW_P0 + i]));
    return s;
  };
  const std::vector<ModelParams> points = model_points(m, opt);
  auto add = [&](int region, const glm::dvec3& wi, const glm::dvec3& wo) {
    for (auto& p : points) {
      Point pt;
      pt.region = region;
      pt.in = record(wi, wo, {p[0], p[1], p[2], p[3], p[4], p[5], p[6]});
      c.points.push_back(pt);
    }
  };
  const std::string params = opt.model_points.empty()
                                 ? "; the model's catalog cases and each parameter at its range ends"
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

}  // namespace mfv::stability_detail
