#include "runtime/dispatch.hpp"

#include <fmt/format.h>

namespace mfv {

TermSelection TermSelection::all() {
  TermSelection s;
  s.d = terms_of(Kind::D);
  s.g = terms_of(Kind::G);
  s.f = terms_of(Kind::F);
  s.g1 = true;
  for (auto& m : ::mfv::models()) s.models.push_back(&m);
  return s;
}

int term_index(const Term& t) { return static_cast<int>(&t - catalog().data()); }

namespace {

// One function `name(int id, args)` switching over `terms`, calling `fn(t)`.
template <class Fn>
std::string switch_fn(const std::string& name, const std::string& params, const std::string& args,
                      const std::vector<const Term*>& terms, Fn fn) {
  std::string s = fmt::format("static inline real {}(int id, {}) {{\n", name, params);
  if (terms.size() == 1) return s + fmt::format("  return {}({});\n}}\n", fn(*terms[0]), args);
  s += "  switch (id) {\n";
  for (auto* t : terms) s += fmt::format("    case {}: return {}({});\n", term_index(*t), fn(*t), args);
  return s + "  }\n  return NAN;\n}\n";
}

}  // namespace

std::string generate_dispatch(const TermSelection& s) {
  std::string out;
  auto kfn = [](const Term& t) { return t.kernel_fn; };
  // A kind left out still gets a function (returning NaN, so a stray call
  // cannot pass silently): shared code such as brdf_eval must compile.
  auto emit = [&](const char* name, const std::string& params, const std::string& args,
                  const std::vector<const Term*>& terms) {
    out += terms.empty() ? fmt::format("static inline real {}(int id, {}) {{ return NAN; }}\n", name, params)
                         : switch_fn(name, params, args, terms, kfn);
  };
  emit("eval_D", "real NoH, real sin2H, real p", "NoH, sin2H, p", s.d);
  emit("eval_G", "real NoL, real NoV, real NoH, real VoH, real p", "NoL, NoV, NoH, VoH, p", s.g);
  emit("eval_F", "real VoH, real p0, real p1", "VoH, p0, p1", s.f);
  // Whole models (kernels/models.cl), by Model::number(); none selected
  // still gives the function, returning NaN.
  std::string mp = "real3 wi, real3 wo, const real* p";
  if (s.models.empty()) {
    out += fmt::format("static inline real eval_model(int id, {}) {{ return NAN; }}\n", mp);
  } else if (s.models.size() == 1) {
    out += fmt::format("static inline real eval_model(int id, {}) {{\n  return {}(wi, wo, p);\n}}\n", mp,
                       s.models[0]->kernel_fn);
  } else {
    out += fmt::format("static inline real eval_model(int id, {}) {{\n  switch (id) {{\n", mp);
    for (auto* m : s.models) out += fmt::format("    case {}: return {}(wi, wo, p);\n", m->number(), m->kernel_fn);
    out += "  }\n  return NAN;\n}\n";
  }
  if (s.g1) {
    std::vector<const Term*> smith;
    for (auto* t : s.g)
      if (!t->g1_kernel_fn.empty()) smith.push_back(t);
    if (!smith.empty())
      out += switch_fn("eval_G1", "real NoV, real p", "NoV, p", smith, [](const Term& t) { return t.g1_kernel_fn; });
  }
  return out;
}

}  // namespace mfv
