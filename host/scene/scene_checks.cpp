#include "scene/scene_checks.hpp"

#include "catalog/models.hpp"
#include "checks/furnace_truth.hpp"
#include "checks/suite_bsdf.hpp"
#include "catalog/roughness.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>

namespace mfv {
namespace {

const Term& term(const char* id, Kind k) { return *try_find_term(id, k); }

// One check's plan with the distinct sets already in it (by key).
struct SetPlan {
  Plan plan;
  std::map<std::string, bool> keys;  // set keys present
  std::set<std::string> models;      // D/G/F names or "gltf"
  void add_terms(const Term* d, const Term* g, const Term* f) {
    auto add = [](std::vector<const Term*>& v, const Term* t) {
      if (t && std::find(v.begin(), v.end(), t) == v.end()) v.push_back(t);
    };
    add(plan.terms.d, d);
    add(plan.terms.g, g);
    add(plan.terms.f, f);
  }
  void add_model(const Model& m) {
    if (std::find(plan.terms.models.begin(), plan.terms.models.end(), &m) == plan.terms.models.end())
      plan.terms.models.push_back(&m);
  }
};

std::string dgf(const Term* d, const Term* g, const Term* f) {
  return d->id + (g ? "/" + g->id : "") + (f ? "/" + f->id : "");
}

// A microfacet integral of kind `kind` over D x G x F at the native
// parameters (pd, pg), the proposal width alpha and the view cos_o; the
// caller names the rest (F's parameters, kd).
MicrofacetIntegral dgf_integral(IntegralKind kind, const Term* d, const Term* g, const Term* f, double pd, double pg,
                                double alpha, double cos_o) {
  MicrofacetIntegral mi;
  mi.kind = kind;
  mi.d = d, mi.g = g, mi.f = f;
  mi.pd = pd, mi.pg = pg;
  mi.width = alpha, mi.cos_o = cos_o;
  return mi;
}

// The material's own D x G x F BRDF (F's parameters, kd) at the view cos_o,
// integrated by `kind` (a kind's own estimator; reciprocity reads the BRDF only).
IntegralSpec material_spec(IntegralKind kind, const SceneMaterial& m, double cos_o) {
  MicrofacetIntegral mi = dgf_integral(kind, m.d, m.g, m.f, m.pd, m.pg, m.alpha, cos_o);
  mi.f0 = m.f0, mi.f1 = m.f1, mi.kd = m.kd;
  return spec_of(mi);
}

// One point of a set: a spec and its expectation.
void add(SetPlan& sp, const std::string& key, const IntegralSpec& s, const Term* d, const Term* g, const Term* f,
         std::map<std::string, double> params, const Expectation& e, bool upper) {
  sp.plan.specs.push_back(s);
  PointResult p;
  p.check = sp.plan.check;
  p.d = d;
  p.g = g;
  p.f = f;
  p.model = key;
  p.params = std::move(params);
  p.expected = check_kind(sp.plan.check).expected;
  p.upper_only = upper;
  p.take(e);
  sp.plan.points.push_back(p);
}

// The catalog's glTF model at one channel's parameters.
IntegralSpec gltf_spec(IntegralKind kind, const GltfChannelParams& c, double cos_l) {
  return model_spec(kind, gltf_model(), c.params(), cos_l);
}

std::map<std::string, double> whole_params(const WholePoint& w) {
  std::map<std::string, double> out;
  for (size_t i = 0; i < w.model->params.size(); ++i) out[w.model->params[i].name] = w.p[i];
  return out;
}

struct SceneSets {
  std::map<std::string, SetPlan> plans;              // by check
  std::vector<std::set<std::string>> material_keys;  // per material: "check|key"
};

SetPlan& plan_for(SceneSets& s, const CheckKind& k, uint64_t base_samples, const SuiteOptions& opt) {
  auto it = s.plans.find(k.check);
  if (it == s.plans.end()) {
    SetPlan sp;
    sp.plan = new_plan(k.check, base_samples, opt.scale);
    if (k.runner == Runner::Pairs) sp.plan.samples = 0;  // pairs, not samples (record_reciprocity)
    it = s.plans.emplace(k.check, sp).first;
  }
  return it->second;
}

// One material's share of the scene's sets (make_sets): the D and G it is
// checked with (glTF: GGX with the height-correlated Smith G), their
// parameters, the views, and the keys it claims.
struct MaterialSets {
  SceneSets& s;
  const SceneMaterial& m;
  const SuiteOptions& opt;
  std::set<std::string>& mine;
  const std::vector<double>& views;
  const Term *d, *g, *ggx, *smith, *none;
  double pd, pg;
  // Registers `key` under the plan's check for this material; true when the set is new.
  bool claim(SetPlan& sp, const std::string& key, const std::string& model) {
    mine.insert(sp.plan.check + "|" + key);
    sp.models.insert(model);
    return sp.keys.emplace(key, true).second;
  }
  // The material's points of kind k, by its shape; false for a shape it has none of.
  bool add_kind(const CheckKind& k);
  // The widths the material's D and G are checked at, (pD, pG) with alpha =
  // pD for glTF: every roughness point of a glTF range.
  std::vector<std::pair<double, double>> widths() const;
  void add_d_norm(const CheckKind& k);       // D at every width the material has
  void add_masking(const CheckKind& k);      // D and G1 at every width the material has
  void add_furnace(const CheckKind& k);      // the material's D and G (glTF: its lobes) with F = 1
  void add_energy(const CheckKind& k);       // the material's own BRDF (a diffuse kind: with a Lambert kd)
  void add_reciprocity(const CheckKind& k);  // reciprocity of the material's own BRDF
  void add_thin_identity(const CheckKind& k);  // KHR_materials_transmission thin-walled: R + T = the F = 1 albedo
  void add_volume(const CheckKind& k);         // KHR_materials_volume: the Walter BSDF at eta = ior
};

bool MaterialSets::add_kind(const CheckKind& k) {
  switch (shape_of(k)) {
    case Shape::DNorm: add_d_norm(k); return true;
    case Shape::Masking: add_masking(k); return true;
    case Shape::Furnace: add_furnace(k); return true;
    case Shape::Energy: add_energy(k); return true;
    case Shape::Pairs: add_reciprocity(k); return true;
    case Shape::Exact: add_thin_identity(k); return true;
    case Shape::BsdfFlux:
    case Shape::MaskingT:
    case Shape::BsdfAvg: add_volume(k); return true;
    default: return false;
  }
}

std::vector<std::pair<double, double>> MaterialSets::widths() const {
  std::vector<std::pair<double, double>> out;
  if (m.gltf) {
    for (double a : m.alphas()) out.push_back({a, a});
    for (double a : m.coat_alphas()) out.push_back({a, a});  // KHR_materials_clearcoat: the coat's GGX
  } else
    out.push_back({pd, pg});
  return out;
}

void MaterialSets::add_d_norm(const CheckKind& k) {
  for (auto [wd, wg] : widths()) {
    const double a = m.gltf ? wd : m.alpha;
    SetPlan& sp = plan_for(s, k, k.base_samples, opt);
    std::string key = fmt::format("{} {}={:.9g}", d->id, d->params[0].name, wd);
    if (claim(sp, key, d->id)) {
      IntegralSpec is = spec_of(dgf_integral(k.kind, d, nullptr, nullptr, wd, 0, a, 1.0));
      add(sp, key, is, d, nullptr, nullptr, {{d->params[0].name, wd}}, expect(k.check, d, nullptr, a, 0, 0), false);
      sp.add_terms(d, nullptr, nullptr);
    }
  }
}

void MaterialSets::add_masking(const CheckKind& k) {
  for (auto [wd, wg] : widths()) {
    const double a = m.gltf ? wd : m.alpha;
    SetPlan& sp = plan_for(s, k, k.base_samples, opt);
    std::string key = fmt::format("{}/{} alpha={:.9g} pD={:.9g} pG={:.9g}", d->id, g->id, a, wd, wg);
    if (claim(sp, key, dgf(d, g, nullptr))) {
      for (double co : views) {
        IntegralSpec is = spec_of(dgf_integral(k.kind, d, g, nullptr, wd, wg, a, co));
        add(sp, key, is, d, g, nullptr, {{"alpha", a}, {"cos_o", co}}, expect(k.check, d, g, a, 0, 0), false);
      }
      sp.add_terms(d, g, nullptr);
    }
  }
}

// F = 1: for glTF the model itself as a white metal (base colour 1 makes
// conductor_fresnel 1), so the energy loss 1 - E is the material's specular
// lobe at its roughness; integrated by the kind's own estimator (AlbedoMis:
// kernels/albedo.cl albedo_mis_general for the glTF lobes).
void MaterialSets::add_furnace(const CheckKind& k) {
  {
    SetPlan& sp = plan_for(s, k, k.base_samples, opt);
    if (m.gltf) {
      // every specular lobe of the material's range (alpha_t, alpha_b under KHR_materials_anisotropy)
      for (const GltfChannelParams& white : m.white_lobes()) {
        const double at = white.alpha, ab = white.alpha_b;
        std::string key = fmt::format("gltf alpha={:.9g} alpha_b={:.9g} (white metal: F = 1)", at, ab);
        if (!claim(sp, key, "gltf")) continue;
        for (double co : views)
          add(sp, key, gltf_spec(k.kind, white, co), nullptr, nullptr, nullptr,
              {{"alpha", at}, {"alpha_b", ab}, {"cos_l", co}}, {}, k.upper_only);
        sp.add_model(gltf_model());
      }
    } else {
      std::string key = fmt::format("{} pD={:.9g} pG={:.9g}", dgf(d, g, none), pd, pg);
      if (claim(sp, key, dgf(d, g, none))) {
        for (double co : views) {
          IntegralSpec is = spec_of(dgf_integral(k.kind, d, g, none, pd, pg, m.alpha, co));
          add(sp, key, is, d, g, none, {{"alpha", m.alpha}, {"cos_o", co}}, expect(k.check, d, g, m.alpha, 1, 0),
              k.upper_only);
        }
        sp.add_terms(d, g, none);
      }
    }
  }
}

// The material's own BRDF: a D/G/F with a Lambert kd in the diffuse kind
// (diffuse_of: energy_diffuse), every other material in the other.
void MaterialSets::add_energy(const CheckKind& k) {
  if (diffuse_of(k) == (!m.gltf && m.kd > 0)) {
    SetPlan& sp = plan_for(s, k, k.base_samples, opt);
    if (m.gltf) {
      for (auto& w : m.whole_points()) {
        std::string key = w.key();
        if (!claim(sp, key, w.model->id)) continue;
        for (double co : views) {
          std::map<std::string, double> ps = whole_params(w);
          ps["cos_l"] = co;
          add(sp, key, model_spec(k.kind, *w.model, w.p, co), nullptr, nullptr, nullptr, ps,
              {w.energy, w.energy_why, 0}, true);
        }
        sp.add_model(*w.model);
      }
      // KHR_materials_ior: the specular lobe also with the exact dielectric
      // Fresnel at eta = ior (Walter et al. 2007 eq. 22), not Schlick's
      // approximation from f0, at every roughness point
      if (m.ior_exact) {
        const Term* exact = &term("dielectric", Kind::F);
        for (double a : m.alphas()) {
          std::string key =
              fmt::format("{} pD={:.9g} pG={:.9g} eta={:.9g}", dgf(ggx, smith, exact), a, a, m.factors.ior);
          if (!claim(sp, key, dgf(ggx, smith, exact))) continue;
          for (double co : views) {
            MicrofacetIntegral mi = dgf_integral(k.kind, ggx, smith, exact, a, a, a, co);
            mi.f0 = m.factors.ior;  // eta
            IntegralSpec is = spec_of(mi);
            add(sp, key, is, ggx, smith, exact, {{"alpha", a}, {"cos_o", co}, {"eta", m.factors.ior}},
                expect(sp.plan.check, ggx, smith, a, m.factors.ior, 0), true);
          }
          sp.add_terms(ggx, smith, exact);
        }
      }
    } else if (m.f != none || m.kd > 0) {
      const bool diffuse = m.kd > 0;
      SetPlan& dp = sp;
      std::string key =
          fmt::format("{} pD={:.9g} pG={:.9g} p0={:.9g} p1={:.9g} kd={:.9g}", m.model(), pd, pg, m.f0, m.f1, m.kd);
      if (claim(dp, key, m.model())) {
        for (double co : views) {
          IntegralSpec is = material_spec(k.kind, m, co);
          std::map<std::string, double> ps{{"alpha", m.alpha}, {"cos_o", co}};
          for (size_t i = 0; i < m.f->params.size(); ++i) ps[m.f->params[i].name] = i ? m.f1 : m.f0;
          if (diffuse) ps["kd"] = m.kd;
          add(dp, key, is, d, g, m.f, ps, expect(dp.plan.check, d, g, m.alpha, m.f0, m.kd), true);
        }
        dp.add_terms(d, g, m.f);
      }
    }
  }
}

// reciprocity of the material's own BRDF.
void MaterialSets::add_reciprocity(const CheckKind& k) {
  {
    SetPlan& sp = plan_for(s, k, 0, opt);
    if (m.gltf) {
      for (auto& w : m.whole_points()) {
        std::string key = w.key();
        if (!claim(sp, key, w.model->id)) continue;
        add(sp, key, model_spec(IntegralKind::Albedo, *w.model, w.p, 1.0), nullptr, nullptr, nullptr, whole_params(w),
            {w.reciprocity, w.reciprocity_why, 0}, false);
        sp.add_model(*w.model);
      }
    } else {
      std::string key =
          fmt::format("{} pD={:.9g} pG={:.9g} p0={:.9g} p1={:.9g} kd={:.9g}", m.model(), pd, pg, m.f0, m.f1, m.kd);
      if (claim(sp, key, m.model())) {
        IntegralSpec is = material_spec(IntegralKind::Albedo, m, 1.0);
        add(sp, key, is, d, g, m.f, {{"alpha", m.alpha}, {"kd", m.kd}}, {}, false);
        sp.add_terms(d, g, m.f);
      }
    }
  }
}

// KHR_materials_transmission, thin-walled (issue 29): with a white base, full
// transmission and no metal the transmission lobe takes 1 - F of the light
// the reflection lobe takes F of, at the same mirrored half vector, so R + T
// is the F = 1 albedo of the same D and Vis at every ior. Expected: that
// albedo (ggx/smith_ggx_correlated/none) by quadrature of the double
// reference, its rule's error added to the point's tolerance (two-sided).
void MaterialSets::add_thin_identity(const CheckKind& k) {
  const Term* white = &term("none", Kind::F);
  for (const ModelParams& p : m.thin_identity_points()) {
    SetPlan& sp = plan_for(s, k, k.base_samples, opt);
    const std::string key = fmt::format("gltf_transmission alpha={:.9g} f0={:.9g} (R + T = the F = 1 albedo)", p[0], p[3]);
    if (!claim(sp, key, "gltf_transmission")) continue;
    for (double co : view_cosines(k.n_view)) {
      const IntegralSpec is = model_spec(k.kind, gltf_transmission_model(), p, co);
      const KnownValue truth = cached_albedo_by_quadrature(
          spec_of(dgf_integral(IntegralKind::Albedo, ggx, smith, white, p[0], p[0], p[0], double(is.cos_o))));
      add(sp, key, is, nullptr, nullptr, nullptr, {{"alpha", p[0]}, {"f0", p[3]}, {"cos_l", co}}, {}, false);
      sp.plan.points.back().expected = truth.value;
      sp.plan.points.back().tolerance += truth.error / truth.value;
    }
    sp.add_model(gltf_transmission_model());
  }
}

// KHR_materials_volume with thickness > 0: a refracting boundary, the
// catalog's rough dielectric BSDF (height-correlated GGX, exact Fresnel) at
// eta = ior and alpha = roughness², built and judged as the catalog's points.
void MaterialSets::add_volume(const CheckKind& k) {
  if (!m.volume_checked) return;
  const Bsdf& b = *try_find_bsdf("walter_ggx_correlated");
  SetPlan& sp = plan_for(s, k, k.base_samples, opt);
  const std::string key = fmt::format("{} eta={:.9g}", b.id, m.factors.ior);
  std::vector<double> widths;
  for (double a : m.alphas())
    if (claim(sp, fmt::format("{} alpha={:.9g}", key, a), b.id)) widths.push_back(a);
  if (widths.empty()) return;
  Plan p = bsdf_points(k, opt, b, widths, {m.factors.ior});
  const size_t offset = sp.plan.specs.size();
  for (size_t i = 0; i < p.specs.size(); ++i) {
    PointResult r = p.points[i];
    r.model = fmt::format("{} alpha={:.9g}", key, r.params.at("alpha"));  // the material's group
    sp.plan.specs.push_back(p.specs[i]);
    sp.plan.points.push_back(r);
  }
  if (p.reference_pick) {
    if (!sp.plan.reference_pick) sp.plan.reference_pick = std::vector<size_t>{};
    for (size_t i : *p.reference_pick) sp.plan.reference_pick->push_back(offset + i);
  }
  sp.add_terms(b.d, b.g, nullptr);
}

SceneSets make_sets(const Scene& scene, const SuiteOptions& opt) {
  SceneSets s;
  const std::vector<double> views = view_cosines(32);
  const Term* ggx = &term("ggx", Kind::D);
  const Term* smith = &term("smith_ggx_correlated", Kind::G);
  const Term* none = &term("none", Kind::F);
  s.material_keys.resize(scene.materials.size());
  // the scene's materials as a point source crossed with the registry (the plans are s's, by check)
  PointSource source{kSourceScene, "a scene's materials", [&](const CheckKind& k, std::vector<Plan>&) {
                       for (size_t mi = 0; mi < scene.materials.size(); ++mi) {
                         const SceneMaterial& m = scene.materials[mi];
                         if (!m.not_checked.empty())
                           continue;  // accounted for in the report (skipped), never checked as something else
                         MaterialSets c{s,
                                        m,
                                        opt,
                                        s.material_keys[mi],
                                        views,
                                        m.gltf ? ggx : m.d,
                                        m.gltf ? smith : m.g,
                                        ggx,
                                        smith,
                                        none,
                                        m.gltf ? m.alpha : m.pd,
                                        m.gltf ? m.alpha : m.pg};
                         if (!c.add_kind(k)) return false;
                       }
                       return true;
                     }};
  cross_sources({source}, [&opt](const CheckKind& k) {
    return (k.runner == Runner::Integral || k.runner == Runner::Pairs) && k.in_run && suite_check_wanted(opt, k.check);
  });
  return s;
}

// A combination of the full catalog: D/G/F ids, or a whole model's id (without its case).
std::string full_model_name(const PointResult& p) {
  return p.d ? dgf(p.d, p.g, p.f) : p.model.substr(0, p.model.find('['));
}

}  // namespace

SceneRun run_scene(Runtime& rt, const Scene& scene, const SuiteOptions& opt, bool compare_full) {
  validate_suite_options(opt);
  if (!opt.models.empty()) throw Error("--model and --scene cannot be combined: the scene chooses the models");
  const auto t0 = std::chrono::steady_clock::now();
  SceneRun run;
  run.scene = scene;
  SceneSets sets = make_sets(scene, opt);
  const int builds0 = rt.build_stats().builds;
  std::map<std::string, size_t> stat_of;  // check -> index in rep.stats
  for (const std::string& check : suite_checks()) {
    auto it = sets.plans.find(check);
    if (it == sets.plans.end() || it->second.plan.specs.empty()) continue;
    Plan& plan = it->second.plan;
    if (check_kind(check).runner == Runner::Pairs)
      run_reciprocity(rt, plan, opt, run.rep);
    else
      run_plan(rt, plan, opt, run.rep);
    stat_of[check] = run.rep.stats.size() - 1;
  }
  const bool any_checked =
      std::any_of(scene.materials.begin(), scene.materials.end(), [](auto& m) { return m.not_checked.empty(); });
  // a scene whose every material is accounted for as not checked still reports them (skipped)
  if (run.rep.points.empty() && any_checked) throw Error("the scene's materials need none of the chosen checks");
  judge(run.rep, opt);
  // the checks' own programs; the reference comparison's double twins apart
  run.scene_builds = rt.build_stats().builds - builds0 - run.rep.reference_builds;
  // groups of each material, in check order
  for (size_t mi = 0; mi < scene.materials.size(); ++mi) {
    std::vector<size_t> gs;
    for (size_t gi = 0; gi < run.rep.groups.size(); ++gi)
      if (sets.material_keys[mi].count(run.rep.groups[gi].check + "|" + run.rep.groups[gi].model)) gs.push_back(gi);
    run.material_groups.push_back(gs);
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // What the full catalog would have run with the same options.
  SuiteOptions full = opt;
  full.models.clear();
  SuitePlans full_suite = make_suite_plans(full);
  std::vector<Plan>& full_plans = full_suite.plans;
  if (!full_suite.reciprocity.specs.empty()) full_plans.push_back(full_suite.reciprocity);
  SuiteReport full_rep;
  if (compare_full) {
    const auto f0 = std::chrono::steady_clock::now();
    full_rep = run_suite(rt, full);
    run.full_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - f0).count();
    run.full_measured = true;
  }
  // One row per check: the full run has two energy plans (D x G x F, whole models).
  run.full_builds = 0;
  std::map<std::string, std::set<std::string>> full_models;
  for (auto& fp : full_plans) {
    if (fp.specs.empty()) continue;
    ++run.full_builds;
    auto row = std::find_if(run.left_out.begin(), run.left_out.end(), [&](auto& l) { return l.check == fp.check; });
    if (row == run.left_out.end()) {
      LeftOut lo;
      lo.check = fp.check;
      for (auto& st : full_rep.stats)
        if (st.check == fp.check) lo.full_samples += st.samples, lo.full_seconds += st.seconds;
      if (auto s = stat_of.find(fp.check); s != stat_of.end()) {
        const CheckStats& st = run.rep.stats[s->second];
        lo.scene_integrals = st.integrals;
        lo.scene_samples = st.samples;
        lo.scene_seconds = st.seconds;
        lo.scene_combinations = sets.plans[fp.check].models.size();
      }
      run.left_out.push_back(lo);
      row = run.left_out.end() - 1;
    }
    for (auto& p : fp.points) full_models[fp.check].insert(full_model_name(p));
    row->full_combinations = full_models[fp.check].size();
    row->full_integrals += fp.specs.size();
    // reciprocity: per batch 64 work-items x 64 x scale pairs, two evaluations each (suite.cpp)
    const uint64_t per = check_kind(fp.check).runner == Runner::Pairs
                             ? uint64_t(64) * std::max<uint32_t>(1, uint32_t(64 * opt.scale)) * 2
                             : fp.samples;
    if (!compare_full) row->full_samples += fp.specs.size() * per;  // requested; a run rounds up to whole work-groups
  }
  return run;
}

}  // namespace mfv
