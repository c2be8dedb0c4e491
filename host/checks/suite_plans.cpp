// The plan builder: "what to check" (the catalog's D x G x F grid by the
// registry of check kinds, checks/registry.hpp; whole models; reciprocity
// batches) into integrals (IntegralSpec) and the points that describe them,
// each with the verdict the catalog expects. mfv run --scene
// (scene/scene_checks.cpp), mfv check (user/user_check.cpp) and the
// anisotropic cases (suite_aniso.cpp) build theirs from the same pieces.
#include "checks/suite.hpp"

#include "catalog/roughness.hpp"
#include "checks/registry.hpp"
#include "checks/integrate.hpp"
#include "checks/profile.hpp"
#include "runtime/specialize.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace mfv {

namespace {

// ---- grids ---------------------------------------------------------------

// Widths from extreme to rough, for d_norm; each D keeps those in its range.
// Down to 1e-7 (near-mirror, issue 16): d_norm's stratified radius keeps
// sin²θ to full precision, so the narrowest lobes still integrate to 1.
const std::vector<double> kNormAlphas = {1e-7, 1e-6, 1e-5, 1e-4, 3e-4, 1e-3, 3e-3, 0.01, 0.03,
                                         0.1,  0.2,  0.3,  0.5,  0.7,  1.0,  1.5,  2.0};
const std::vector<double> kNormPhong = {0, 1, 2, 5, 10, 30, 100, 300, 1e3, 1e4, 1e5, 1e6};
// Shared widths and view cosines for the combination checks.
const std::vector<double> kAlphas = {0.01, 0.03, 0.07, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.65, 0.8, 1.0};
}  // namespace

const std::vector<double>& suite_norm_alphas() { return kNormAlphas; }
const std::vector<double>& suite_alphas() { return kAlphas; }

bool suite_check_wanted(const SuiteOptions& opt, const std::string& check) {
  return opt.checks.empty() || std::find(opt.checks.begin(), opt.checks.end(), check) != opt.checks.end();
}

bool suite_model_wanted(const std::vector<std::string>& filter, const std::string& name) {
  if (filter.empty()) return true;
  for (auto& f : filter)
    if (name.find(f) != std::string::npos) return true;
  return false;
}

std::vector<double> view_cosines(int n) {
  // dense towards grazing: cos from 1e-4 (0.006 degrees above the horizon) to 1
  std::vector<double> c;
  for (int i = 0; i < n; ++i) c.push_back(std::pow(10.0, -4.0 * double(n - 1 - i) / double(n - 1)));
  return c;
}

