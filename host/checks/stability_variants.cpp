// mfv stability's alternative formulations (kernels/stability_variants.cl):
// each form of D_ggx, Lambda_ggx, G1_smith_ggx and the half vector, side by
// side with the one the kernels use, over the regions where forms differ.
#include "checks/stability_cases.hpp"

#include "checks/pointwise_inputs.hpp"
#include "reference/brdf.hpp"
#include "reference/reference.hpp"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <cmath>

namespace mfv::stability_detail {
namespace {

// ---- Cases: alternative formulations -----------------------------------------

enum Variant {  // = VAR_* in stability_variants.cl
  kDggxTan2,
  kDggxCos,
  kDggxSin2,
  kLambdaTan2,
  kLambdaCos,
  kLambdaDefault,
  kG1Lambda,
  kG1Closed,
  kVohDot,
  kVohHalfLength,
  kSin2hFromCos,
  kSin2hCross
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

// D_ggx: the half vector near the normal, at mid angles and at grazing, and
// the scan for the plots.
void d_ggx_points(CaseDef& c, const std::vector<double>& alphas) {
  // Inputs: the half vector's components h = (r0, 0, r2); the reference
  // takes cos² and sin² from those components (Walter et al. 2007, eq. 33).
  c.ref = [](const In& r) {
    double x2 = r[PW_H_X] * r[PW_H_X], z2 = r[PW_H_Z] * r[PW_H_Z], n2 = x2 + z2;
    return r[PW_H_Z] <= 0 ? 0.0 : ref::D_ggx_cs(z2 / n2, x2 / n2, r[PW_PD]);
  };
  c.describe = [](const In& r) {
    return fmt::format("h=({}, 0, {}) alpha={}", hx(r[PW_H_X]), hx(r[PW_H_Z]), hx(r[PW_PD]));
  };
  auto add = [&](int reg, double hxv, double hzv, double a, double theta) {
    Point pt;
    pt.region = reg;
    pt.in[PW_H_X] = hxv;
    pt.in[PW_H_Z] = hzv;
    pt.in[PW_PD] = a;
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
    for (double z : {kTinyCos[0], kTinyCos[1], kTinyCos[2], 1e-7, 1e-4, 1e-2})
      add(rg, std::sqrt((1 - z) * (1 + z)), z, a, NAN);
  }
  int rs = c.add_region({"scan", "dense theta x alpha in {1e-4 .. 1} (plots)", true, ""});
  for (double a : kScanAlphas)
    for (auto [th, cth] : scan_angles()) add(rs, th < 1 ? std::sin(th) : std::cos(M_PI / 2 - th), cth, a, th);
}

CaseDef variant_case(const VariantDef& v, bool fp64) {
  CaseDef c;
  c.info.group = "variant";
  c.info.family = v.family;
  c.info.name = fmt::format("variant {} {}", v.family, v.form);
  c.info.formula = v.formula;
  c.info.is_default = v.is_default;
  c.mode = PW_VARIANT;
  c.variant = v.id;
  const std::vector<double> alphas = {1e-7, 1e-5, 1e-4, 1e-3, 1e-2, 0.1, 0.3, 1, 2, 10};
  if (v.family == "D_ggx") {
    d_ggx_points(c, alphas);
  } else if (v.family == "Lambda_ggx" || v.family == "G1_smith_ggx") {
    bool lambda = v.family == "Lambda_ggx";
    if (lambda)
      c.ref = [](const In& r) { return ref::Lambda_ggx(r[PW_NOV], r[PW_PG]); };
    else
      c.ref = [](const In& r) { return ref::G1_smith_ggx(r[PW_NOV], r[PW_PG]); };
    c.describe = [](const In& r) { return fmt::format("NoV={} alpha={}", hx(r[PW_NOV]), hx(r[PW_PG])); };
    for (auto& cc : cos_classes(fp64)) {
      std::string expect;
      if (cc.name == "tan_zero" || cc.name == "above_one") expect = lambda ? "0" : "1";
      if (cc.name == "below_horizon" && !lambda) expect = "0";
      int r = c.add_region({cc.name, cc.what + " x alpha in {1e-7 .. 10}", cc.in_domain, expect});
      for (double a : alphas)
        for (double cv : cc.values) {
          Point pt;
          pt.region = r;
          pt.in[PW_NOV] = cv;
          pt.in[PW_PG] = a;
          c.points.push_back(pt);
        }
    }
    int rs = c.add_region({"scan", "dense theta x alpha in {1e-4 .. 1} (plots)", true, ""});
    for (double a : kScanAlphas)
      for (auto [th, cth] : scan_angles()) {
        Point pt;
        pt.region = rs;
        pt.in[PW_NOV] = cth;
        pt.in[PW_PG] = a;
        pt.theta = th;
        pt.alpha = a;
        c.points.push_back(pt);
      }
  } else {  // half vector
    bool voh = v.family == "VoH";
    c.ref = [voh](const In& r) {
      // seed 000: H = (L + V)/|L + V| of the directions made unit in double
      glm::dvec3 wi = glm::normalize(wi_of(r)), wo = glm::normalize(wo_of(r));
      if (voh) return ref::shading_from(wi, wo).VoH;
      glm::dvec3 h = glm::normalize(wi + wo);
      return h.x * h.x + h.y * h.y;
    };
    c.describe = [](const In& r) {
      return fmt::format("wi=({}, {}, {}) wo=({}, {}, {})", hx(r[PW_WI_X]), hx(r[PW_WI_Y]), hx(r[PW_WI_Z]),
                         hx(r[PW_WO_X]), hx(r[PW_WO_Y]), hx(r[PW_WO_Z]));
    };
    for (auto& ps : pair_sets(fp64)) {
      if (ps.name == "below_horizon") continue;  // no half vector is formed there
      int r = c.add_region({ps.name, ps.what, true, ""});
      for (auto& pr : ps.pairs) {
        if (pr.wi.z <= 0 || pr.wo.z <= 0) continue;  // brdf_eval returns before forming h
        Point pt;
        pt.region = r;
        pt.in = record(pr.wi, pr.wo, {});
        c.points.push_back(pt);
      }
    }
  }
  return c;
}

}  // namespace

std::vector<CaseDef> variant_cases(bool fp64) {
  std::vector<CaseDef> out;
  for (auto& v : variant_table()) out.push_back(variant_case(v, fp64));
  return out;
}

}  // namespace mfv::stability_detail
