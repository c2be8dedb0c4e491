// The anisotropic cases of mfv run (issue 8): anisotropic GGX and Beckmann
// (Term::aniso, widths alpha_x along t = +x and alpha_y along b = +y) in
// d_norm, masking and furnace, with the view at azimuths along t, along b
// and between them. The generic D x G grids pass one width and leave these
// terms out (terms_of); here every integral carries both (IntegralSpec::pd2).
#include "checks/suite.hpp"

#include "reference/reference.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace mfv {
namespace {

struct Widths {
  double ax, ay;
};
// Strongly anisotropic both ways, near-zero roughness, rough, and the
// isotropic limit (ax = ay, where the terms equal ggx / beckmann).
const std::vector<Widths> kPairs = {{0.05, 0.5}, {0.5, 0.05}, {1e-3, 0.3}, {1e-4, 1e-3},
                                    {0.2, 0.8},  {1.0, 0.1},  {0.3, 0.3}};
// Views: cosines from grazing to near-normal, azimuths along t (0), along b
// (π/2), the diagonal (π/4) and a generic one.
const std::vector<double> kViewCos = {1e-3, 0.02, 0.1, 0.3, 0.6, 0.95};
const std::vector<double> kViewPhi = {0.0, M_PI / 2, M_PI / 4, 2.5};

// The Smith Λ of an anisotropic D's own family at the direction v.
double lambda_of(const Term& d, const glm::dvec3& v, const Widths& w) {
  return d.id == "aniso_beckmann" ? ref::Lambda_beckmann_aniso(v, w.ax, w.ay) : ref::Lambda_ggx_aniso(v, w.ax, w.ay);
}

// The masking integral in closed form: a Smith G1(o) does not depend on m,
// so ∫ G1(o) D(m) max(0, o·m) dm / cos_o = G1(o) (1 + Λ_D(o)) (Heitz 2014
// eq. 19 with the projected area cos_o (1 + Λ_D(o)) of the visible facets).
double masking_closed_form(const Term& d, const Term& g, const glm::dvec3& o, const Widths& w) {
  double g1 = g.aniso ? g.ref_g1_aniso(o, w.ax, w.ay) : g.ref_g1(o.z, w.ax);
  return g1 * (1.0 + lambda_of(d, o, w));
}

IntegralSpec aniso_spec(IntegralKind kind, const Term& d, const Term* g, const Term* f, const Widths& w, double co,
                        double phi) {
  MicrofacetIntegral m;
  m.kind = kind;
  m.d = &d, m.g = g, m.f = f;
  m.pd = m.pg = w.ax;
  m.pd2 = m.pg2 = w.ay;
  m.width = w.ax;
  m.cos_o = co, m.phi_o = phi;
  return spec_of(m);
}

PointResult aniso_point(const std::string& check, const Term& d, const Term* g, const Term* f, const Widths& w) {
  PointResult p;
  p.check = check;
  p.d = &d;
  p.g = g;
  p.f = f;
  p.params = {{"alpha_x", w.ax}, {"alpha_y", w.ay}};
  p.expected = 1.0;
  return p;
}

// Every pair and view of `kind` for D x G (x F): the spec and its point,
// which `expect` may annotate with the view o it was given.
template <class Expect_>
void add_views(Plan& p, IntegralKind kind, const Term& d, const Term* g, const Term* f, Expect_ expect) {
  for (auto& w : kPairs)
    for (double co : kViewCos)
      for (double phi : kViewPhi) {
        p.specs.push_back(aniso_spec(kind, d, g, f, w, co, phi));
        PointResult pt = aniso_point(p.check, d, g, f, w);
        pt.params["cos_o"] = co;
        pt.params["phi_o"] = phi;
        // the view the kernel takes, from the float cosine and azimuth
        const double c = double(float(co)), ph = double(float(phi)), so = std::sqrt((1 - c) * (1 + c));
        expect(pt, glm::dvec3(so * std::cos(ph), so * std::sin(ph), c), w);
        p.points.push_back(pt);
      }
}

// Gs paired with the anisotropic Ds in masking: the anisotropic Smith terms
// and the isotropic Smith G1s of both families, whose single width alpha_x
// is right only for views along t.
std::vector<const Term*> masking_gs() {
  std::vector<const Term*> gs = aniso_terms_of(Kind::G);
  for (const char* id : {"smith_ggx", "smith_beckmann"}) gs.push_back(try_find_term(id, Kind::G));
  return gs;
}

}  // namespace

