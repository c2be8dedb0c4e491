// mfv eval: one term, one D/G/F BRDF, whole model or BTDF at one point, on the device and in the
// double reference, and how far apart they are.
#include "catalog/bsdfs.hpp"
#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "catalog/roughness.hpp"
#include "checks/agree.hpp"
#include "cli/shared_options.hpp"
#include "util/error.hpp"
#include "util/parse.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <sstream>

namespace mfv::cli {
namespace {

// A direction is unit when its float32 rounding is, up to that rounding: a
// unit vector w rounded componentwise to float (relative error u = 2^-24
// each) has ||w~| - 1| <= |w~ - w| <= u |w|; typed in decimal with 9
// significant digits (what the error message suggests) it is rounded twice,
// so the tolerance is 2u = 2^-23.
constexpr double kUnitTolerance = 0x1p-23;

std::array<float, 3> parse_direction(const std::string& what, const std::string& text) {
  auto parts = split(text, ',');
  if (parts.size() != 3) throw Error(fmt::format("{} needs three comma-separated numbers, got '{}'", what, text));
  std::array<float, 3> v{};
  double len2 = 0;
  for (int i = 0; i < 3; ++i) {
    double x = parse_number(what, parts[i]);
    if (!std::isfinite(x)) throw Error(fmt::format("{} has a non-finite component", what));
    v[i] = static_cast<float>(x);
    len2 += double(v[i]) * double(v[i]);
  }
  const double len = std::sqrt(len2);
  if (!(std::fabs(len - 1.0) <= kUnitTolerance)) {
    if (!(len > 0)) throw Error(fmt::format("{} {} is the zero vector; give a unit direction", what, text));
    throw Error(
        fmt::format("{} {} has length {:.9g}, not 1 within float rounding (2^-23); the unit vector is "
                    "{:.9g},{:.9g},{:.9g}",
                    what, text, len, v[0] / len, v[1] / len, v[2] / len));
  }
  return v;
}

// The --param values by name; each term reads what it needs, and a name no
// term read is an error at the end (none is silently dropped).
struct Given {
  std::map<std::string, double> values;
  std::set<std::string> used;
  const double* find(const std::string& name) {
    auto it = values.find(name);
    if (it == values.end()) return nullptr;
    used.insert(name);
    return &it->second;
  }
};

// A term's native parameter: --param NAME=V if given, else from --alpha.
double term_param(const Term& t, size_t i, Given& given, double alpha, bool alpha_given) {
  const Param& p = t.params[i];
  double v = p.fallback;
  if (const double* x = given.find(p.name))
    v = *x;
  else if (i == 0 && alpha_given && t.roughness != Roughness::None)
    v = native_from_alpha(t.roughness, alpha);
  validate_param(t, i, v);
  return v;
}

// The point: directions (unit, x,y,z) or cosines, and which of them were given.
struct EvalArgs {
  std::string wi = "0,0,1", wo = "0,0,1", h;
  double NoL = 1, NoV = 1, NoH = 1, VoH = 1;
  bool wi_given = false, wo_given = false, h_given = false, cosines_given = false;
};

// A single term: cosines for the isotropic ones; an anisotropic D takes the
// half vector (--h), an anisotropic G's G1 the view (--wo), in the tangent
// frame t = +x, b = +y, n = +z.
void single_term(PointSpec& ps, const Term& t, bool g1, const EvalArgs& a) {
  if (g1 && (t.kind != Kind::G || !(t.ref_g1 || t.ref_g1_aniso)))
    throw Error(fmt::format("'{}' has no Smith G1", t.id));
  if (!t.aniso) {
    if (a.h_given) throw Error(fmt::format("--h is for anisotropic D terms; give '{}' cosines (--NoH ...)", t.id));
    float cos[6] = {float(a.NoL), float(a.NoV), float(a.NoH), float(a.VoH), 0, 0};
    std::copy(cos, cos + 6, ps.inputs);
    ps.mode = t.kind == Kind::D ? EvalMode::D : t.kind == Kind::F ? EvalMode::F : g1 ? EvalMode::G1 : EvalMode::G;
    return;
  }
  if (a.cosines_given)
    throw Error(fmt::format("'{}' is anisotropic: cosines alone lose alpha_y; give {}", t.id,
                            t.kind == Kind::D ? "the half vector --h x,y,z" : "--g1 and the view --wo x,y,z"));
  if (t.kind == Kind::G && !g1)
    throw Error(
        fmt::format("'{}' is anisotropic: evaluate its G1 (--g1 --wo x,y,z) or a BRDF D/G/F with --wi, --wo", t.id));
  if (t.kind == Kind::D && !a.h_given)
    throw Error(fmt::format("'{}' is anisotropic: give the half vector --h x,y,z", t.id));
  if (t.kind == Kind::G && !a.wo_given)
    throw Error(fmt::format("'{}' G1 is anisotropic: give the view --wo x,y,z", t.id));
  auto w = t.kind == Kind::D ? parse_direction("--h", a.h) : parse_direction("--wo", a.wo);
  ps.inputs[t.kind == Kind::D ? 2 : 1] = w[2];
  ps.inputs[4] = w[0];
  ps.inputs[5] = w[1];
  ps.mode = t.kind == Kind::D ? EvalMode::DAniso : EvalMode::G1Aniso;
}

}  // namespace

namespace {

// mfv eval: its values, bound to its options, and its work.
struct EvalCommand : SharedValues {
  std::string spec;
  std::vector<std::string> params;
  double alpha = 0.3, kd = 0.0;
  bool g1 = false, fp64 = false;
  EvalArgs args;
  CLI::Option *alpha_opt = nullptr, *wi_opt = nullptr, *wo_opt = nullptr, *h_opt = nullptr;
  std::vector<CLI::Option*> cos_opts;