namespace {

// ---- running ---------------------------------------------------------------

void add_point(Plan& plan, IntegralKind kind, const Term* d, const Term* g, const Term* f, double alpha, double pd,
               double pg, double f0, double f1, double kd, double cos_o, double expected, bool upper,
               std::map<std::string, double> params) {
  MicrofacetIntegral m;
  m.kind = kind;
  m.d = d, m.g = g, m.f = f;
  m.pd = pd, m.pg = pg, m.f0 = f0, m.f1 = f1, m.kd = kd;
  m.width = alpha, m.cos_o = cos_o;
  plan.specs.push_back(spec_of(m));
  PointResult p;
  p.check = plan.check;
  p.d = d;
  p.g = g;
  p.f = f;
  p.params = std::move(params);
  p.expected = expected;
  p.upper_only = upper;
  p.take(expect(plan.check, d, g, alpha, f0, kd));
  plan.points.push_back(p);
}

// ---- whole models (catalog/models.hpp) ------------------------------------

std::map<std::string, double> case_params(const Model& m, const ModelCase& c) {
  std::map<std::string, double> out;
  for (size_t i = 0; i < m.params.size(); ++i) out[m.params[i].name] = c.p[i];
  return out;
}

// Whole models' albedo kinds (the source kSourceModels): an Energy kind,
// E(l) = ∫ f(l, v)(n·v) dv <= 1 at every light direction, with the catalog's
// expectation per case; an Exact kind, E(l) equals the model's exact albedo
// wherever it has one (evidence that model and estimator are right).
bool add_model_plans(const CheckKind& k, const SuiteOptions& opt, std::vector<Plan>& plans) {
  const Shape shape = shape_of(k);
  if (shape != Shape::Energy && shape != Shape::Exact) return false;
  const bool exact = shape == Shape::Exact;
  Plan p = new_plan(k.check, kSuiteBaseSamples, opt.scale);
  p.samples *= exact ? kClosedFormFactor : kModelEnergyFactor;  // scaled first, as the records were taken
  for (auto& m : models()) {
    bool used = false;
    for (auto& c : m.cases) {
      const std::string name = model_case_name(m, c);
      if (!suite_model_wanted(opt.models, name)) continue;
      for (double co : view_cosines(kModelLights * opt.density)) {
        const double closed = m.ref_albedo ? m.ref_albedo(co, c.p.data()) : std::nan("");
        if (exact && std::isnan(closed)) continue;
        p.specs.push_back(model_spec(k.kind, m, c.p, co));  // energy: AlbedoMis; closed_form: Albedo
        PointResult r;
        r.check = k.check;
        r.model = name;
        r.params = case_params(m, c);
        r.params["cos_l"] = co;
        r.expected = exact ? closed : 1.0;
        r.upper_only = !exact;
        r.expect = exact ? Expect::Hold : c.energy;
        r.reason = exact ? "" : c.energy_why;
        p.points.push_back(r);
        used = true;
      }
    }
    if (used) p.terms.models.push_back(&m);
  }
  plans.push_back(p);
  return true;
}

// The widths of a row: the D's own d_norm grid (n_alpha = 0: native
// values in its range), else n_alpha of kAlphas, evenly thinned.
std::vector<double> row_alphas(const CheckRow& row, int density) {
  const std::vector<double> all = densify(kAlphas, density);
  const size_t n = std::min(all.size(), size_t(row.n_alpha * density));
  std::vector<double> out;
  for (size_t ai = 0; ai < n; ++ai) out.push_back(all[ai * all.size() / n]);
  return out;
}

std::vector<const Term*> row_fs(const CheckRow& row) {
  if (row.fs == FSet::Schlick) return {try_find_term("schlick", Kind::F)};
  std::vector<const Term*> out;
  for (auto* f : terms_of(Kind::F))
    if ((f->id == "none") == (row.fs == FSet::None)) out.push_back(f);
  return out;
}

// A DNorm kind: every D at the values of its grid within its range.
Plan d_norm_plan(const CheckKind& row, const SuiteOptions& opt) {
  Plan p = new_plan(row.check, row.base_samples, opt.scale);
  for (auto* d : terms_of(Kind::D)) {
    if (!suite_model_wanted(opt.models, d->id)) continue;
    p.terms.d.push_back(d);
    const Param& par = d->params[0];
    for (double v : densify(d->roughness == Roughness::PhongExponent ? kNormPhong : kNormAlphas, opt.density)) {
      if (v < par.lo || v > par.hi) continue;
      add_point(p, row.kind, d, nullptr, nullptr, alpha_from_native(d->roughness, v), v, 0, 0, 0, 0, 1, 1.0, false,
                {{par.name, v}});
    }
  }
  return p;
}

// One row over D x G x F: widths x F points x kds x views per combination.
Plan dgf_plan(const CheckRow& row, const SuiteOptions& opt) {
  Plan p = new_plan(row.check, row.base_samples, opt.scale);
  const bool masking = row.kind == IntegralKind::Masking;
  const std::vector<double> views = view_cosines(row.n_view * opt.density);
  const std::vector<const Term*> fs = row_fs(row);
  p.terms.d = terms_of(Kind::D);
  p.terms.g = terms_of(Kind::G);
  p.terms.f = masking ? std::vector<const Term*>{} : fs;
  for (auto* d : p.terms.d)
    for (auto* g : p.terms.g)
      for (auto* f : fs) {
        if (!suite_model_wanted(opt.models, d->id + "/" + g->id + (masking ? "" : "/" + f->id))) continue;
        for (double alpha : row_alphas(row, opt.density)) {
          const NativeWidths w = native_widths(*d, *g, alpha);
          for (auto& fp : masking ? std::vector<ParamPoint>{{0, 0, ""}} : densify_points(*f, opt.density))
            for (double kd : row.kds)
              for (double co : views) {
                std::map<std::string, double> params{{"alpha", alpha}, {"cos_o", co}};
                if (!fp.label.empty()) {
                  params[f->params[0].name] = fp.p0;
                  if (f->params.size() > 1) params[f->params[1].name] = fp.p1;
                }
                if (kd > 0) params["kd"] = kd;
                add_point(p, row.kind, d, g, masking ? nullptr : f, alpha, w.pd, w.pg, fp.p0, fp.p1, kd, co, 1.0,
                          row.upper_only, params);
              }
        }
      }
  return p;
}

// Reciprocity batches (Shape::Pairs) of every D x G x F (the kernel dispatches on ids).
Plan grid_reciprocity(const CheckKind& k, const SuiteOptions& opt) {
  Plan plan;
  plan.check = k.check;
  plan.terms.d = terms_of(Kind::D);
  plan.terms.g = terms_of(Kind::G);
  plan.terms.f = terms_of(Kind::F);
  std::vector<IntegralSpec>& specs = plan.specs;
  std::vector<PointResult>& pts = plan.points;
  const double alpha = 0.3;
  for (auto* d : terms_of(Kind::D))
    for (auto* g : terms_of(Kind::G))
      for (auto* f : terms_of(Kind::F)) {
        std::string m = d->id + "/" + g->id + "/" + f->id;
        if (!suite_model_wanted(opt.models, m)) continue;
        for (auto& fp : f->check_points) {
          IntegralSpec s;
          s.d = term_index(*d);
          s.g = term_index(*g);
          s.f = term_index(*f);
          s.pd = float(native_from_alpha(d->roughness, alpha));
          s.pg = g->params.empty() ? 0.f : float(native_from_alpha(g->roughness, alpha));
          s.f0 = float(fp.p0);
          s.f1 = float(fp.p1);
          s.kd = 0.2f;
          specs.push_back(s);
          PointResult p;
          p.check = k.check;
          p.d = d;
          p.g = g;
          p.f = f;
          p.params = {{"alpha", alpha}, {"kd", 0.2}};
          if (!fp.label.empty()) p.params[f->params[0].name] = fp.p0;
          pts.push_back(p);
        }
      }
  return plan;
}

// Reciprocity batches of the whole models with a case.
Plan model_reciprocity(const CheckKind& k, const SuiteOptions& opt) {
  Plan plan;
  plan.check = k.check;
  std::vector<IntegralSpec>& specs = plan.specs;
  std::vector<PointResult>& pts = plan.points;
  for (auto& m : models()) {
    bool used = false;
    for (auto& c : m.cases) {
      const std::string name = model_case_name(m, c);
      if (!suite_model_wanted(opt.models, name)) continue;
      specs.push_back(model_spec(IntegralKind::DNorm, m, c.p, 1.0));  // the reciprocity kernel ignores the kind
      PointResult p;
      p.check = k.check;
      p.model = name;
      p.params = case_params(m, c);
      p.expect = c.reciprocity;
      p.reason = c.reciprocity_why;
      pts.push_back(p);
      used = true;
    }
    if (used) plan.terms.models.push_back(&m);
  }
  plan.terms.reciprocity_per_model =
      model_reciprocity_per_model_pays(uint64_t(specs.size()) * reciprocity_pairs(opt.scale), plan.terms.models.size());
  return plan;
}

}  // namespace

