#include "catalog/catalog.hpp"

#include "catalog/pairing.hpp"
#include "catalog/roughness.hpp"
#include "reference/reference.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

namespace mfv {
namespace ref_ = ::mfv::ref;

const char* kind_name(Kind k) {
  static const char* const names[] = {"D", "G", "F"};  // in Kind's order
  return names[static_cast<int>(k)];
}

namespace {

// Parameter ranges. alpha spans the stiff 1e-7 to very rough 10; the Phong
// exponent reaches 1e7 (alpha ~ 4.5e-4).
Param p_alpha() { return {"alpha", 1e-7, 10.0, 0.3, "microfacet width (slope RMS)"}; }
Param p_alpha_xy(const char* name, const char* axis) {
  return {name, 1e-7, 10.0, 0.3, std::string("microfacet width along ") + axis + " (slope RMS)"};
}
Param p_alpha_p() { return {"alpha_p", 0.0, 1e7, 100.0, "Phong exponent, 0 rough .. inf mirror"}; }

// Beckmann's G1 used for the Phong D (and seed 004's rho form of it).
SmithFit beckmann_as_phong(double tol, const char* d) {
  return {d, tol, 0.2,
          "Walter et al. 2007 §5.2: Beckmann's G1 with alpha_p = 2/alpha^2 - 2 stands in for Phong's; measured within "
          "2.5 % up to alpha = 0.2, 4 % at 0.3, 7 % at 0.4 and 77 % at alpha = 1 (grazing view), where Phong's "
          "tails outgrow Beckmann's"};
}

std::vector<Term> build_catalog() {
  std::vector<Term> c;
  // A term of kind k, appended to the catalog; the D, G and F below add its reference twin.
  auto term = [&](Kind k, std::string id, std::string fn, std::string src, std::string formula, std::vector<Param> p,
                  Roughness r) {
    Term t;
    t.id = std::move(id);
    t.kind = k;
    t.kernel_fn = std::move(fn);
    t.source = std::move(src);
    t.formula = std::move(formula);
    t.params = std::move(p);
    t.roughness = r;
    c.push_back(t);
    return &c.back();
  };
  auto D = [&](std::string id, std::string fn, std::string src, std::string formula, Param p, Roughness r, RefD ref) {
    Term* t = term(Kind::D, std::move(id), std::move(fn), std::move(src), std::move(formula), {std::move(p)}, r);
    t->ref_d = ref;
    return t;
  };
  D("phong", "D_phong", "seed 000 \"Phong\"; seed 003 Blinn normalisation", "(ap+2)/(2pi) (n.h)^ap", p_alpha_p(),
    Roughness::PhongExponent, ref_::D_phong);
  D("beckmann", "D_beckmann", "seed 000 \"Beckman\"", "exp(-tan^2/a^2) / (pi a^2 cos^4)", p_alpha(), Roughness::Alpha,
    ref_::D_beckmann);
  D("ggx", "D_ggx", "seed 000 \"GGX\"; Walter et al. 2007 eq. 33", "a^2 / (pi ((n.h)^2 (a^2-1) + 1)^2)", p_alpha(),
    Roughness::Alpha, ref_::D_ggx);
  D("blinn_rho", "D_blinn_rho", "seed 004 Cook-Torrance \"blinn version\"", "(h.n)^(2/rho^2-2) / (pi rho^2)",
    Param{"rho", 1e-4, 1.0, 0.3, "roughness rho (= alpha)"}, Roughness::Rho, ref_::D_blinn_rho);
  D("beckmann_ct82", "D_beckmann_ct82", "seed 001 Cook-Torrance, as written", "exp(-(tan/m)^2) / (4 m^2 cos^4)",
    Param{"m", 1e-7, 10.0, 0.3, "RMS slope m (= alpha)"}, Roughness::BeckmannM, ref_::D_beckmann_ct82)
      ->known_bad = "4 m^2 in place of pi m^2: integrates to pi/4, not 1";
  for (auto& t : c) {  // the (cos², sin²) forms of the D with tan²θ or (n·h)^e
    if (t.id == "ggx") t.ref_d_cs = ref_::D_ggx_cs;
    if (t.id == "beckmann") t.ref_d_cs = ref_::D_beckmann_cs;
    if (t.id == "beckmann_ct82") t.ref_d_cs = ref_::D_beckmann_ct82_cs;
    if (t.id == "phong") t.ref_d_cs = ref_::D_phong_cs;
    if (t.id == "blinn_rho") t.ref_d_cs = ref_::D_blinn_rho_cs;
  }

  auto G = [&](std::string id, std::string fn, std::string src, std::string formula, std::optional<Param> p,
               Roughness r, RefG ref) {
    std::vector<Param> ps;
    if (p) ps = {*p};
    Term* t = term(Kind::G, std::move(id), std::move(fn), std::move(src), std::move(formula), std::move(ps), r);
    t->ref_g = ref;
    return t;
  };
  // A separable Smith G, G1(l) G1(v), with its G1's kernel and reference twins.
  auto separable = [](Term* t, std::string g1_fn, RefG1 g1) {
    t->g1_kernel_fn = std::move(g1_fn);
    t->ulp_budget = 16;  // G1(l) G1(v): two factors of 8 ulps each
    t->ref_g1 = g1;
    t->g_separable = true;
    return t;
  };
  // A separable Smith G with a Beckmann G1: it fits Beckmann within `tol`
  // (`why`) and the Phong-type Ds as Beckmann, and under-masks GGX's heavier tails.
  auto beckmann_smith = [&](Term* t, std::string g1_fn, RefG1 g1, double tol, std::string why) {
    separable(t, std::move(g1_fn), g1);
    t->smith_for = {{"beckmann", tol, 1e300, std::move(why)},
                    beckmann_as_phong(0.03, "phong"),
                    beckmann_as_phong(0.03, "blinn_rho")};
    t->under_masks = {"ggx"};
  };
  G("implicit", "G_implicit", "seed 000 \"V(L,V) = 1\"", "(n.l)(n.v)", std::nullopt, Roughness::None, ref_::G_implicit);
  G("kelemen", "G_kelemen", "seed 000 \"G/((L.N)(V.N)) ~ 1/(L.H)^2\"; Kelemen 2001", "(n.l)(n.v)/(l.h)^2", std::nullopt,
    Roughness::None, ref_::G_kelemen);
  G("cook_torrance", "G_cook_torrance", "seeds 001, 003, 004 (V-cavity)",
    "min(1, 2(n.h)(n.v)/(v.h), 2(n.h)(n.l)/(v.h))", std::nullopt, Roughness::None, ref_::G_cook_torrance)
      ->masking_exact =
      "the V-cavity masking is exact for its own microsurface of V-grooves, so it conserves projected area for "
      "every D (Heitz 2014 §5.3), although that surface is unrealistic at grazing angles";
  {
    auto* t = G("smith_beckmann_approx", "G_smith_beckmann_approx", "seed 000 Beckman rational G1",
                "G1(l)G1(v), G1 = (3.535a+2.181a^2)/(1+2.276a+2.577a^2), a = 1/(alpha tan)", p_alpha(),
                Roughness::Alpha, ref_::G_smith_beckmann_approx);
    // seed 000: "very accurate"; Walter et al. 2007 eq. 27 report under 0.35 %
    beckmann_smith(t, "G1_smith_beckmann_approx", ref_::G1_smith_beckmann_approx, 0.004, "Walter et al. 2007 eq. 27");
  }
  {
    auto* t = G("smith_beckmann", "G_smith_beckmann", "Walter et al. 2007 eq. 23-25 (exact Lambda, erf)",
                "G1(l)G1(v), G1 = 1/(1+Lambda_beckmann)", p_alpha(), Roughness::Alpha, ref_::G_smith_beckmann);
    beckmann_smith(t, "G1_smith_beckmann", ref_::G1_smith_beckmann, 0.0, "Walter et al. 2007 eq. 25 (exact)");
  }
  {
    auto* t =
        G("smith_phong", "G_smith_phong", "seed 000 \"Phong\" G1", "Beckman rational G1 with a = sqrt(ap/2+1)/tan",
          p_alpha_p(), Roughness::PhongExponent, ref_::G_smith_phong);
    // a = sqrt(alpha_p/2 + 1)/tan with alpha_p = 2/alpha^2 - 2 is a = 1/(alpha tan):
    // exactly seed 000's rational Beckmann G1, so it fits Beckmann to 0.4 %.
    beckmann_smith(t, "G1_smith_phong", ref_::G1_smith_phong, 0.004,
                   "alpha_p = 2/alpha^2 - 2 makes a = 1/(alpha tan): Walter et al. 2007 eq. 27");
  }
  {
    auto* t = G("smith_ggx", "G_smith_ggx", "seed 000 \"GGX\"; Walter et al. 2007 eq. 34",
                "G1(l)G1(v), G1 = 2/(1+sqrt(1+alpha^2 tan^2))", p_alpha(), Roughness::Alpha, ref_::G_smith_ggx);
    separable(t, "G1_smith_ggx", ref_::G1_smith_ggx);
    t->smith_for = {{"ggx", 0.0, 1e300, "Walter et al. 2007 eq. 34 (exact)"}};
  }
  {
    auto* t = G("smith_ggx_correlated", "G_smith_ggx_correlated", "Heitz 2014 eq. 99 (height-correlated)",
                "1/(1 + Lambda(l) + Lambda(v))", p_alpha(), Roughness::Alpha, ref_::G_smith_ggx_correlated);
    t->g1_kernel_fn = "G1_smith_ggx";
    t->ref_g1 = ref_::G1_smith_ggx;
    t->g_correlated_lambda = ref_::Lambda_ggx;
    t->smith_for = {{"ggx", 0.0, 1e300, "Walter et al. 2007 eq. 34 (exact)"}};
  }
  G("hammon_002", "G_hammon_002", "seed 002 `geometry` (Hammon 2017 visibility)",
    "4(n.l)(n.v) * 0.5/max(0.01, mix(2(n.l)(n.v), n.l+n.v, alpha))",
    Param{"alpha", 0.0, 1.0, 0.3, "mix weight = alpha (seed 002 squares roughness first)"}, Roughness::Alpha,
    ref_::G_hammon_002);

  // Anisotropic GGX and Beckmann with their Smith G (tangent frame t = +x,
  // b = +y, n = +z): two widths; see Term::aniso.
  auto aniso = [&](Term* t, RefDAniso d, RefG1Aniso g1, RefGAniso g) {
    t->aniso = true;
    t->params = {p_alpha_xy("alpha_x", "t = +x"), p_alpha_xy("alpha_y", "b = +y")};
    t->ref_d_aniso = d;
    t->ref_g1_aniso = g1;
    t->ref_g_aniso = g;
    return t;
  };
  aniso(D("aniso_ggx", "D_ggx_aniso", "Heitz 2014 (anisotropic GGX); Burley 2012 app. B (GTR2 aniso)",
          "1 / (pi ax ay ((n.h)^2 + (t.h/ax)^2 + (b.h/ay)^2)^2)", p_alpha(), Roughness::Alpha, ref_::D_ggx_aniso_slice),
        ref_::D_ggx_aniso, nullptr, nullptr);
  aniso(D("aniso_beckmann", "D_beckmann_aniso", "Heitz 2014 (anisotropic Beckmann; Ward's exponent, seed 004)",
          "exp(-((t.h/ax)^2 + (b.h/ay)^2)/(n.h)^2) / (pi ax ay (n.h)^4)", p_alpha(), Roughness::Alpha,
          ref_::D_beckmann_aniso_slice),
        ref_::D_beckmann_aniso, nullptr, nullptr);
  // Their Smith G: G1(l) G1(v), the isotropic Lambda at the projected width,
  // exact for the D of the same family.
  auto aniso_smith = [&](std::string id, std::string fn, std::string g1_fn, std::string formula, RefG slice,
                         RefG1 g1_slice, RefG1Aniso g1, RefGAniso g, std::string exact_for, std::string note) {
    auto* t = aniso(
        G(id, fn,
          "Heitz 2014: the isotropic Lambda at the projected width alpha_o = sqrt(cos^2 phi ax^2 + sin^2 phi ay^2)",
          formula, p_alpha(), Roughness::Alpha, slice),
        nullptr, g1, g);
    separable(t, g1_fn, g1_slice);
    t->smith_for = {{exact_for, 0.0, 1e300, note}};
  };
  aniso_smith("smith_aniso_ggx", "G_smith_ggx_aniso", "G1_smith_ggx_aniso",
              "G1(l)G1(v), G1 = 2/(1+sqrt(1+alpha_o^2 tan^2))", ref_::G_smith_ggx_aniso_slice,
              ref_::G1_smith_ggx_aniso_slice, ref_::G1_smith_ggx_aniso, ref_::G_smith_ggx_aniso, "aniso_ggx",
              "Heitz 2014, anisotropic GGX (exact)");
  aniso_smith("smith_aniso_beckmann", "G_smith_beckmann_aniso", "G1_smith_beckmann_aniso",
              "G1(l)G1(v), G1 = 1/(1+Lambda_beckmann(alpha_o))", ref_::G_smith_beckmann_aniso_slice,
              ref_::G1_smith_beckmann_aniso_slice, ref_::G1_smith_beckmann_aniso, ref_::G_smith_beckmann_aniso,
              "aniso_beckmann", "Heitz 2014, anisotropic Beckmann (exact)");

  auto F = [&](std::string id, std::string fn, std::string src, std::string formula, std::vector<Param> p, RefF ref) {
    Term* t =
        term(Kind::F, std::move(id), std::move(fn), std::move(src), std::move(formula), std::move(p), Roughness::None);
    t->ref_f = ref;
    return t;
  };
  F("none", "F_none", "white furnace", "1", {}, ref_::F_none);
  F("schlick", "F_schlick", "seed 000; Schlick 1994", "F0 + (1-F0)(1-l.h)^5",
    {{"f0", 0.0, 1.0, 0.04, "reflectance at normal incidence (per channel)"}}, ref_::F_schlick)
      ->check_points = {{0.0, 0, "f0=0"}, {0.04, 0, "f0=0.04"}, {0.5, 0, "f0=0.5"}, {1.0, 0, "f0=1"}};
  F("dielectric", "F_dielectric", "seed 000 exact (seed 001's form has sign typos)",
    "1/2 (g-c)^2/(g+c)^2 (1 + ((c(g+c)-1)/(c(g-c)+1))^2), g^2 = eta^2-1+c^2",
    {{"eta", 0.1, 10.0, 1.5, "relative index eta_t/eta_i; < 1 gives total internal reflection"}}, ref_::F_dielectric);
  c.back().ulp_budget = 24;  // ~20 roundings, squared twice; measured worst 19 ulps at grazing, eta ~ 3
  c.back().check_points = {{1 / 1.5, 0, "eta=0.667"}, {1.33, 0, "eta=1.33"}, {1.5, 0, "eta=1.5"}, {3.0, 0, "eta=3"}};
  F("conductor", "F_conductor", "Born and Wolf 14.2 (complex index n + ik)", "(|r_s|^2 + |r_p|^2)/2",
    {{"n", 0.01, 10.0, 0.2, "real part of the index"}, {"k", 0.0, 20.0, 3.0, "extinction coefficient"}},
    ref_::F_conductor);
  c.back().ulp_budget = 16;  // ~40 operations with three square roots; measured worst 8.6 ulps at grazing
  // silver, aluminium, gold, iron at ~550 nm (Palik)
  c.back().check_points = {{0.059, 3.6, "Ag"}, {0.96, 6.69, "Al"}, {0.43, 2.45, "Au"}, {2.87, 3.0, "Fe"}};

  // KHR_materials_sheen: the Charlie sheen D and its visibility, a lobe of
  // their own (Term::own_lobe). Appended last, so that the other terms keep
  // their kernel ids. alphaG = sheenRoughness (the spec's "Sheen distribution").
  const Param p_sheen{"alpha", 1e-3, 1.0, 0.5,
                      "sheen roughness alphaG = sheenRoughness; below 1e-3 the lobe is a sliver at the horizon"};
  {
    auto* t = D("charlie", "D_charlie", "Estevez and Kulla 2017 eq. 2 (\"Charlie\" sheen); KHR_materials_sheen",
                "(2 + 1/alpha) sin(theta)^(1/alpha) / (2 pi)", p_sheen, Roughness::Alpha, ref_::D_charlie);
    t->ref_d_cs = ref_::D_charlie_cs;
    t->own_lobe = true;
    // exp(x), x = log(sin²θ) · 0.5/α, carries x's relative rounding (log, the
    // quotient, the product: ~3 u) as |x| · 3u of D; above the agreement floor
    // (1e-30) |x| <= ln(D_max / 1e-30) ~ 80: 240 ulps (measured worst 253 with
    // the conditioning allowance, mfv agree --only charlie)
    t->ulp_budget = 256;
    // sin^(1/α)θ = (1 − cos²θ)^(1/(2α)) ≈ exp(−cos²θ/(2α)) falls to 1/e at
    // cos²θ = 2α: slope tanθ ≈ 1/sqrt(2α), where the proposal's median slope
    // then sits (the mass is at grazing m; the cosine lobe covers the normal)
    t->proposal = [](double a) { return 1.0 / std::sqrt(2.0 * a); };
  }
  {
    auto* t = G("charlie_sheen", "G_charlie_sheen",
                "KHR_materials_sheen \"Sheen visibility\" (Charlie); Estevez and Kulla 2017 §3 (fitted Lambda)",
                "1/(1 + Lambda(l) + Lambda(v)), ln Lambda = a/(1 + b x^c) + d x + e, mixed in (1 - alpha)^2", p_sheen,
                Roughness::Alpha, ref_::G_charlie_sheen);
    t->g1_kernel_fn = "G1_charlie";
    t->ref_g1 = ref_::G1_charlie;
    t->g_correlated_lambda = ref_::Lambda_charlie;
    // Λ(1) = exp(2 L(0.5) − L(0)) with L(0) = a + e: the fit is no Smith Λ
    // at normal incidence (Estevez and Kulla 2017 §3)
    t->g1_not_one_at_normal = "the fitted Lambda(1) = exp(2 L(0.5) - L(0)) is not 0";
    t->own_lobe = true;
    // Λ = exp(L): L's absolute rounding becomes Λ's relative error; L sums terms
    // up to a/(1 + b x^c) <= 25.3, |e| <= 4.9, |d x| <= 2 (~3 roundings of ~32:
    // ~96 u), and G = 1/(1 + Λ(l) + Λ(v)) keeps it: 128 (measured worst 72)
    t->ulp_budget = 128;
    t->smith_for = {{"charlie", 0.0, 1e300,
                     "Estevez and Kulla 2017 §3 fit ln Lambda of the Charlie D; masking takes the fit's error from "
                     "the exact Lambda by quadrature (host/checks/suite_sheen.cpp)"}};
  }
  // Terms engines ship (issue 28), appended last; each checked in the pairing
  // engines use it in (kPairings below), out of the shared grids.
  {
    auto* t = G("hammon_clamped", "G_hammon_clamped",
                "Hammon 2017, \"PBR Diffuse Lighting for GGX+Smith Microsurfaces\" (fit of height-correlated "
                "Smith-GGX), the fit's cosines floored at 1e-4 as engines clamp n.v",
                "4(n.l)(n.v) * 0.5/mix(2 l v, l + v, alpha), l, v = max(cosine, 1e-4)",
                Param{"alpha", 0.0, 1.0, 0.3, "GGX width alpha, the fit's mix weight"}, Roughness::Alpha,
                ref_::G_hammon_clamped);
    t->own_lobe = true;
  }
  {
    auto* t = G("neubelt_sheen", "G_neubelt_sheen",
                "Neubelt and Pettineo 2013, \"Crafting a Next-Gen Material Pipeline for The Order: 1886\" (cloth "
                "visibility, after Ashikhmin and Premoze 2007)",
                "4(n.l)(n.v) / (4 (n.l + n.v - (n.l)(n.v)))", std::nullopt, Roughness::None, ref_::G_neubelt_sheen);
    t->own_lobe = true;
  }
  {
    auto* t = F("schlick_f90", "F_schlick_f90", "Schlick 1994 with the grazing value f90 (Burley 2012 §5.3)",
                "F0 + (F90-F0)(1-l.h)^5",
                {{"f0", 0.0, 1.0, 0.04, "reflectance at normal incidence (per channel)"},
                 {"f90", 0.0, 1.0, 1.0, "reflectance at grazing incidence"}},
                ref_::F_schlick_f90);
    t->own_lobe = true;
    // m = 1 - c carries a relative rounding up to u, which m^5 multiplies by
    // 5; four products, the sum of five in u and the final f0 u + f90 w add
    // ~10 roundings of u: ~15 u = 7.5 ulps (measured worst 6.95, mfv agree)
    t->ulp_budget = 12;
    // f90 below f0 is in range: F then falls towards grazing
    t->check_points = {{0.04, 1.0, "f0=0.04,f90=1"}, {0.04, 0.5, "f0=0.04,f90=0.5"}, {1.0, 0.0, "f0=1,f90=0"}};
  }
  {
    auto* t = F("schlick_sg", "F_schlick_sg",
                "Karis 2013, \"Real Shading in Unreal Engine 4\", Fresnel (spherical-Gaussian fit, Lagarde 2012)",
                "F0 + (1-F0) 2^((-5.55473 l.h - 6.98316) l.h)",
                {{"f0", 0.0, 1.0, 0.04, "reflectance at normal incidence (per channel)"}}, ref_::F_schlick_sg);
    t->own_lobe = true;
    // 2^x = exp(x ln 2): x = (a c + b) c ln 2 reaches |x| = 8.7, formed in four
    // roundings (~4 |x| u absolute), which exp turns into that relative error
    // of 2^x: ~35 u = 17 ulps, plus exp's own 2-8 ulps (common.cl): 24
    // (measured worst 8.3, mfv agree)
    t->ulp_budget = 24;
    t->check_points = {{0.0, 0, "f0=0"}, {0.04, 0, "f0=0.04"}, {1.0, 0, "f0=1"}};
  }
  return c;
}

}  // namespace

// The engine terms' pairings (catalog/pairing.hpp): the Gs under the D they
// are shipped with, the Fs under GGX with the correlated Smith G.
const Pairing* engine_pairing(const Term& t) {
  static const std::map<std::string, Pairing> kPairings = {{"hammon_clamped", {"ggx", ""}},
                                                           {"neubelt_sheen", {"charlie", ""}},
                                                           {"schlick_f90", {"ggx", "smith_ggx_correlated"}},
                                                           {"schlick_sg", {"ggx", "smith_ggx_correlated"}}};
  auto it = kPairings.find(t.id);
  return it == kPairings.end() ? nullptr : &it->second;
}

const SmithFit* Term::fit_for(const std::string& d_id) const {
  for (auto& f : smith_for)
    if (f.d == d_id) return &f;
  return nullptr;
}

const std::vector<Term>& catalog() {
  static const std::vector<Term> c = build_catalog();
  return c;
}

std::vector<const Term*> terms_of(Kind k) {
  std::vector<const Term*> out;
  for (auto& t : catalog())
    if (t.kind == k && !t.aniso && !t.own_lobe) out.push_back(&t);
  return out;
}

double proposal_width(const Term& d, double alpha) { return d.proposal ? d.proposal(alpha) : alpha; }

std::vector<const Term*> own_lobe_terms_of(Kind k) {
  std::vector<const Term*> out;
  for (auto& t : catalog())
    if (t.kind == k && t.own_lobe) out.push_back(&t);
  return out;
}

std::vector<const Term*> aniso_terms_of(Kind k) {
  std::vector<const Term*> out;
  for (auto& t : catalog())
    if (t.kind == k && t.aniso) out.push_back(&t);
  return out;
}

std::vector<const Term*> all_terms_of(Kind k) {
  std::vector<const Term*> out;
  for (auto& t : catalog())
    if (t.kind == k) out.push_back(&t);
  return out;
}

const Term* try_find_term(const std::string& id, Kind k) {
  for (auto& t : catalog())
    if (t.kind == k && t.id == id) return &t;
  return nullptr;
}

const Term& find_term(const std::string& id) {
  for (auto& t : catalog())
    if (t.id == id) return t;
  std::string known;
  for (auto& t : catalog()) known += (known.empty() ? "" : ", ") + t.id;
  throw Error(fmt::format("unknown term '{}' (known: {})", id, known));
}

void validate_value(const std::string& owner, const Param& p, double value) {
  if (std::isnan(value)) throw Error(fmt::format("{}.{} is NaN; give a number in [{}, {}]", owner, p.name, p.lo, p.hi));
  if (value < p.lo || value > p.hi)
    throw Error(fmt::format("{}.{} = {} is out of range [{}, {}]", owner, p.name, value, p.lo, p.hi));
}

void validate_param(const Term& t, size_t index, double value) {
  if (index >= t.params.size())
    throw Error(fmt::format("term '{}' has no parameter #{} (it takes {})", t.id, index, t.params.size()));
  validate_value(t.id, t.params[index], value);
}

double alpha_from_native(Roughness r, double native) {
  switch (r) {
    case Roughness::None: return native;
    case Roughness::Alpha: return native;
    case Roughness::PhongExponent: return alpha_from_phong_exponent(native);
    case Roughness::Rho: return native;
    case Roughness::BeckmannM: return native;
    case Roughness::Perceptual: return alpha_from_perceptual(native);
    case Roughness::MirrorExponent: return alpha_from_mirror_exponent(native);
    case Roughness::HalfCosine: return alpha_from_half_cosine(native);
  }
  return native;
}

double native_from_alpha(Roughness r, double alpha) {
  switch (r) {
    case Roughness::None: return 0.0;
    case Roughness::Alpha: return alpha;
    case Roughness::PhongExponent: return phong_exponent_from_alpha(alpha);
    case Roughness::Rho: return alpha;
    case Roughness::BeckmannM: return alpha;
    case Roughness::Perceptual: return perceptual_from_alpha(alpha);
    case Roughness::MirrorExponent: return phong_exponent_from_alpha(alpha) / 4.0;
    case Roughness::HalfCosine: return 1.0 / std::sqrt(1.0 + alpha * alpha);  // cos(atan alpha)
  }
  return alpha;
}

}  // namespace mfv