  void add_options(CLI::App* cmd) {
    cmd->description("evaluate one term or one D/G/F BRDF at one point on the device and in the reference");
    cmd->add_option("spec", spec,
                    "a term id (ggx, smith_ggx, schlick...), a BRDF D/G/F (ggx/smith_ggx/schlick) or "
                    "a whole model (lambert, eon, phong_004...) or a rough dielectric BTDF (walter_ggx_correlated...)")
        ->required();
    alpha_opt = cmd->add_option("--alpha", alpha, "shared width alpha, converted to each term's parameter");
    cmd->add_option("--param", params,
                    "native parameter NAME=VALUE (alpha_p, rho, m, f0, eta, n, k, alpha_x, alpha_y...)");
    cmd->add_option("--kd", kd, "Lambert albedo added to a BRDF");
    wi_opt = cmd->add_option("--wi", args.wi, "light direction x,y,z, unit (n = +z, tangent t = +x)");
    wo_opt = cmd->add_option("--wo", args.wo, "view direction x,y,z, unit (also the view of an anisotropic G1)");
    h_opt = cmd->add_option("--h", args.h, "half vector x,y,z, unit, of an anisotropic D (aniso_ggx...)");
    cos_opts = {
        cmd->add_option("--NoL", args.NoL, "cos between normal and light (single isotropic terms), in [-1, 1]"),
        cmd->add_option("--NoV", args.NoV, "cos between normal and view (single isotropic terms), in [-1, 1]"),
        cmd->add_option("--NoH", args.NoH, "cos between normal and half vector (single isotropic terms), in [-1, 1]"),
        cmd->add_option("--VoH", args.VoH, "cos between view and half vector (single isotropic terms), in [-1, 1]")};
    cmd->add_flag("--g1", g1,
                  "evaluate a Smith G term's G1 (at NoV, or at --wo for an anisotropic one) instead of its G2");
    SharedOptions(cmd, *this).fp64(fp64);
  }

  // The --param values, and every input checked; true when --alpha was given.
  bool read_inputs(Given& given) {
    for (auto& p : params) {
      auto kv = split(p, '=');
      if (kv.size() != 2) throw Error(fmt::format("--param wants NAME=VALUE, got '{}'", p));
      given.values[kv[0]] = parse_number("--param " + kv[0], kv[1]);
    }
    const bool alpha_given = alpha_opt->count() > 0;
    if (alpha_given && !(alpha > 0.0 && std::isfinite(alpha)))
      throw Error(fmt::format("--alpha = {} must be a positive finite number", alpha));
    if (!(kd >= 0.0 && kd <= 1.0)) throw Error(fmt::format("--kd = {} is out of range [0, 1]", kd));
    const double cos_values[4] = {args.NoL, args.NoV, args.NoH, args.VoH};
    args.cosines_given = false;
    for (size_t i = 0; i < 4; ++i) {
      if (!(cos_values[i] >= -1.0 && cos_values[i] <= 1.0))
        throw Error(fmt::format("{} = {} is not a cosine (outside [-1, 1])", cos_opts[i]->get_name(), cos_values[i]));
      args.cosines_given = args.cosines_given || cos_opts[i]->count() > 0;
    }
    args.wi_given = wi_opt->count() > 0;
    args.wo_given = wo_opt->count() > 0;
    args.h_given = h_opt->count() > 0;
    return alpha_given;
  }

  // --wi and --wo into the point's inputs (BRDFs and whole models).
  void set_directions(PointSpec& ps) const {
    if (args.cosines_given || args.h_given)
      throw Error(fmt::format("'{}' takes directions --wi and --wo, not cosines or --h", spec));
    auto wi = parse_direction("--wi", args.wi), wo = parse_direction("--wo", args.wo);
    for (int i = 0; i < 3; ++i) ps.inputs[i] = wi[i], ps.inputs[3 + i] = wo[i];
  }