Plan new_plan(const std::string& check, uint64_t base_samples, double scale) {
  Plan p;
  p.check = check;
  p.samples = scaled_samples(base_samples, scale);
  return p;
}

std::vector<Plan> cross_sources(const std::vector<PointSource>& sources,
                                const std::function<bool(const CheckKind&)>& wanted) {
  std::vector<Plan> plans;
  for (const CheckKind& k : check_kinds()) {
    if (!wanted(k)) continue;
    for (const PointSource& src : sources)
      if ((k.sources & src.source) && !src.add(k, plans))
        throw Error(
            fmt::format("internal: the registry says {} takes check kind '{}', but it builds no points of its shape "
                        "(checks/registry.cpp: sources, not_taken)",
                        src.name, k.check));
  }
  return plans;
}

std::vector<PointSource> suite_sources(const SuiteOptions& opt) {
  PointSource grid{kSourceGrid, "the D x G x F grid", [&opt](const CheckKind& k, std::vector<Plan>& plans) {
                     switch (shape_of(k)) {
                       case Shape::DNorm: plans.push_back(d_norm_plan(k, opt)); return true;
                       case Shape::Masking:
                       case Shape::Furnace:
                       case Shape::Energy: plans.push_back(dgf_plan(k, opt)); return true;
                       case Shape::Pairs: plans.push_back(grid_reciprocity(k, opt)); return true;
                       default: return false;
                     }
                   }};
  PointSource whole{kSourceModels, "whole models", [&opt](const CheckKind& k, std::vector<Plan>& plans) {
                      if (shape_of(k) != Shape::Pairs) return add_model_plans(k, opt, plans);
                      plans.push_back(model_reciprocity(k, opt));
                      return true;
                    }};
  // anisotropic D and G: two widths (suite_aniso.cpp); the sheen D and its visibility (suite_sheen.cpp);
  // the rough dielectric BSDFs (suite_bsdf.cpp)
  return {grid, whole, aniso_source(opt), sheen_source(opt), bsdf_source(opt)};
}

std::vector<Plan> make_plans(const SuiteOptions& opt) {
  return cross_sources(suite_sources(opt), [&opt](const CheckKind& k) {
    return k.runner == Runner::Integral && k.in_run && suite_check_wanted(opt, k.check);
  });
}

uint64_t scaled_samples(uint64_t n, double scale) {
  const double x = double(n) * scale;
  if (!(x < 0x1p64))  // also NaN
    throw Error(fmt::format("--samples/--scale ask for {:.3g} samples per integral: too many", x));
  return std::max<uint64_t>(64, uint64_t(x));
}

void validate_scale(double scale) {
  if (!(scale > 0) || !std::isfinite(scale)) throw Error("--scale must be a positive number");
  if (scale > 0x1p26)
    throw Error(
        fmt::format("--scale {:g} (or --samples {:.0f}) is too large: at most 2^26 = 67108864 (--samples "
                    "2^38)",
                    scale, scale * double(kSuiteBaseSamples)));
}

Plan reciprocity_plan(const CheckKind& k, const SuiteOptions& opt) {
  // one plan of the sources' batches (one bounded point each), the grid's first
  Plan plan;
  plan.check = k.check;
  for (Plan& p : cross_sources(suite_sources(opt), [&k](const CheckKind& c) { return &c == &k; })) {
    plan.specs.insert(plan.specs.end(), p.specs.begin(), p.specs.end());
    plan.points.insert(plan.points.end(), p.points.begin(), p.points.end());
    plan.terms.add(p.terms);
  }
  return plan;
}

}  // namespace mfv
