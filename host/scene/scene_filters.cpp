#include "scene/scene_filters.hpp"

#include "catalog/bsdfs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace mfv {
namespace {

void add_unique(std::vector<std::string>& v, const std::string& s) {
  if (std::find(v.begin(), v.end(), s) == v.end()) v.push_back(s);
}

// The D, G and F a material evaluates: the glTF model is GGX D, the
// height-correlated Smith G and Schlick F (glTF 2.0 Appendix B).
void terms_of_material(const SceneMaterial& m, const Term*& d, const Term*& g, const Term*& f) {
  d = m.gltf ? try_find_term("ggx", Kind::D) : m.d;
  g = m.gltf ? try_find_term("smith_ggx_correlated", Kind::G) : m.g;
  f = m.gltf ? try_find_term("schlick", Kind::F) : m.f;
}

}  // namespace

namespace {

// The energy points of a glTF material: its distinct parameter points, then
// each of its lobes as a white metal (F = 1: the specular lobe's own loss), with
// both widths under KHR_materials_anisotropy.
std::vector<ModelPoint> gltf_points(const SceneMaterial& m) {
  std::vector<ModelPoint> out;
  if (!m.not_checked.empty()) return out;
  const auto points = m.whole_points();
  for (size_t k = 0; k < points.size(); ++k)
    out.push_back({points[k].model,
                   fmt::format("{} ({} point {} of {})", m.name, points[k].model->id, k + 1, points.size()),
                   points[k].p, points[k].energy, points[k].energy_why});
  for (const GltfChannelParams& white : m.white_lobes()) {
    const double at = white.alpha, ab = white.alpha_b;
    out.push_back({&gltf_model(),
                   ab > 0 ? fmt::format("{} (F = 1 at alpha_t {:g}, alpha_b {:g})", m.name, at, ab)
                          : fmt::format("{} (F = 1 at alpha {:g})", m.name, at),
                   white.params(), Expect::Hold, ""});
  }
  return out;
}

const ModelEnergy* find_point(const EnergyReport& rep, const ModelPoint& p) {
  for (auto& me : rep.models)
    if (me.point.model == p.model && me.point.p == p.p) return &me;
  return nullptr;
}

}  // namespace

void scene_energy_options(const Scene& scene, EnergyOptions& opt) {
  opt.models.clear();
  opt.catalog_models = false;
  opt.model_points.clear();
  for (auto& m : scene.materials) {
    if (m.gltf) {
      for (auto& p : gltf_points(m))
        if (std::none_of(opt.model_points.begin(), opt.model_points.end(),
                         [&](auto& q) { return q.model == p.model && q.p == p.p; }))
          opt.model_points.push_back(p);  // distinct parameter sets only
      continue;
    }
    add_unique(opt.models, m.d->id + "/" + m.g->id);
  }
  opt.tables = !opt.models.empty();
}

void print_scene_energy(const Scene& scene, const EnergyReport& rep) {
  const size_t full = terms_of(Kind::D).size() * terms_of(Kind::G).size();
  size_t cases = 0;
  for (auto& m : models()) cases += m.cases.size();
  fmt::print(
      "\nscene {}: {} of {} D x G tables and {} glTF parameter sets computed (the catalog's {} whole-model "
      "cases left out)\n",
      scene.path, rep.tables.size(), full, rep.models.size(), cases);
  for (auto& m : scene.materials) {
    if (m.gltf) {
      for (auto& p : gltf_points(m)) {
        const ModelEnergy* me = find_point(rep, p);
        if (!me) continue;
        const GltfChannelParams c{
            p.p[0], p.p[1], p.p[2], p.p[3], p.p[4], p.p[5], p.model == &gltf_model() ? p.p[6] : 0.0};
        fmt::print(
            "  material {}: alpha {:g}{}: E_avg {:.4f} ± {:.1e}, energy loss 1 - E_avg {:.4f}; max E {:.4f} ± "
            "{:.1e} at cos_l {:.3g}{}\n",
            p.name, c.alpha, c.alpha_b > 0 ? fmt::format(", alpha_b {:g}", c.alpha_b) : "", me->eavg.mean, me->eavg.se,
            me->loss(), me->E[me->max_at].mean, me->E[me->max_at].se, rep.mu[me->max_at],
            me->gains        ? (p.expect == Expect::Hold ? " (GAINS energy beyond noise: a defect)"
                                                         : " (gains energy beyond noise, as the catalog expects there)")
            : me->unresolved ? " (UNRESOLVED: standard error above target, gain not ruled out)"
                             : "");
      }
      continue;
    }
    const EnergyTable* t = nullptr;
    for (auto& tb : rep.tables)
      if (tb.d == m.d && tb.g == m.g) t = &tb;
    if (!t || rep.alpha.empty()) continue;
    // E_avg at the material's alpha: linear in log alpha between grid points (clamped to the grid).
    const double la = std::log(std::clamp(m.alpha, rep.alpha.front(), rep.alpha.back()));
    size_t k = 0;
    while (k + 2 < rep.alpha.size() && std::log(rep.alpha[k + 1]) < la) ++k;
    double e = t->eavg[k].mean;
    if (rep.alpha.size() > 1) {
      const double l0 = std::log(rep.alpha[k]), l1 = std::log(rep.alpha[k + 1]);
      const double w = std::clamp((la - l0) / (l1 - l0), 0.0, 1.0);
      e = (1 - w) * t->eavg[k].mean + w * t->eavg[k + 1].mean;
    }
    fmt::print("  material '{}': {}/{} at alpha {:g}{}: E_avg {:.4f}, energy loss 1 - E_avg {:.4f}\n", m.name, m.d->id,
               m.g->id, m.alpha,
               m.alpha < rep.alpha.front() || m.alpha > rep.alpha.back() ? " (outside the grid: nearest end)" : "", e,
               1 - e);
  }
}