  // The point `spec` names: a D/G/F BRDF, a whole model or a single term.
  PointSpec point(const std::vector<std::string>& parts, Given& given, bool alpha_given) const {
    PointSpec ps;
    if (parts.size() == 3) {
      ps.mode = EvalMode::Brdf;
      ps.d = &find_term(parts[0]);
      ps.g = &find_term(parts[1]);
      ps.f = &find_term(parts[2]);
      if (ps.d->kind != Kind::D || ps.g->kind != Kind::G || ps.f->kind != Kind::F)
        throw Error(fmt::format("'{}' must name a D, a G and an F term, in that order", spec));
      if (ps.d->aniso != ps.g->aniso)
        throw Error(fmt::format(
            "'{}': an anisotropic D goes with an anisotropic Smith G (e.g. aniso_ggx/smith_aniso_ggx)", spec));
      set_directions(ps);
      ps.params[0] = static_cast<float>(term_param(*ps.d, 0, given, alpha, alpha_given));
      if (!ps.g->params.empty()) ps.params[1] = static_cast<float>(term_param(*ps.g, 0, given, alpha, alpha_given));
      for (size_t i = 0; i < ps.f->params.size(); ++i)
        ps.params[2 + i] = static_cast<float>(term_param(*ps.f, i, given, alpha, alpha_given));
      ps.params[4] = static_cast<float>(kd);
      if (ps.d->aniso) {
        // one alpha_y for both (kernels/agree.cl record slot 14), as D and G share the surface
        ps.mode = EvalMode::BrdfAniso;
        ps.params[6] = static_cast<float>(term_param(*ps.d, 1, given, alpha, alpha_given));
        term_param(*ps.g, 1, given, alpha, alpha_given);
      }
    } else if (const Model* m = parts.size() == 1 ? try_find_model(spec) : nullptr) {
      // a whole model: f(wi, wo) with its parameters by name, defaults otherwise
      if (alpha_given) throw Error(fmt::format("'{}' is a whole model: give its parameters with --param", spec));
      ps.mode = EvalMode::Model;
      ps.model = m;
      set_directions(ps);
      for (size_t i = 0; i < m->params.size(); ++i) {
        double v = m->params[i].fallback;
        if (const double* x = given.find(m->params[i].name)) v = *x;
        validate_model_param(*m, i, v);
        ps.params[i] = static_cast<float>(v);
      }
    } else if (const Bsdf* b = parts.size() == 1 ? try_find_bsdf(spec) : nullptr) {
      // a rough dielectric BTDF (docs/transmission.md): wi incident, wo outgoing,
      // on opposite sides; D's and G's widths as a BRDF's, and eta
      ps.mode = EvalMode::Btdf;
      ps.bsdf = b;
      ps.d = b->d;
      ps.g = b->g;
      set_directions(ps);
      ps.params[0] = static_cast<float>(term_param(*b->d, 0, given, alpha, alpha_given));
      ps.params[1] = static_cast<float>(term_param(*b->g, 0, given, alpha, alpha_given));
      double eta = b->eta.fallback;
      if (const double* x = given.find(b->eta.name)) eta = *x;
      validate_value(b->id, b->eta, eta);
      ps.params[2] = static_cast<float>(eta);
    } else if (parts.size() == 1) {
      const Term& t = find_term(spec);
      if (t.kind == Kind::D) ps.d = &t;
      if (t.kind == Kind::G) ps.g = &t;
      if (t.kind == Kind::F) ps.f = &t;
      single_term(ps, t, g1, args);
      int slot = t.kind == Kind::D ? 0 : t.kind == Kind::G ? 1 : 2;
      if (t.aniso) {
        ps.params[slot] = static_cast<float>(term_param(t, 0, given, alpha, alpha_given));
        ps.params[6] = static_cast<float>(term_param(t, 1, given, alpha, alpha_given));
      } else {
        for (size_t i = 0; i < t.params.size(); ++i)
          ps.params[slot + i] = static_cast<float>(term_param(t, i, given, alpha, alpha_given));
      }
    } else {
      throw Error(fmt::format("'{}' is neither a term id nor D/G/F", spec));
    }
    return ps;
  }

  int run(const Globals& g) {
    Given given;
    const bool alpha_given = read_inputs(given);
    const auto parts = split(spec, '/');
    const PointSpec ps = point(parts, given, alpha_given);
    if (g1 && parts.size() != 1) throw Error("--g1 applies to a single Smith G term");
    for (auto& [name, v] : given.values)
      if (!given.used.count(name))
        throw Error(fmt::format("parameter '{}' belongs to none of the terms in '{}'", name, spec));

    Runtime rt(g.device, g.kernel_dir);
    PointValue r = eval_point(rt, ps, fp64);
    fmt::print("kernel    {:.9g}  ({:a})  on {}, {}\n", r.kernel, r.kernel, rt.device().name,
               fp64 ? "float64" : "float32");
    fmt::print("reference {:.17g}  ({:a})  double\n", r.reference, r.reference);
    fmt::print("relative error {:.3g}, {:.3g} ulps\n", r.rel, r.ulps);
    return 0;
  }
};

}  // namespace

void add_eval(CLI::App& app, Globals& g, int& rc) { add_command<EvalCommand>(app, g, rc, "eval"); }

}  // namespace mfv::cli
