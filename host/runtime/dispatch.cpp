#include "runtime/dispatch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace mfv {

TermSelection TermSelection::all() {
  TermSelection s;
  s.d = all_terms_of(Kind::D);
  s.g = all_terms_of(Kind::G);
  s.f = all_terms_of(Kind::F);
  s.g1 = true;
  for (auto& m : ::mfv::models()) s.models.push_back(&m);
  return s;
}

void TermSelection::add(const TermSelection& o) {
  auto append = [](auto& to, const auto& from) {
    for (const auto& x : from)
      if (std::find(to.begin(), to.end(), x) == to.end()) to.push_back(x);
  };
  append(d, o.d);
  append(g, o.g);
  append(f, o.f);
  append(models, o.models);
  g1 = g1 || o.g1;
  reciprocity_per_model = reciprocity_per_model || o.reciprocity_per_model;
  std::set<TermPair> pairs(specialized.begin(), specialized.end());
  for (const TermPair& p : o.specialized) {
    auto [at, added] = pairs.insert(p);
    if (!added && p.rqmc && !at->rqmc) {  // the pair's RQMC kernel where either selection asks for it
      pairs.erase(at);
      pairs.insert(p);
    }
  }
  specialized.assign(pairs.begin(), pairs.end());
}

int term_index(const Term& t) { return static_cast<int>(&t - catalog().data()); }

namespace {

// One function `name(int id, params)` switching over `terms`; `call(t)` is
// the expression that evaluates term t from the parameters. With `select`,
// a program of several terms evaluates every one and selects the id's value
// (always inlined, as the terms are): a switch, or a call left in the body,
// keeps PoCL from running work-items in SIMD lanes, and the fast paths of
// kernels/integrate.cl spend less on the extra terms than they gain from 8
// lanes (measured: docs/performance.md, "Full-catalog programs,
// vectorized"). Without it (the anisotropic and G1 variants, run by scalar
// kernels), a switch.
template <class Call>
std::string switch_fn(const std::string& name, const std::string& params, const std::vector<const Term*>& terms,
                      Call call, bool select = false) {
  const char* attr = select ? "static inline __attribute__((always_inline)) real" : "static inline real";
  std::string s = fmt::format("{} {}(int id, {}) {{\n", attr, name, params);
  if (terms.empty()) return fmt::format("static inline real {}(int id, {}) {{ return NAN; }}\n", name, params);
  if (terms.size() == 1) return s + fmt::format("  return {};\n}}\n", call(*terms[0]));
  if (select) {
    s += "  real r = NAN;\n";
    for (auto* t : terms) s += fmt::format("  r = id == {} ? {} : r;\n", term_index(*t), call(*t));
    return s + "  return r;\n}\n";
  }
  s += "  switch (id) {\n";
  for (auto* t : terms) s += fmt::format("    case {}: return {};\n", term_index(*t), call(*t));
  return s + "  }\n  return NAN;\n}\n";
}

// The select form where the program forces its terms inline
// (MFV_INLINE_TERMS: the integration programs on PoCL, whose anisotropic
// fast paths, kernels/aniso_values.cl, vectorize with it) and the switch
// elsewhere (Intel's CPU runtime, agree and pointwise programs), so that
// those keep the code they had.
template <class Call>
std::string select_if_inline(const std::string& name, const std::string& params, const std::vector<const Term*>& terms,
                             Call call) {
  if (terms.size() <= 1) return switch_fn(name, params, terms, call);
  return "#ifdef MFV_INLINE_TERMS\n" + switch_fn(name, params, terms, call, true) + "#else\n" +
         switch_fn(name, params, terms, call) + "#endif\n";
}

// Anisotropic terms (Term::aniso) seen through the one-width functions:
// their isotropic slice, the direction in the xz-plane and alpha_y = alpha_x.
std::string slice_dir(const char* cos) { return fmt::format("(real3)(sqrt(sin2_from_cos({0})), R(0.0), {0})", cos); }

}  // namespace

