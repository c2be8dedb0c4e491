// The sheen cases of mfv run (issue 21): the lobes of their own
// (Term::own_lobe: the Charlie sheen D and its visibility, KHR_materials_sheen)
// in d_norm, masking and furnace. The shared-width D x G grids leave them out
// (terms_of): the Charlie D pairs with no other G, and its mass sits at
// grazing microfacet normals, so the proposal takes its own width here.
// With them, the terms engines ship (issue 28; catalog/pairing.hpp): each
// G in its pairing under masking and furnace, each F under energy, all in
// reciprocity.
#include "catalog/pairing.hpp"
#include "checks/check_table.hpp"
#include "checks/furnace_truth.hpp"
#include "checks/integrate.hpp"
#include "checks/suite.hpp"
#include "checks/registry.hpp"
#include "runtime/dispatch.hpp"
#include "numeric/hemisphere_quadrature.hpp"
#include "util/parallel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace mfv {
namespace {

// Widths of masking and furnace: the catalog's range [1e-3, 1] at its ends
// and inside (d_norm takes every suite width in range).
const std::vector<double> kSheenAlphas = {1e-3, 0.01, 0.1, 0.3, 0.6, 1.0};

PointResult sheen_point(const std::string& check, const Term* d, const Term* g, const Term* f, double alpha) {
  PointResult p;
  p.check = check;
  p.d = d;
  p.g = g;
  p.f = f;
  p.params = {{"alpha", alpha}};
  p.expected = 1.0;
  return p;
}

// The exact Smith Λ of D at the view cosine cos_o, by quadrature of the
// double reference: cos_o (1 + Λ(o)) = ∫ max(0, o·m) D(m) dm, the projected
// area of the facets o sees (Heitz 2014 eq. 17 with Smith's G1 = 1/(1 + Λ)).
double lambda_by_quadrature(const Term& d, double alpha, double cos_o) {
  const glm::dvec3 o(std::sqrt((1.0 - cos_o) * (1.0 + cos_o)), 0.0, cos_o);
  auto g = [&](const glm::dvec3& m) {
    const double om = o.x * m.x + o.z * m.z;
    return om > 0.0 ? om * d.ref_d(m.z, alpha) : 0.0;
  };
  return integrate_normals(g, ProductRule{}).value / cos_o - 1.0;
}

// A sheen integral: F, its parameters and kd are 0 (none); the proposal's width its own.
IntegralSpec sheen_spec(IntegralKind kind, const Term* d, const Term* g, const Term* f, double alpha, double cos_o) {
  MicrofacetIntegral m;
  m.kind = kind;
  m.d = d;
  m.g = g;
  m.f = f;
  m.pd = alpha;
  m.pg = g ? native_widths(*d, *g, alpha).pg : 0.0;
  m.width = proposal_width(*d, alpha);
  m.cos_o = cos_o;
  return spec_of(m);
}

}  // namespace

// The masking integral's closed form G1(o) (1 + Λ_D(o)) for a sheen pair: 1
// where G1 is D's own Smith G1; the fit's error where G1 is a fit.
double sheen_masking_closed_form(const Term& d, const Term& g, double alpha, double cos_o) {
  return g.ref_g1(cos_o, alpha) * (1.0 + lambda_by_quadrature(d, alpha, cos_o));
}

namespace {

// One pairing of own-lobe terms mfv run checks: D, G and F (F none: the furnace's).
struct LobePair {
  const Term *d, *g, *f;
  bool smith;  // g's G1 is a Smith fit of d (masking from the closed form)
};

// The sheen pairs (a G whose Smith fit names the D), then the engine terms'
// pairings (engine_pairing), in catalog order.
std::vector<LobePair> lobe_pairs() {
  std::vector<LobePair> out;
  const Term* none = try_find_term("none", Kind::F);
  for (auto* d : own_lobe_terms_of(Kind::D))
    for (auto* g : own_lobe_terms_of(Kind::G))
      if (g->fit_for(d->id)) out.push_back({d, g, none, true});
  for (auto* g : own_lobe_terms_of(Kind::G))
    if (const Pairing* p = engine_pairing(*g)) out.push_back({try_find_term(p->d, Kind::D), g, none, false});
  for (auto* f : own_lobe_terms_of(Kind::F))
    if (const Pairing* p = engine_pairing(*f))
      out.push_back({try_find_term(p->d, Kind::D), try_find_term(p->g, Kind::G), f, false});
  return out;
}

// A plan's terms, each once (the generated dispatch has one case per term).
void add_terms(TermSelection& t, const Term* d, const Term* g, const Term* f) {
  auto once = [](std::vector<const Term*>& v, const Term* x) {
    if (x && std::find(v.begin(), v.end(), x) == v.end()) v.push_back(x);
  };
  once(t.d, d);
  once(t.g, g);
  once(t.f, f);
}

std::string pair_name(const LobePair& p, bool with_f) {
  return p.d->id + "/" + p.g->id + (with_f ? "/" + p.f->id : "");
}

}  // namespace

