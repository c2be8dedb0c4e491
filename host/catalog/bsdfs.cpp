#include "catalog/bsdfs.hpp"

#include "abi/bsdf.h"

#include <fmt/format.h>

namespace mfv {

const char* const kBtdfConvention =
    "radiance form (Walter et al. 2007 eq. 21, with eta_o^2): f_t(i,o)/eta_o^2 = f_t(o,i)/eta_i^2; flux form: "
    "E_T(i) = integral of f_t(i,o)|o.n| over o (the power from i that is transmitted, no eta factor)";

int Bsdf::code() const { return MFV_BTDF_CODE(form, variant); }

const char* btdf_form_name(int form) { return form == MFV_BTDF_CORRELATED ? "correlated" : "separable"; }

namespace {

const char* kWalter =
    "Walter et al. 2007 eq. 21 (BTDF), eq. 16 (h_t), eq. 23 (G1 with chi+); the height-correlated G2 as pbrt-v4 "
    "(Heitz 2014 eq. 99)";

std::vector<Bsdf> build_bsdfs() {
  std::vector<Bsdf> c;
  auto add = [&](std::string id, const char* d, const char* g, int form, int variant, std::string bad) {
    Bsdf b;
    b.id = std::move(id);
    b.d = &find_term(d);
    b.g = &find_term(g);
    b.form = form;
    b.variant = variant;
    b.source = kWalter;
    b.formula = fmt::format(
        "|i.h||o.h|/(|i.n||o.n|) eta^2 (1-F(i.h)) G2 D(h) / (i.h + eta o.h)^2, h ~ -(i + eta o), D {}, G1 of {}, G2 {}",
        d, g, btdf_form_name(form));
    b.known_bad = std::move(bad);
    if (auto* fit = b.g->fit_for(d); fit && fit->tol > 0) b.g1_fit = fit->why;
    // D, two G1, F and the half vector's and the quotients' ~10 roundings
    b.ulp_budget = b.d->ulp_budget + b.g->ulp_budget + find_term("dielectric").ulp_budget + 16;
    c.push_back(std::move(b));
  };
  // Every catalog D with a Smith G (Term::smith_for), both G2 forms.
  const struct {
    const char *d, *g;
  } pairs[] = {{"ggx", "smith_ggx"}, {"beckmann", "smith_beckmann"}, {"phong", "smith_beckmann"},
               {"blinn_rho", "smith_beckmann"}};
  for (auto& p : pairs)
    for (int form : {MFV_BTDF_SEPARABLE, MFV_BTDF_CORRELATED})
      add(fmt::format("walter_{}_{}", p.d, btdf_form_name(form)), p.d, p.g, form, MFV_BTDF_OK, "");
  // Known-bad variants on GGX with the height-correlated G2: each must fail.
  const struct {
    const char *id, *g;
    int variant;
    const char* why;
  } bad[] = {
      {"walter_ggx_f_at_n", "smith_ggx", MFV_BTDF_BAD_F_AT_N,
       "F at the macro-surface cosine n.i instead of the facet's i.h: the transmitted share is the smooth "
       "interface's, not the facets'"},
      {"walter_ggx_no_eta2", "smith_ggx", MFV_BTDF_BAD_NO_ETA2,
       "eta_o^2 missing from the numerator of eq. 21: transmission is scaled by (eta_i/eta_o)^2, and generalized "
       "reciprocity f_t(i,o)/eta_o^2 = f_t(o,i)/eta_i^2 fails"},
      {"walter_ggx_jacobian_sum", "smith_ggx", MFV_BTDF_BAD_JACOBIAN,
       "the Jacobian's (eta_i i.h + eta_o o.h)^2 written (i.h + o.h)^2: the refracted solid angle is mis-measured "
       "and the transmitted energy is wrong wherever eta != 1"},
      {"walter_ggx_same_side", "smith_ggx", MFV_BTDF_BAD_SAME_SIDE,
       "no orientation test: directions on the incident side of the facet are counted as refracted, adding energy "
       "that no refraction sends there"},
      {"walter_ggx_beckmann_g1", "smith_beckmann", MFV_BTDF_OK,
       "a G1 from the wrong D (Beckmann's Smith G1 with GGX's D) under-masks GGX's heavier tails: the transmission "
       "furnace's masking integral is not |o.n|"},
  };
  for (auto& k : bad) add(k.id, "ggx", k.g, MFV_BTDF_CORRELATED, k.variant, k.why);
  return c;
}

}  // namespace

const std::vector<Bsdf>& bsdfs() {
  static const std::vector<Bsdf> c = build_bsdfs();
  return c;
}

const Bsdf* try_find_bsdf(const std::string& id) {
  for (auto& b : bsdfs())
    if (b.id == id) return &b;
  return nullptr;
}

}  // namespace mfv
