#include "scene/scene_filters.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

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

// The energy points of a glTF material: its distinct channels, then the white metal.
std::vector<ModelPoint> gltf_points(const SceneMaterial& m) {
  std::vector<ModelPoint> out;
  const auto chans = m.channels();
  for (size_t k = 0; k < chans.size(); ++k)
    out.push_back({&gltf_model(), fmt::format("{} (channel set {} of {})", m.name, k + 1, chans.size()),
                   chans[k].params(), gltf_energy_expect(chans[k]), kGltfFresnelMixGain});
  GltfChannelParams white{m.alpha, 1.0, 1.0, 1.0, 1.0, 1.0};
  out.push_back({&gltf_model(), fmt::format("{} (F = 1: the specular lobe)", m.name), white.params(), Expect::Hold,
                 ""});
  return out;
}

const ModelEnergy* find_point(const EnergyReport& rep, const ModelParams& p) {
  for (auto& me : rep.models)
    if (me.point.model == &gltf_model() && me.point.p == p) return &me;
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
        if (std::none_of(opt.model_points.begin(), opt.model_points.end(), [&](auto& q) { return q.p == p.p; }))
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
  fmt::print("\nscene {}: {} of {} D x G tables and {} glTF parameter sets computed (the catalog's {} whole-model "
             "cases left out)\n",
             scene.path, rep.tables.size(), full, rep.models.size(), cases);
  for (auto& m : scene.materials) {
    if (m.gltf) {
      for (auto& p : gltf_points(m)) {
        const ModelEnergy* me = find_point(rep, p.p);
        if (!me) continue;
        fmt::print("  material {}: alpha {:g}: E_avg {:.4f} ± {:.1e}, energy loss 1 - E_avg {:.4f}; max E {:.4f} at "
                   "cos_l {:.3g}{}\n",
                   p.name, m.alpha, me->eavg.mean, me->eavg.se, me->loss(), me->E[me->max_at].mean,
                   rep.mu[me->max_at], me->gains ? " (gains energy beyond noise)" : "");
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
    fmt::print("  material '{}': {}/{} at alpha {:g}{}: E_avg {:.4f}, energy loss 1 - E_avg {:.4f}\n", m.name,
               m.d->id, m.g->id, m.alpha,
               m.alpha < rep.alpha.front() || m.alpha > rep.alpha.back() ? " (outside the grid: nearest end)" : "", e,
               1 - e);
  }
}

std::vector<std::string> scene_stability_cases(const Scene& scene) {
  std::vector<std::string> out;
  for (auto& m : scene.materials) {
    const Term *d, *g, *f;
    terms_of_material(m, d, g, f);
    add_unique(out, "D " + d->id);
    add_unique(out, "G " + g->id);
    if (!g->g1_kernel_fn.empty())  // smith_ggx_correlated shares smith_ggx's G1
      add_unique(out, "G1 " + (g->id == "smith_ggx_correlated" ? std::string("smith_ggx") : g->id));
    add_unique(out, "F " + f->id);
    // glTF: the model itself (its Fresnel mix and metal/dielectric blend) besides its terms' product
    add_unique(out, m.gltf ? "MODEL gltf" : "BRDF " + d->id + "/" + g->id + "/" + f->id);
  }
  return out;
}

void print_scene_stability(const Scene& scene, const StabilityReport& rep) {
  size_t g1 = 0;
  for (auto& t : catalog()) g1 += !t.g1_kernel_fn.empty() && t.id != "smith_ggx_correlated";
  const size_t full = catalog().size() + g1 +
                      terms_of(Kind::D).size() * terms_of(Kind::G).size() * terms_of(Kind::F).size() + models().size();
  size_t points = 0;
  for (auto& c : rep.cases)
    for (auto& r : c.regions) points += r.points;
  fmt::print("\nscene {}: {} of {} term, BRDF and whole-model cases swept ({} points; alternative formulations left "
             "out)\n",
             scene.path, rep.cases.size(), full, points);
  bool gltf = std::any_of(scene.materials.begin(), scene.materials.end(), [](auto& m) { return m.gltf; });
  if (gltf)
    fmt::print("  the glTF model is swept whole (MODEL gltf, at its catalog cases and parameter range ends) and "
               "through its terms (GGX D, height-correlated Smith G and G1, Schlick F)\n");
}

}  // namespace mfv