std::vector<std::string> sheen_model_names() {
  std::vector<std::string> out;
  for (auto* d : own_lobe_terms_of(Kind::D)) out.push_back(d->id);
  for (auto& p : lobe_pairs()) {
    out.push_back(pair_name(p, false));
    out.push_back(pair_name(p, true));
  }
  return out;
}

namespace {

bool add_sheen_plans(const CheckKind& kind, const SuiteOptions& opt, std::vector<Plan>& plans) {
  const Term* none = try_find_term("none", Kind::F);
  const std::vector<double> views = view_cosines(12);
  const Shape shape = shape_of(kind);
  if (shape == Shape::DNorm) {
    // ∫ D(m) (m·n) dm = 1 at every suite width in the D's range, the stratified estimator of mfv run
    Plan p = new_plan(kind.check, kind.base_samples, opt.scale);
    for (auto* d : own_lobe_terms_of(Kind::D)) {
      if (!suite_model_wanted(opt.models, d->id)) continue;
      p.terms.d.push_back(d);
      for (double a : suite_norm_alphas()) {
        if (a < d->params[0].lo || a > d->params[0].hi) continue;
        p.specs.push_back(sheen_spec(kind.kind, d, nullptr, nullptr, a, 1.0));
        PointResult pt = sheen_point(kind.check, d, nullptr, nullptr, a);
        pt.take(expect(kind.check, d, nullptr, a, 0, 0));
        p.points.push_back(pt);
      }
    }
    if (!p.specs.empty()) plans.push_back(p);
    return true;
  }
  // The pairs of G's own (F none) for masking and furnace; `smith`: those
  // whose G1 is a Smith fit of D, else the engine Gs
  auto pairs = [&](bool smith, auto add) {
    for (auto& lp : lobe_pairs())
      if (lp.smith == smith && lp.f == none &&
          suite_model_wanted(opt.models, pair_name(lp, shape != Shape::Masking)))
        add(*lp.d, *lp.g);
  };
  if (shape == Shape::Masking) {
    Plan p = new_plan(kind.check, kind.base_samples, opt.scale);
    pairs(true, [&](const Term& d, const Term& g) {
      add_terms(p.terms, &d, &g, nullptr);
      // The expectation from the closed form at the float cosine the kernel takes
      // (a quadrature each, on the host's threads): a fitted G1 is D's Smith G1
      // within the fit's error there, the tolerance.
      std::vector<double> closed(kSheenAlphas.size() * views.size());
      parallel_for(closed.size(), host_threads(), [&](size_t k) {
        const double a = kSheenAlphas[k / views.size()], co = views[k % views.size()];
        closed[k] = sheen_masking_closed_form(d, g, a, double(float(co)));
      });
      for (size_t k = 0; k < closed.size(); ++k) {
        const double a = kSheenAlphas[k / views.size()], co = views[k % views.size()];
        p.specs.push_back(sheen_spec(kind.kind, &d, &g, nullptr, a, co));
        PointResult pt = sheen_point(kind.check, &d, &g, nullptr, a);
        pt.params["cos_o"] = co;
        const double dev = std::fabs(closed[k] - 1.0);
        if (dev > kClosedFormMustFail) {
          pt.expect = Expect::Fail;
          pt.reason = fmt::format("{}'s G1 is off the Smith G1 of {} by {:.2g} here (closed form)", g.id, d.id, dev);
        } else {
          pt.tolerance = dev;
        }
        p.points.push_back(pt);
      }
    });
    // an engine's G with no Smith G1: the registry's expectation (may fail: a close fit can pass; see registry.cpp)
    pairs(false, [&](const Term& d, const Term& g) {
      add_terms(p.terms, &d, &g, nullptr);
      for (double a : kSheenAlphas)
        for (double co : views) {
          p.specs.push_back(sheen_spec(kind.kind, &d, &g, nullptr, a, co));
          PointResult pt = sheen_point(kind.check, &d, &g, nullptr, a);
          pt.params["cos_o"] = co;
          pt.take(expect(kind.check, &d, &g, a, 0, 0));
          p.points.push_back(pt);
        }
    });
    if (!p.specs.empty()) plans.push_back(p);
    return true;
  }
  if (shape == Shape::Energy) {
    // an engine's F under its D and G (F <= 1, so the albedo stays under the
    // furnace's): the registry's expectation, at the F's check points
    Plan p = new_plan(kind.check, kind.base_samples, opt.scale);
    for (auto& lp : lobe_pairs()) {
      if (lp.f == none || !suite_model_wanted(opt.models, pair_name(lp, true))) continue;
      add_terms(p.terms, lp.d, lp.g, lp.f);
      for (auto& fp : lp.f->check_points)
        for (double a : kSheenAlphas)
          for (double co : views) {
            MicrofacetIntegral m;
            m.kind = kind.kind;
            m.d = lp.d, m.g = lp.g, m.f = lp.f;
            const NativeWidths w = native_widths(*lp.d, *lp.g, a);
            m.pd = w.pd, m.pg = w.pg, m.f0 = fp.p0, m.f1 = fp.p1;
            m.width = proposal_width(*lp.d, a);
            m.cos_o = co;
            p.specs.push_back(spec_of(m));
            PointResult pt = sheen_point(kind.check, lp.d, lp.g, lp.f, a);
            pt.params["cos_o"] = co;
            pt.params[lp.f->params[0].name] = fp.p0;
            if (lp.f->params.size() > 1) pt.params[lp.f->params[1].name] = fp.p1;
            pt.upper_only = kind.upper_only;
            pt.take(expect(kind.check, lp.d, lp.g, a, fp.p0, 0));
            p.points.push_back(pt);
          }
    }
    if (!p.specs.empty()) plans.push_back(p);
    return true;
  }
  if (shape == Shape::Pairs) {
    // reciprocity batches of every pairing (as the grid's: alpha 0.3, each F point)
    Plan p;
    p.check = kind.check;
    for (auto& lp : lobe_pairs()) {
      if (!suite_model_wanted(opt.models, pair_name(lp, true))) continue;
      add_terms(p.terms, lp.d, lp.g, lp.f);
      const NativeWidths w = native_widths(*lp.d, *lp.g, 0.3);
      for (auto& fp : lp.f->check_points) {
        IntegralSpec s;
        s.d = term_index(*lp.d);
        s.g = term_index(*lp.g);
        s.f = term_index(*lp.f);
        s.pd = float(w.pd);
        s.pg = float(w.pg);
        s.f0 = float(fp.p0);
        s.f1 = float(fp.p1);
        p.specs.push_back(s);
        PointResult pt = sheen_point(kind.check, lp.d, lp.g, lp.f, 0.3);
        pt.expected = 0.0;
        if (!fp.label.empty()) pt.params[lp.f->params[0].name] = fp.p0;
        if (lp.f->params.size() > 1) pt.params[lp.f->params[1].name] = fp.p1;
        p.points.push_back(pt);
      }
    }
    plans.push_back(p);
    return true;
  }
  if (shape == Shape::Furnace) {
    // white furnace (F = 1): the sheen lobe's albedo E_sheen(cos_o) <= 1
    // (two-sided in the pool, against the quadrature of checks/furnace_truth)
    Plan p = new_plan(kind.check, kind.base_samples, opt.scale);
    auto furnace = [&](const Term& d, const Term& g) {
      add_terms(p.terms, &d, &g, none);
      for (double a : kSheenAlphas)
        for (double co : views) {
          p.specs.push_back(sheen_spec(kind.kind, &d, &g, none, a, co));
          PointResult pt = sheen_point(kind.check, &d, &g, none, a);
          pt.params["cos_o"] = co;
          pt.upper_only = kind.upper_only;
          // The expectation from the albedo by quadrature of the double reference
          // (checks/furnace_truth): Estevez and Kulla's fitted Λ under-masks near
          // grazing for small widths (masking shows it), and there the lobe alone
          // reflects more than it receives.
          const KnownValue q = cached_albedo_by_quadrature(p.specs.back());  // attach_furnace_truth reuses it
          if (q.value - q.error > 1.1) {  // ~5 standard errors of a default-size integral
            pt.expect = Expect::Fail;
            pt.reason = g.fit_for(d.id)
                            ? fmt::format("the fitted Lambda of {} under-masks {} here: E = {:.3g} by quadrature",
                                          g.id, d.id, q.value)
                            : fmt::format("{} is no Smith G of {} and masks too little here: E = {:.3g} by "
                                          "quadrature",
                                          g.id, d.id, q.value);
          } else if (q.value + q.error > 1.0) {
            pt.expect = Expect::May;
            pt.reason = fmt::format("E = {:.3g} by quadrature, within noise of 1", q.value);
          }
          p.points.push_back(pt);
        }
    };
    pairs(true, furnace);
    pairs(false, furnace);
    if (!p.specs.empty()) plans.push_back(p);
    return true;
  }
  return false;
}

}  // namespace

PointSource sheen_source(const SuiteOptions& opt) {
  return {kSourceSheen, "the sheen lobes",
          [&opt](const CheckKind& k, std::vector<Plan>& plans) { return add_sheen_plans(k, opt, plans); }};
}

}  // namespace mfv
