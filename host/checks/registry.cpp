#include "checks/registry.hpp"

#include "abi/bsdf.h"
#include "catalog/roughness.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace mfv {

namespace {

// ---- expectations: which models must fail which kind, and why, from catalog properties

Expectation expect_d_norm(const ExpectPoint& p) {
  if (p.d && !p.d->known_bad.empty()) return {Expect::Fail, "D " + p.d->id + ": " + p.d->known_bad, 0};
  return {};
}

Expectation expect_masking(const ExpectPoint& p) {
  if (p.d && !p.d->known_bad.empty()) return {Expect::Fail, "D " + p.d->id + ": " + p.d->known_bad, 0};
  const Term *d = p.d, *g = p.g;
  const SmithFit* fit = g->fit_for(d->id);
  if (g->smith_for.empty()) {
    if (!g->masking_exact.empty()) return {Expect::Hold, "", 0};
    // an engine's own-lobe G (hammon_clamped fits height-correlated Smith-GGX
    // closely): its masking error is below the check's power on some seeds
    // (ggx/hammon_clamped passed at seed 20 of the 20-seed test), so may fail
    if (g->own_lobe)
      return {Expect::May, g->id + " is no Smith G1 of any D (Heitz 2014 §5.4): its projected area is not conserved",
              0};
    return {Expect::Fail, g->id + " is no Smith G1 of any D (Heitz 2014 §5.4): its projected area is not conserved", 0};
  }
  if (!fit) return {Expect::Fail, g->id + "'s G1 belongs to " + g->smith_for.front().d + ", not to " + d->id, 0};
  if (p.alpha > fit->alpha_max) return {Expect::Fail, fmt::format("beyond alpha = {}: {}", fit->alpha_max, fit->why), 0};
  return {Expect::Hold, "", fit->tol};
}

// furnace (F = 1) and energy (F <= 1): a G1 that masks less than D's own lets
// the albedo exceed 1; one that masks more only loses energy. `broken`: what
// such a point must do (furnace: fail; energy: F <= 1 may hide the gain).
Expectation expect_albedo(const ExpectPoint& p, Expect broken) {
  const Term *d = p.d, *g = p.g;
  if (g->smith_for.empty()) return {};
  const SmithFit* fit = g->fit_for(d->id);
  if (std::find(g->under_masks.begin(), g->under_masks.end(), d->id) != g->under_masks.end())
    return {broken,
            g->id + "'s G1 (of " + g->smith_for.front().d + ") under-masks " + d->id +
                "'s heavier tails, so the albedo exceeds 1 at grazing view",
            0};
  if (fit && p.alpha > fit->alpha_max)
    return {broken, fmt::format("beyond alpha = {}: {}", fit->alpha_max, fit->why), 0};
  return {Expect::Hold, "", fit ? fit->tol : 0.0};
}
Expectation expect_furnace(const ExpectPoint& p) { return expect_albedo(p, Expect::Fail); }
Expectation expect_energy(const ExpectPoint& p) { return expect_albedo(p, Expect::May); }

// kd/pi + specular, no (1 - F) weight: at kd = 1 and F0 = 1 the albedo is
// 1 + the specular albedo; at smaller kd or F0 it may or may not pass 1.
Expectation expect_energy_diffuse(const ExpectPoint& p) {
  std::string why = "seed 000's kd/pi + specular adds the diffuse albedo to the specular one with no (1-F) weight";
  return {p.kd >= 1.0 && p.f0 >= 1.0 ? Expect::Fail : Expect::May, why, 0};
}

// The rough dielectric BSDF's flux against the facet-space truth: every
// known-bad entry of catalog/bsdfs.cpp plants a bug that moves E_T (F at n.i,
// eta_o^2 dropped, the Jacobian's sum, same-side directions counted) or
// E_R + E_T (a G1 from another D: the truth takes D's own Smith G).
Expectation expect_bsdf_furnace(const ExpectPoint& p) {
  if (p.bsdf && !p.bsdf->known_bad.empty()) return {Expect::Fail, p.bsdf->id + ": " + p.bsdf->known_bad, 0};
  return {};
}

// The BTDF's G1 from below is D's Smith G1 where G belongs to D (as masking
// from above): the known-bad entry with another D's G1 fails, the rest hold.
// A fit used beyond its alpha_max (Beckmann's G1 for Phong and Blinn rho) is
// off by 4-7 % at alpha 0.3-0.4, which the transmission-masking estimator's
// SE at grazing view (0.097 at 512 samples, cos_o 0.01) cannot resolve on
// every seed: the 20-seed test saw 15 of 80 such groups pass. There a failure
// is allowed, not required.
Expectation expect_transmission_masking(const ExpectPoint& p) {
  Expectation e = expect_masking(p);
  const SmithFit* fit = p.g && p.d && !p.g->smith_for.empty() ? p.g->fit_for(p.d->id) : nullptr;
  if (e.expect == Expect::Fail && fit && p.alpha > fit->alpha_max) e.expect = Expect::May;
  return e;
}

// Generalized reciprocity f_t(i,o)/eta_o^2 = f_t(o,i)/eta_i^2: the known-bad
// entries whose bug is not symmetric in i and o fail it (eta_o^2 dropped, F
// at n.i, the Jacobian's unweighted sum); a same-side count and another D's
// G1 keep it (tests/test_btdf.cpp shows both on the reference).
Expectation expect_bsdf_reciprocity(const ExpectPoint& p) {
  if (!p.bsdf) return {};
  const int v = p.bsdf->variant;
  if (v == MFV_BTDF_BAD_NO_ETA2 || v == MFV_BTDF_BAD_F_AT_N || v == MFV_BTDF_BAD_JACOBIAN)
    return {Expect::Fail, p.bsdf->id + ": " + p.bsdf->known_bad + " (not symmetric under i <-> o)", 0};
  return {};
}

// The hemispherical averages' reciprocity T_avg(1/eta) = T_avg(eta)/eta^2 is
// the pointwise identity integrated over both directions: the entries that
// break that one break this one, as far as the averages' estimator resolves
// (measured, mfv run seeds 1-3 at 16384 samples: eta_o^2 dropped |z| 19-37 at
// every width; F at n.i |z| 8-46 at alpha >= 0.3 but at most 4 at 0.05 and
// 1 at 1e-4, where F at n.i is nearly F at the facet; the Jacobian's sum,
// which vanishes at o = -i, makes E_T diverge and the estimate's variance
// infinite: -2.4e4 +- 1.4e4, no verdict).
Expectation expect_bsdf_avg(const ExpectPoint& p) {
  Expectation e = expect_bsdf_reciprocity(p);
  if (e.expect != Expect::Fail) return e;
  const int v = p.bsdf->variant;
  if (v == MFV_BTDF_BAD_JACOBIAN || (v == MFV_BTDF_BAD_F_AT_N && p.alpha < 0.3)) e.expect = Expect::May;
  return e;
}

// An exact albedo holds exactly in a correct model: a whole model's closed
// form, and a thin-walled transmitting material's R + T = the F = 1 albedo of
// its lobe (white base, full transmission, no metal: F and 1 - F of one
// mirrored half vector add to 1). Every point must hold.
Expectation expect_exact(const ExpectPoint&) { return {}; }

std::vector<CheckKind> make_kinds() {
  std::vector<CheckKind> k;
  auto add = [&](const char* name) -> CheckKind& {
    k.emplace_back();
    k.back().check = name;
    return k.back();
  };
  {
    CheckKind& c = add("d_norm");
    c.kind = IntegralKind::DNorm;
    c.terms_read = 1;
    c.base_samples = 256 * kSuiteBaseSamples;
    c.sources = kSourceGrid | kSourceAniso | kSourceSheen | kSourceScene | kSourceUser;
    c.not_taken = "a whole model has no D of its own to integrate";
    c.expect = expect_d_norm;
    c.verdict = "holds for every D but those the catalog marks known_bad";
    c.summary = "D is normalized: the integral of D(m)(m.n) over the hemisphere is 1 (two-sided)";
  }
  {
    CheckKind& c = add("masking");
    c.kind = IntegralKind::Masking;
    c.terms_read = 2;
    c.base_samples = kSuiteBaseSamples;
    c.n_alpha = 12;
    c.n_view = 32;
    c.sources = kSourceGrid | kSourceAniso | kSourceSheen | kSourceScene | kSourceUser;
    c.not_taken = "a whole model has no separate D and G1";
    c.expect = expect_masking;
    c.verdict =
        "holds where G's Smith G1 belongs to D (Term::smith_for, within its tolerance and alpha_max) or G is "
        "normalised against every D (masking_exact); fails otherwise";
    c.summary = "G1 is D's Smith masking: the weak white furnace integrates to 1 (Heitz 2014 eq. 19, two-sided)";
  }
  {
    CheckKind& c = add("furnace");
    c.kind = IntegralKind::AlbedoMis;
    c.base_samples = kSuiteBaseSamples;
    c.n_alpha = 12;
    c.n_view = 32;
    c.upper_only = true;
    c.sources = kSourceGrid | kSourceAniso | kSourceSheen | kSourceScene | kSourceUser;
    c.not_taken = "a whole model's white furnace is its energy check";
    c.expect = expect_furnace;
    c.truth = true;
    c.verdict =
        "holds for Smith Gs (and non-Smith Gs); fails where G's G1 under-masks D's tails (under_masks) or beyond "
        "the fit's alpha_max";
    c.summary = "the white furnace (F = 1): the albedo is at most 1 (one-sided; pooled against quadrature)";
  }
  {
    CheckKind& c = add("energy");
    c.kind = IntegralKind::AlbedoMis;
    c.base_samples = kSuiteBaseSamples / 2;
    c.n_alpha = 6;
    c.n_view = 24;
    c.fs = FSet::Real;
    c.upper_only = true;
    c.sources = kSourceGrid | kSourceModels | kSourceSheen | kSourceScene | kSourceUser;
    c.not_taken = "the anisotropic pairs are checked with F = 1 only (furnace); of the own lobes, only engines' F terms";
    c.expect = expect_energy;
    c.verdict = "as furnace, but F <= 1 may hide a gain: may fail where furnace must";
    c.summary = "energy with every F (and whole models at 10 lights): the albedo is at most 1 (one-sided)";
  }
  {
    CheckKind& c = add("energy_diffuse");
    c.kind = IntegralKind::AlbedoMis;
    c.base_samples = kSuiteBaseSamples / 2;
    c.n_alpha = 3;
    c.n_view = 8;
    c.fs = FSet::Schlick;
    c.kds = {0.5, 1.0};
    c.upper_only = true;
    c.sources = kSourceGrid | kSourceScene;
    c.not_taken = "only seed 000's kd/pi + specular sum (the grid, a scene's kd material) has a diffuse term";
    c.expect = expect_energy_diffuse;
    c.verdict = "seed 000's kd/pi + specular: fails at kd = 1 and F0 = 1, may fail below";
    c.summary = "diffuse + specular (seed 000): the albedo is at most 1 (one-sided)";
  }
  {
    CheckKind& c = add("reciprocity");
    c.runner = Runner::Pairs;
    c.domain = Domain::Hemisphere;
    c.base_samples = 64;  // pairs per work-item at scale 1 (record_reciprocity)
    c.expected = 0.0;
    c.sources = kSourceGrid | kSourceModels | kSourceSheen | kSourceScene | kSourceUser;
    c.not_taken = "the anisotropic pairs' terms are reciprocal by their form (agree compares them)";
    c.verdict = "holds for every D x G x F; whole models from their cases (ModelCase::reciprocity)";
    c.summary = "f(i,o) = f(o,i) to float rounding over sampled pairs (a bounded maximum)";
  }
  {
    CheckKind& c = add("closed_form");
    c.kind = IntegralKind::Albedo;
    c.base_samples = kSuiteBaseSamples * kClosedFormFactor;
    c.n_view = kModelLights;
    c.sources = kSourceModels | kSourceScene;
    c.expect = expect_exact;
    c.not_taken = "only a whole model has an exact albedo of its own (Model::ref_albedo; a scene's thin-walled "
                  "transmitting material: the F = 1 albedo of its lobe)";
    c.verdict = "holds for every whole model with a closed-form albedo, and for a correct thin-walled "
                "KHR_materials_transmission (white base, full transmission, no metal: R + T = the F = 1 albedo)";
    c.summary = "a whole model's albedo equals its closed form (two-sided): model and estimator agree";
  }
  {
    CheckKind& c = add("agree");
    c.runner = Runner::Pointwise;
    c.base_samples = 4096;  // inputs per term or BRDF at scale 1 (mfv agree's default: 10^6)
    c.expected = 0.0;
    // a user's file (mfv check) against its double twin (user/user_twin.hpp)
    c.sources = kSourceGrid | kSourceAniso | kSourceSheen | kSourceModels | kSourceBsdf | kSourceUser;
    c.not_taken = "a scene's materials are compared by mfv agree --scene";
    c.verdict = "holds for every term, BRDF and model: kernel and reference agree within the ULP table";
    c.summary = "kernel and double reference agree on identical inputs within each term's ULP budget";
  }
  {
    CheckKind& c = add("stability");
    c.runner = Runner::Pointwise;
    c.base_samples = 0;  // a fixed deterministic sweep (mfv stability's)
    c.expected = 0.0;
    c.sources = kSourceGrid | kSourceAniso | kSourceSheen | kSourceModels | kSourceBsdf;
    c.not_taken = "a scene's models are swept by mfv stability --scene";
    c.verdict = "holds for every case the catalog marks stable; the others are reported by mfv stability";
    c.summary = "no NaN, Inf or out-of-domain value on in-domain extreme inputs (stable terms and BRDFs)";
  }
  {
    // mfv check's census of a user's code (user/user_pointwise.cpp): the
    // stability sweep's extreme inputs, judged finite and non-negative (a
    // user's file has no catalog entry to say which cases are stable).
    CheckKind& c = add("finite");
    c.runner = Runner::Pointwise;
    c.base_samples = 0;  // a fixed deterministic sweep
    c.expected = 0.0;
    c.in_run = false;
    c.sources = kSourceUser;
    c.not_taken = "the catalog's models are swept by stability, which knows which cases are stable";
    c.verdict = "holds for a correct BRDF: no NaN, Inf or negative value of brdf, D or G1 on the sweep's inputs";
    c.summary = "no NaN, Inf or negative value on the stability sweep's extreme inputs (mfv check)";
  }
  {
    CheckKind& c = add("bsdf_furnace");
    c.kind = IntegralKind::BsdfFlux;
    c.domain = Domain::Sphere;
    c.terms_read = 2;  // D and G (F is the exact dielectric one, bsdf and eta carry the rest)
    c.base_samples = kSuiteBaseSamples;
    c.n_view = 6;
    // a scene: its refracting materials (KHR_materials_volume); a user's btdf or bsdf (mfv check)
    c.sources = kSourceBsdf | kSourceScene | kSourceUser;
    c.not_taken = "only the rough dielectric BSDFs (catalog/bsdfs.hpp) transmit";
    c.expect = expect_bsdf_furnace;
    c.verdict = "holds for every rough dielectric BSDF but the known-bad entries (Bsdf::known_bad), which must fail";
    c.summary =
        "rough dielectric BSDF, flux form: E_R and E_T of the light from one direction (o over the sphere) equal the "
        "facet-space truth with the total-internal-reflection cut, whose E_R + E_T <= 1 (two-sided)";
  }
  {
    CheckKind& c = add("transmission_masking");
    c.kind = IntegralKind::MaskingT;
    c.terms_read = 2;
    c.base_samples = kSuiteBaseSamples;
    c.n_view = 8;
    c.sources = kSourceBsdf | kSourceScene | kSourceUser;  // a user's btdf or bsdf with D and G1 (mfv check)
    c.not_taken = "only the rough dielectric BSDFs (catalog/bsdfs.hpp) mask a direction below the surface";
    c.expect = expect_transmission_masking;
    c.verdict = "as masking: holds where the BTDF's G1 is its D's Smith G1 (within the fit); the entry with another "
                "D's G1 (walter_ggx_beckmann_g1) must fail";
    c.summary =
        "the BTDF's G1 below the surface: the weak white furnace integral of G1(o,m) max(0,-o.m) D(m) is |o.n| "
        "(Heitz 2014 eq. 19, two-sided)";
  }
  {
    CheckKind& c = add("bsdf_avg_reciprocity");
    c.kind = IntegralKind::BsdfAvg;
    c.domain = Domain::Sphere;
    c.terms_read = 2;  // D and G (F is the exact dielectric one)
    c.base_samples = 4 * kSuiteBaseSamples;
    c.expected = 0.0;
    // a scene: its refracting materials (KHR_materials_volume); a user's btdf or bsdf (mfv check)
    c.sources = kSourceBsdf | kSourceScene | kSourceUser;
    c.not_taken = "only the rough dielectric BSDFs (catalog/bsdfs.hpp) transmit";
    c.expect = expect_bsdf_avg;
    c.verdict = "holds for every rough dielectric BSDF but eta_o^2 dropped and F at n.i (at alpha >= 0.3), which "
                "must fail; the Jacobian's sum may (its averages diverge)";
    c.summary =
        "rough dielectric BSDF, flux form: the hemispherical averages obey reciprocity, T_avg(1/eta) = "
        "T_avg(eta)/eta^2 (two-sided; at alpha = 1e-4 the smooth interface's 1 - Fbar(1/eta) = (1 - Fbar(eta))/eta^2)";
  }
  {
    CheckKind& c = add("bsdf_reciprocity");
    c.runner = Runner::Pointwise;
    c.domain = Domain::Sphere;
    c.base_samples = 1024;  // pairs per BSDF, width and index at scale 1 (checks/bsdf_reciprocity.cpp)
    c.expected = 0.0;
    c.sources = kSourceBsdf | kSourceUser;  // a user's btdf or bsdf: host/user/user_transmission.cpp
    c.not_taken = "only the rough dielectric BSDFs (catalog/bsdfs.hpp) transmit";
    c.expect = expect_bsdf_reciprocity;
    c.verdict = "holds for every rough dielectric BSDF but the known-bad entries not symmetric in i and o (eta_o^2 "
                "dropped, F at n.i, the Jacobian's sum), which must fail";
    c.summary =
        "rough dielectric BTDF, radiance form: f_t(i,o)/eta_o^2 = f_t(o,i)/eta_i^2 over random, grazing, "
        "near-critical and refracted pairs, float kernel and double twin each within its derived bound";
  }
  {
    CheckKind& c = add("energy_mu");
    c.runner = Runner::Table;
    c.kind = IntegralKind::AlbedoRqmc;
    c.base_samples = 1024;  // points per replicate of the first pass (--min-points)
    c.n_alpha = 32;
    c.n_view = 32;
    c.upper_only = true;
    c.in_run = false;
    c.sources = kSourceGrid | kSourceModels | kSourceScene;
    c.not_taken = "mfv energy tabulates the catalog's and a scene's models";
    c.verdict =
        "tables: measured, no verdict; whole models: E(mu) <= 1 beyond noise and float rounding (ModelCase::energy)";
    c.summary = "mfv energy: E(mu) and the split sum's B per width and view (RQMC replicates)";
  }
  {
    CheckKind& c = add("energy_avg");
    c.runner = Runner::Table;
    c.kind = IntegralKind::EavgRqmc;
    c.base_samples = 1024;
    c.n_alpha = 32;
    c.n_view = 0;
    c.upper_only = true;
    c.in_run = false;
    c.sources = kSourceGrid | kSourceModels | kSourceScene;
    c.not_taken = "mfv energy tabulates the catalog's and a scene's models";
    c.verdict = "measured, no verdict (cross-checked by the midpoint rule over energy_mu)";
    c.summary = "mfv energy: E_avg, the albedo averaged with density 2 mu (RQMC replicates)";
  }
  return k;
}

}  // namespace