std::vector<std::string> aniso_model_names() {
  std::vector<std::string> out;
  for (auto* d : aniso_terms_of(Kind::D)) {
    out.push_back(d->id);
    for (auto* g : masking_gs()) out.push_back(d->id + "/" + g->id);
    for (auto* g : aniso_terms_of(Kind::G)) out.push_back(d->id + "/" + g->id + "/none");
  }
  return out;
}

PointSource aniso_source(const SuiteOptions& opt) {
  return {
      kSourceAniso, "the anisotropic pairs", [&opt](const CheckKind& k, std::vector<Plan>& plans) {
        const Term* none = try_find_term("none", Kind::F);
        Plan p = new_plan(k.check, k.base_samples, opt.scale);
        switch (shape_of(k)) {
          case Shape::DNorm:
            // ∫ D(m) (m·n) dm = 1, stratified in (stretched radius, azimuth)
            for (auto* d : aniso_terms_of(Kind::D)) {
              if (!suite_model_wanted(opt.models, d->id)) continue;
              p.terms.d.push_back(d);
              for (auto& w : kPairs) {
                p.specs.push_back(aniso_spec(k.kind, *d, nullptr, nullptr, w, 1.0, 0.0));
                p.points.push_back(aniso_point(k.check, *d, nullptr, nullptr, w));
              }
            }
            break;
          case Shape::Masking:
            p.terms.d = aniso_terms_of(Kind::D);
            p.terms.g = masking_gs();
            for (auto* d : p.terms.d)
              for (auto* g : p.terms.g) {
                if (!suite_model_wanted(opt.models, d->id + "/" + g->id)) continue;
                add_views(p, k.kind, *d, g, nullptr, [&](PointResult& pt, const glm::dvec3& o, const Widths& w) {
                  // the expectation from the closed form
                  const double dev = std::fabs(masking_closed_form(*d, *g, o, w) - 1.0);
                  if (dev > kClosedFormMustFail) {
                    pt.expect = Expect::Fail;
                    pt.reason =
                        fmt::format("{}'s G1 is not the Smith G1 of {} at this view (closed form off by {:.2g})", g->id,
                                    d->id, dev);
                  } else if (dev > 1e-4) {
                    pt.expect = Expect::May;
                    pt.reason =
                        fmt::format("{}'s G1 is off by {:.2g} at this view (closed form), near the noise", g->id, dev);
                  }
                });
              }
            break;
          case Shape::Furnace:
            // white furnace (F = 1): albedo <= 1 for the matched anisotropic pairs, by the
            // kind's own estimator (AlbedoMis: kernels/albedo.cl albedo_mis_general)
            p.terms.d = aniso_terms_of(Kind::D);
            p.terms.g = aniso_terms_of(Kind::G);
            p.terms.f = {none};
            for (auto* d : p.terms.d)
              for (auto* g : p.terms.g) {
                if (!g->fit_for(d->id) || !suite_model_wanted(opt.models, d->id + "/" + g->id + "/none")) continue;
                add_views(p, k.kind, *d, g, none,
                          [&k](PointResult& pt, const glm::dvec3&, const Widths&) { pt.upper_only = k.upper_only; });
              }
            break;
          default: return false;
        }
        plans.push_back(p);
        return true;
      }};
}

}  // namespace mfv
