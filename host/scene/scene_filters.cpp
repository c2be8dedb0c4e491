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

std::vector<std::string> scene_energy_models(const Scene& scene) {
  std::vector<std::string> out;
  for (auto& m : scene.materials) {
    const Term *d, *g, *f;
    terms_of_material(m, d, g, f);
    add_unique(out, d->id + "/" + g->id);
  }
  return out;
}

void print_scene_energy(const Scene& scene, const EnergyReport& rep) {
  const size_t full = terms_of(Kind::D).size() * terms_of(Kind::G).size();
  fmt::print("\nscene {}: {} of {} D x G tables computed ({} left out)\n", scene.path, rep.tables.size(), full,
             full - rep.tables.size());
  for (auto& m : scene.materials) {
    const Term *d, *g, *f;
    terms_of_material(m, d, g, f);
    const EnergyTable* t = nullptr;
    for (auto& tb : rep.tables)
      if (tb.d == d && tb.g == g) t = &tb;
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
    fmt::print("  material '{}': {}/{} at alpha {:g}{}: E_avg {:.4f}, energy loss 1 - E_avg {:.4f}\n", m.name, d->id,
               g->id, m.alpha,
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
    add_unique(out, "BRDF " + d->id + "/" + g->id + "/" + f->id);
  }
  return out;
}

void print_scene_stability(const Scene& scene, const StabilityReport& rep) {
  size_t g1 = 0;
  for (auto& t : catalog()) g1 += !t.g1_kernel_fn.empty() && t.id != "smith_ggx_correlated";
  const size_t full = catalog().size() + g1 +
                      terms_of(Kind::D).size() * terms_of(Kind::G).size() * terms_of(Kind::F).size();
  size_t points = 0;
  for (auto& c : rep.cases)
    for (auto& r : c.regions) points += r.points;
  fmt::print("\nscene {}: {} of {} term and BRDF cases swept ({} points; alternative formulations left out)\n",
             scene.path, rep.cases.size(), full, points);
  bool gltf = std::any_of(scene.materials.begin(), scene.materials.end(), [](auto& m) { return m.gltf; });
  if (gltf)
    fmt::print("  the glTF model is swept through its terms (GGX D, height-correlated Smith G and G1, Schlick F) and "
               "the BRDF ggx/smith_ggx_correlated/schlick; its Fresnel mix is covered by mfv agree (MODEL gltf)\n");
}

}  // namespace mfv