std::string generate_dispatch(const TermSelection& s) {
  std::string out;
  // A kind left out still gets a function (returning NaN, so a stray call
  // cannot pass silently): shared code such as brdf_eval must compile.
  out += switch_fn(
      "eval_D", "real NoH, real sin2H, real p", s.d,
      [](const Term& t) {
        return t.aniso ? t.kernel_fn + "(NoH, sqrt(sin2H), R(0.0), p, p)" : t.kernel_fn + "(NoH, sin2H, p)";
      },
      true);
  out += switch_fn(
      "eval_G", "real NoL, real NoV, real NoH, real VoH, real p", s.g,
      [](const Term& t) {
        return t.aniso ? fmt::format("{}({}, {}, VoH, p, p)", t.kernel_fn, slice_dir("NoL"), slice_dir("NoV"))
                       : t.kernel_fn + "(NoL, NoV, NoH, VoH, p)";
      },
      true);
  out += switch_fn(
      "eval_F", "real VoH, real p0, real p1", s.f, [](const Term& t) { return t.kernel_fn + "(VoH, p0, p1)"; }, true);
  // Two widths and the tangent components (kernels/aniso_values.cl, brdf.cl,
  // pointwise.cl): isotropic terms ignore hx, hy and p2 and see exactly what
  // eval_D gives them. eval_G_aniso takes l and v by components (no float3
  // value in the fast paths).
  out += select_if_inline(
      "eval_D_aniso", "real NoH, real sin2H, real hx, real hy, real p, real p2", s.d,
      [](const Term& t) { return t.aniso ? t.kernel_fn + "(NoH, hx, hy, p, p2)" : t.kernel_fn + "(NoH, sin2H, p)"; });
  out += select_if_inline("eval_G_aniso",
                          "real lx, real ly, real lz, real vx, real vy, real vz, real NoH, real VoH, real p, real p2",
                          s.g, [](const Term& t) {
                            return t.aniso ? t.kernel_fn + "((real3)(lx, ly, lz), (real3)(vx, vy, vz), VoH, p, p2)"
                                           : t.kernel_fn + "(lz, vz, NoH, VoH, p)";
                          });
  std::vector<const Term*> smith;
  for (auto* t : s.g)
    if (!t->g1_kernel_fn.empty()) smith.push_back(t);
  out += select_if_inline("eval_G1_aniso", "real NoV, real vx, real vy, real p, real p2", smith, [](const Term& t) {
    return t.aniso ? t.g1_kernel_fn + "(NoV, vx, vy, p, p2)" : t.g1_kernel_fn + "(NoV, p)";
  });
  // Whole models (kernels/models.cl), by Model::number(); none selected
  // still gives the function, returning NaN.
  std::string mp = "real3 wi, real3 wo, const real* p";
  if (s.models.empty()) {
    out += fmt::format("static inline real eval_model(int id, {}) {{ return NAN; }}\n", mp);
  } else if (s.models.size() == 1) {
    out += fmt::format("static inline real eval_model(int id, {}) {{\n  return {}(wi, wo, p);\n}}\n", mp,
                       s.models[0]->kernel_fn);
  } else {
    out += fmt::format("static inline MFV_ALWAYS_INLINE real eval_model(int id, {}) {{\n  switch (id) {{\n", mp);
    for (auto* m : s.models) out += fmt::format("    case {}: return {}(wi, wo, p);\n", m->number(), m->kernel_fn);
    out += "  }\n  return NAN;\n}\n";
  }
  if (s.g1 && !smith.empty())
    out += switch_fn("eval_G1", "real NoV, real p", smith, [](const Term& t) {
      return t.aniso ? fmt::format("{}(NoV, sqrt(sin2_from_cos(NoV)), R(0.0), p, p)", t.g1_kernel_fn)
                     : t.g1_kernel_fn + "(NoV, p)";
    });
  return out;
}

}  // namespace mfv
