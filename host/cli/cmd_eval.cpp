// mfv eval: one term or one D/G/F BRDF at one point, on the device and in the
// double reference, and how far apart they are.
#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "catalog/roughness.hpp"
#include "checks/agree.hpp"
#include "cli/commands.hpp"
#include "runtime/error.hpp"
#include "util/parse.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <sstream>

namespace mfv::cli {
namespace {

std::array<float, 3> parse_direction(const std::string& what, const std::string& text) {
  auto parts = split(text, ',');
  if (parts.size() != 3) throw Error(fmt::format("{} needs three comma-separated numbers, got '{}'", what, text));
  std::array<float, 3> v{};
  for (int i = 0; i < 3; ++i) {
    double x = parse_number(what, parts[i]);
    if (!std::isfinite(x)) throw Error(fmt::format("{} has a non-finite component", what));
    v[i] = static_cast<float>(x);
  }
  return v;
}

// A term's native parameter: --param NAME=V if given, else from --alpha.
double term_param(const Term& t, size_t i, std::map<std::string, double>& given, double alpha, bool alpha_given) {
  const Param& p = t.params[i];
  double v = p.fallback;
  if (auto it = given.find(p.name); it != given.end()) {
    v = it->second;
    given.erase(it);
  } else if (i == 0 && alpha_given && t.roughness != Roughness::None) {
    v = native_from_alpha(t.roughness, alpha);
  }
  validate_param(t, i, v);
  return v;
}

}  // namespace

void add_eval(CLI::App& app, Globals& g, int& rc) {
  auto* cmd = app.add_subcommand("eval", "evaluate one term or one D/G/F BRDF at one point on the device and in "
                                         "the reference");
  static std::string spec, wi_s = "0,0,1", wo_s = "0,0,1";
  static std::vector<std::string> params;
  static double alpha = 0.3, kd = 0.0;
  static double NoL = 1, NoV = 1, NoH = 1, VoH = 1;
  static bool g1 = false, fp64 = false;
  cmd->add_option("spec", spec, "a term id (ggx, smith_ggx, schlick...), a BRDF D/G/F (ggx/smith_ggx/schlick) or "
                                "a whole model (lambert, eon, phong_004...)")
      ->required();
  auto* alpha_opt = cmd->add_option("--alpha", alpha, "shared width alpha, converted to each term's parameter");
  cmd->add_option("--param", params, "native parameter NAME=VALUE (alpha_p, rho, m, f0, eta, n, k...)");
  cmd->add_option("--kd", kd, "Lambert albedo added to a BRDF");
  cmd->add_option("--wi", wi_s, "light direction x,y,z (n = +z)");
  cmd->add_option("--wo", wo_s, "view direction x,y,z");
  cmd->add_option("--NoL", NoL, "cos between normal and light (single terms)");
  cmd->add_option("--NoV", NoV, "cos between normal and view (single terms)");
  cmd->add_option("--NoH", NoH, "cos between normal and half vector (single terms)");
  cmd->add_option("--VoH", VoH, "cos between view and half vector (single terms)");
  cmd->add_flag("--g1", g1, "evaluate a Smith G term's G1 (at NoV) instead of its G2");
  cmd->add_flag("--fp64", fp64, "evaluate the kernel in double");
  cmd->callback([&g, &rc, alpha_opt] {
    std::map<std::string, double> given;
    for (auto& p : params) {
      auto kv = split(p, '=');
      if (kv.size() != 2) throw Error(fmt::format("--param wants NAME=VALUE, got '{}'", p));
      given[kv[0]] = parse_number("--param " + kv[0], kv[1]);
    }
    bool alpha_given = alpha_opt->count() > 0;
    if (alpha_given && !(alpha > 0.0 && std::isfinite(alpha)))
      throw Error(fmt::format("--alpha = {} must be a positive finite number", alpha));
    if (!(kd >= 0.0 && kd <= 1.0)) throw Error(fmt::format("--kd = {} is out of range [0, 1]", kd));
    for (double c : {NoL, NoV, NoH, VoH})
      if (!std::isfinite(c)) throw Error("cosines must be finite numbers");

    PointSpec ps;
    auto parts = split(spec, '/');
    if (parts.size() == 3) {
      ps.mode = EvalMode::Brdf;
      ps.d = &find_term(parts[0]);
      ps.g = &find_term(parts[1]);
      ps.f = &find_term(parts[2]);
      if (ps.d->kind != Kind::D || ps.g->kind != Kind::G || ps.f->kind != Kind::F)
        throw Error(fmt::format("'{}' must name a D, a G and an F term, in that order", spec));
      auto wi = parse_direction("--wi", wi_s), wo = parse_direction("--wo", wo_s);
      for (int i = 0; i < 3; ++i) ps.inputs[i] = wi[i], ps.inputs[3 + i] = wo[i];
      ps.params[0] = static_cast<float>(term_param(*ps.d, 0, given, alpha, alpha_given));
      if (!ps.g->params.empty()) ps.params[1] = static_cast<float>(term_param(*ps.g, 0, given, alpha, alpha_given));
      for (size_t i = 0; i < ps.f->params.size(); ++i)
        ps.params[2 + i] = static_cast<float>(term_param(*ps.f, i, given, alpha, alpha_given));
      ps.params[4] = static_cast<float>(kd);
    } else if (const Model* m = parts.size() == 1 ? try_find_model(spec) : nullptr) {
      // a whole model: f(wi, wo) with its parameters by name, defaults otherwise
      if (alpha_given) throw Error(fmt::format("'{}' is a whole model: give its parameters with --param", spec));
      ps.mode = EvalMode::Model;
      ps.model = m;
      auto wi = parse_direction("--wi", wi_s), wo = parse_direction("--wo", wo_s);
      for (int i = 0; i < 3; ++i) ps.inputs[i] = wi[i], ps.inputs[3 + i] = wo[i];
      for (size_t i = 0; i < m->params.size(); ++i) {
        double v = m->params[i].fallback;
        if (auto it = given.find(m->params[i].name); it != given.end()) {
          v = it->second;
          given.erase(it);
        }
        validate_model_param(*m, i, v);
        ps.params[i] = static_cast<float>(v);
      }
    } else if (parts.size() == 1) {
      const Term& t = find_term(spec);
      float cos[6] = {float(NoL), float(NoV), float(NoH), float(VoH), 0, 0};
      std::copy(cos, cos + 6, ps.inputs);
      if (t.kind == Kind::D) ps.mode = EvalMode::D, ps.d = &t;
      if (t.kind == Kind::G) ps.mode = g1 ? EvalMode::G1 : EvalMode::G, ps.g = &t;
      if (t.kind == Kind::F) ps.mode = EvalMode::F, ps.f = &t;
      if (g1 && (t.kind != Kind::G || !t.ref_g1)) throw Error(fmt::format("'{}' has no Smith G1", t.id));
      int slot = t.kind == Kind::D ? 0 : t.kind == Kind::G ? 1 : 2;
      for (size_t i = 0; i < t.params.size(); ++i)
        ps.params[slot + i] = static_cast<float>(term_param(t, i, given, alpha, alpha_given));
    } else {
      throw Error(fmt::format("'{}' is neither a term id nor D/G/F", spec));
    }
    if (!given.empty()) throw Error(fmt::format("parameter '{}' belongs to none of the terms in '{}'", given.begin()->first, spec));

    Runtime rt(g.device, g.kernel_dir);
    PointResult r = eval_point(rt, ps, fp64);
    fmt::print("kernel    {:.9g}  ({:a})  on {}, {}\n", r.kernel, r.kernel, rt.device().name, fp64 ? "float64" : "float32");
    fmt::print("reference {:.17g}  ({:a})  double\n", r.reference, r.reference);
    fmt::print("relative error {:.3g}, {:.3g} ulps\n", r.rel, r.ulps);
    rc = 0;
  });
}

}  // namespace mfv::cli