const std::vector<CheckKind>& check_kinds() {
  static const std::vector<CheckKind> kinds = make_kinds();
  return kinds;
}

const CheckKind* find_check_kind(const std::string& check) {
  for (const CheckKind& k : check_kinds())
    if (check == k.check) return &k;
  return nullptr;
}

const CheckKind& check_kind(const std::string& check) {
  if (const CheckKind* k = find_check_kind(check)) return *k;
  throw Error(fmt::format("internal: no check kind named '{}' (checks/registry.cpp)", check));
}

const std::vector<std::string>& suite_checks() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const CheckKind& k : check_kinds())
      if (k.in_run) out.push_back(k.check);
    return out;
  }();
  return names;
}

std::string suite_check_list() {
  std::string out;
  for (const std::string& c : suite_checks()) out += (out.empty() ? "" : ", ") + c;
  return out;
}

std::vector<const CheckKind*> grid_kinds() {
  std::vector<const CheckKind*> out;
  for (const CheckKind& k : check_kinds())
    if (k.runner == Runner::Integral && k.in_run && (k.sources & kSourceGrid)) out.push_back(&k);
  return out;
}

const std::vector<CheckKind>& energy_check_rows() {
  static const std::vector<CheckKind> rows = [] {
    std::vector<CheckKind> out;
    for (const CheckKind& k : check_kinds())
      if (k.runner == Runner::Table) out.push_back(k);
    return out;
  }();
  return rows;
}