void scene_stability_options(const Scene& scene, StabilityOptions& opt) {
  opt.only = scene_stability_cases(scene);
  std::map<std::string, std::vector<ModelParams>> points;  // model id -> the scene's distinct points
  for (auto& m : scene.materials)
    for (auto& w : m.whole_points()) {
      auto& v = points[w.model->id];
      if (std::find(v.begin(), v.end(), w.p) == v.end()) v.push_back(w.p);
    }
  opt.model_points.assign(points.begin(), points.end());
  // a refracting boundary (KHR_materials_volume): the Walter BSDF at its
  // roughness² and ior, in the BTDF case's `scene` region (issue 29)
  std::map<std::string, std::vector<std::array<double, 2>>> bsdf_pts;
  for (auto& m : scene.materials)
    if (m.volume_checked && m.not_checked.empty())
      for (double a : m.alphas()) {
        auto& v = bsdf_pts[m.model()];
        const std::array<double, 2> p{a, m.factors.ior};
        if (std::find(v.begin(), v.end(), p) == v.end()) v.push_back(p);
      }
  opt.bsdf_points.assign(bsdf_pts.begin(), bsdf_pts.end());
}

std::vector<std::string> scene_stability_cases(const Scene& scene) {
  std::vector<std::string> out;
  for (auto& m : scene.materials) {
    if (!m.not_checked.empty()) continue;
    const Term *d, *g, *f;
    terms_of_material(m, d, g, f);
    add_unique(out, "D " + d->id);
    add_unique(out, "G " + g->id);
    if (!g->g1_kernel_fn.empty())  // smith_ggx_correlated shares smith_ggx's G1
      add_unique(out, "G1 " + (g->id == "smith_ggx_correlated" ? std::string("smith_ggx") : g->id));
    add_unique(out, "F " + f->id);
    // glTF: the models the material evaluates (gltf, and gltf_clearcoat or
    // gltf_sheen where it has those lobes) besides their terms' product; the
    // sweep takes only models with the scene's points (scene_stability_options)
    if (m.volume_checked)  // a refracting boundary: the Walter BSDF (scene_stability_options gives its points)
      add_unique(out, "BTDF " + m.model());
    if (m.gltf)
      for (auto& w : m.whole_points()) add_unique(out, "MODEL " + w.model->id);
    else
      add_unique(out, "BRDF " + d->id + "/" + g->id + "/" + f->id);
  }
  return out;
}

void print_scene_stability(const Scene& scene, const StabilityReport& rep) {
  size_t g1 = 0;
  for (auto& t : catalog()) g1 += !t.g1_kernel_fn.empty() && t.id != "smith_ggx_correlated";
  const size_t full = catalog().size() + g1 +
                      terms_of(Kind::D).size() * terms_of(Kind::G).size() * terms_of(Kind::F).size() + models().size() +
                      bsdfs().size();
  size_t points = 0;
  for (auto& c : rep.cases)
    for (auto& r : c.regions) points += r.points;
  fmt::print(
      "\nscene {}: {} of {} term, BRDF and whole-model cases swept ({} points; alternative formulations left "
      "out)\n",
      scene.path, rep.cases.size(), full, points);
  bool gltf = std::any_of(scene.materials.begin(), scene.materials.end(), [](auto& m) { return m.gltf; });
  if (gltf) {
    fmt::print(
        "  the glTF model is swept whole (MODEL gltf) at the scene's own parameter points and each parameter's "
        "range ends, and through its terms (GGX D, height-correlated Smith G and G1, Schlick F):\n");
    for (auto& m : scene.materials) {
      if (!m.gltf) continue;
      if (!m.not_checked.empty()) {
        fmt::print("    material '{}': not swept: {}\n", m.name, m.not_checked);
        continue;
      }
      if (m.volume_checked) {  // KHR_materials_volume: a refracting boundary
        std::string pts;
        for (double a : m.alphas()) pts += fmt::format(" (alpha {:.4g}, eta {:.4g})", a, m.factors.ior);
        fmt::print("    material '{}': refracting (KHR_materials_volume): BTDF {} in its region 'scene' at{}, both "
                   "sides, and through its terms\n",
                   m.name, m.model(), pts);
        continue;
      }
      std::string pts;
      for (auto& c : m.channels())
        pts += fmt::format(" (alpha {:.4g}{}, metallic {:g}, base {:.4g})", c.alpha,
                           c.alpha_b > 0 ? fmt::format(", alpha_b {:.4g}", c.alpha_b) : "", c.metallic, c.base);
      fmt::print("    material '{}': {} points:{}\n", m.name, m.channels().size(), pts);
    }
  }
}

}  // namespace mfv