Shape shape_of(const CheckKind& k) {
  if (k.runner == Runner::Pairs) return Shape::Pairs;
  if (k.runner != Runner::Integral) return Shape::None;
  switch (k.kind) {
    case IntegralKind::DNorm: return Shape::DNorm;
    case IntegralKind::Masking: return Shape::Masking;
    case IntegralKind::Albedo:
    case IntegralKind::AlbedoMis:
    case IntegralKind::AlbedoRqmc:
      if (!k.upper_only) return Shape::Exact;
      return k.fs == FSet::None ? Shape::Furnace : Shape::Energy;
    case IntegralKind::BsdfFlux: return Shape::BsdfFlux;
    case IntegralKind::MaskingT: return Shape::MaskingT;
    case IntegralKind::BsdfAvg: return Shape::BsdfAvg;
    default: return Shape::None;
  }
}

bool diffuse_of(const CheckKind& k) {
  return shape_of(k) == Shape::Energy && std::any_of(k.kds.begin(), k.kds.end(), [](double kd) { return kd > 0; });
}

Expectation expect(const std::string& check, const Term* d, const Term* g, double alpha, double f0, double kd) {
  const CheckKind& k = check_kind(check);
  return k.expect ? k.expect({d, g, alpha, f0, kd, nullptr}) : Expectation{};
}

NativeWidths native_widths(const Term& d, const Term& g, double alpha) {
  NativeWidths w;
  w.pd = native_from_alpha(d.roughness, alpha);
  w.pg = g.params.empty() ? 0.0 : std::min(native_from_alpha(g.roughness, alpha), g.params[0].hi);
  return w;
}

}  // namespace mfv
