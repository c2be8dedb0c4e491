// The parameter points a glTF material is checked at (issue 21): every range
// at its ends, and the parameters that enter non-linearly also inside.
//
// Why the ends suffice for some parameters: the model (kernels/model_gltf.cl)
// is affine in base, metallic and specularFactor (weight) with the others
// fixed: dielectric = (1 - w F(f0_max)) base/pi + w F(f0) spec, metal =
// (base + (1 - base) F_w) spec, material = mix(dielectric, metal, metallic).
// An affine function on an interval takes its extremes at the ends, so the
// albedo's maximum (energy) over such a range is at one of its ends; the
// dielectric F0s enter through Schlick's F, affine in f0 too. Roughness
// (alpha = roughness²) and anisotropyStrength enter D and G non-linearly:
// they are also checked at 1/3 and 2/3 of their range.
#include "scene/scene.hpp"

#include "catalog/roughness.hpp"
#include "reference/model_gltf.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace mfv {
namespace {

std::vector<double> ends(const ParamRange& r) {
  return r.varies() ? std::vector<double>{r.lo, r.hi} : std::vector<double>{r.hi};
}

std::vector<double> ends_and_inside(const ParamRange& r) {
  if (!r.varies()) return {r.hi};
  const double d = r.hi - r.lo;
  return {r.lo, r.lo + d / 3.0, r.lo + 2.0 * d / 3.0, r.hi};
}

template <class T>
void push_unique(std::vector<T>& v, const T& x) {
  if (std::find(v.begin(), v.end(), x) == v.end()) v.push_back(x);
}

// The widths of a perceptual roughness range, at its ends and inside, none
// below kSceneMinAlpha (the alpha glTF roughness below 0.01 is checked at).
std::vector<double> alphas_of(const ParamRange& roughness) {
  std::vector<double> out;
  for (double rough : ends_and_inside(roughness))
    push_unique(out, std::max(alpha_from_perceptual(rough), kSceneMinAlpha));
  return out;
}

// KHR_materials_ior: f0 = ((ior - 1)/(ior + 1))², ior = 0 giving 1 (the
// specular-glossiness conversion); KHR_materials_specular: dielectric F0 =
// min(f0 · specularColor, 1) per channel (the extension's own clamp).
double f0_of(const GltfFactors& f, double specular_color) {
  const double r = f.ior == 0 ? 1.0 : (f.ior - 1.0) / (f.ior + 1.0);
  return std::min(r * r * specular_color, 1.0);
}

void push_unique_point(std::vector<WholePoint>& v, const WholePoint& w) {
  for (auto& x : v)
    if (x.model == w.model && x.p == w.p) return;
  v.push_back(w);
}

}  // namespace

std::vector<GltfChannelParams> SceneMaterial::channels() const {
  std::vector<GltfChannelParams> out;
  // the fresnel_mix base weight max_rgb(F) grows with f0: its ends over the colour range
  std::vector<double> f0_max;
  for (bool high : {false, true}) {
    double m = 0;
    for (int k = 0; k < 3; ++k)
      m = std::max(m, f0_of(factors, high ? specular_color[size_t(k)].hi : specular_color[size_t(k)].lo));
    push_unique(f0_max, m);
  }
  for (double rough : ends_and_inside(roughness))
    for (double strength : ends_and_inside(anisotropy_strength)) {
      // glTF Appendix B: alpha = roughness², floored where float32 estimators end
      const double alpha = std::max(alpha_from_perceptual(rough), kSceneMinAlpha);
      // KHR_materials_anisotropy: alpha_t = mix(alpha, 1, strength²) along the
      // anisotropy direction, alpha_b = alpha across it. anisotropyRotation turns
      // that direction about n; the model is evaluated in its own frame (t = +x),
      // where the BRDF does not depend on the rotation, so it is recorded, not integrated.
      const double s2 = strength * strength;
      const double alpha_t = s2 > 0.0 ? alpha + (1.0 - alpha) * s2 : alpha;
      const double alpha_b = s2 > 0.0 ? alpha : 0.0;
      for (double metal : ends(metallic))
        for (double weight : ends(specular))
          for (int k = 0; k < 3; ++k)
            for (double b : ends(base[size_t(k)]))
              for (double sc : ends(specular_color[size_t(k)]))
                for (double fm : f0_max) {
                  const double f0 = f0_of(factors, sc);
                  if (f0 > fm) continue;  // not a colour the range can hold
                  GltfChannelParams c{alpha_t, metal, b, f0, fm, weight, alpha_b};
                  // a metal (metallic 1) never evaluates its dielectric part: one point for all of them
                  if (metal >= 1.0) c.f0 = c.f0_max = 0.04, c.weight = 1.0;
                  push_unique(out, c);
                }
    }
  return out;
}

std::vector<std::pair<double, double>> SceneMaterial::lobes() const {
  std::vector<std::pair<double, double>> out;
  for (auto& c : channels()) push_unique(out, std::make_pair(c.alpha, c.alpha_b));
  return out;
}

std::vector<double> SceneMaterial::alphas() const { return gltf ? alphas_of(roughness) : std::vector<double>{alpha}; }

std::vector<double> SceneMaterial::coat_alphas() const {
  return coat_checked ? alphas_of(clearcoat_roughness) : std::vector<double>{};
}

std::vector<GltfChannelParams> SceneMaterial::white_lobes() const {
  auto all = lobes();
  for (double a : coat_alphas()) all.push_back({a, 0.0});  // KHR_materials_clearcoat: the coat's own lobe
  std::vector<GltfChannelParams> out;
  for (auto [at, ab] : all)
    out.push_back({at, 1.0, 1.0, 1.0, 1.0, 1.0, ab});  // metallic, base colour, f0, f0_max, weight 1: F = 1
  return out;
}

// KHR_materials_clearcoat: the coat's weight clearcoat enters the layering
// affinely (mix(material, layer, clearcoat · F)): its ends; the coat's
// roughness non-linearly: ends and inside.
std::vector<ModelParams> SceneMaterial::coat_points() const {
  std::vector<ModelParams> out;
  if (!coat_checked) return out;
  for (auto& c : channels())
    if (!(c.alpha_b > 0.0))
      for (double cc : ends(clearcoat))
        for (double ca : coat_alphas())
          push_unique(out, ModelParams{c.alpha, c.metallic, c.base, c.f0, c.f0_max, ca, cc});
  return out;
}

// The same over the anisotropic channel points (KHR_materials_anisotropy):
// the "gltf_clearcoat_aniso" model, both lobes.
std::vector<ModelParams> SceneMaterial::coat_aniso_points() const {
  std::vector<ModelParams> out;
  if (!coat_checked) return out;
  for (auto& c : channels())
    if (c.alpha_b > 0.0)
      for (double cc : ends(clearcoat))
        for (double ca : coat_alphas())
          push_unique(out, ModelParams{c.alpha, c.metallic, c.base, c.f0, ca, cc, c.alpha_b});
  return out;
}

// KHR_materials_sheen: f = sheen D V + base (1 − max3 max(E(n·v), E(n·l)))
// (min(1 − m a, 1 − m b) = 1 − m max(a, b) for m >= 0) is affine in this
// channel's sheen and in max3 apart, so the energy is extreme at their ends:
// each channel's sheenColor ends with the ends of the largest of the other
// two; the sheen roughness enters non-linearly: ends and inside. The base is
// each isotropic channel point (an anisotropic base is not layered here).
std::vector<ModelParams> SceneMaterial::sheen_points() const {
  std::vector<ModelParams> out;
  if (!sheen_checked) return out;
  const double lo_alpha = gltf_sheen_model().params[4].lo;  // the Charlie D's range starts at 1e-3
  for (auto& c : channels()) {
    if (c.alpha_b > 0.0) continue;
    for (size_t k = 0; k < 3; ++k) {
      const ParamRange& a = sheen_color[(k + 1) % 3];
      const ParamRange& b = sheen_color[(k + 2) % 3];
      const ParamRange others{std::max(a.lo, b.lo), std::max(a.hi, b.hi), "max of the other channels"};
      for (double s : ends(sheen_color[k]))
        for (double o : ends(others))
          for (double r : ends_and_inside(sheen_roughness))
            push_unique(out, ModelParams{c.alpha, c.metallic, c.base, c.f0, std::max(r, lo_alpha), s, o});
    }
  }
  return out;
}

std::string WholePoint::key() const {
  std::string s = model->id;
  for (size_t i = 0; i < model->params.size(); ++i) s += fmt::format(" {}={:.9g}", model->params[i].name, p[i]);
  return s;
}

std::vector<WholePoint> SceneMaterial::whole_points() const {
  std::vector<WholePoint> out;
  // a refracting boundary (KHR_materials_volume) is checked as the Walter BSDF (scene_checks.cpp), not as a BRDF
  if (!gltf || !not_checked.empty() || volume_checked) return out;
  if (thin_checked) {
    // KHR_materials_transmission, thin-walled: transmission enters affinely
    // (mix(diffuse, btdf, transmission)): its ends. R + T <= 1 where no
    // diffuse is left (fresnel_mix's gain needs one: kGltfFresnelMixGain)
    for (auto& c : channels())
      for (double t : ends(transmission)) {
        const bool plain = c.metallic >= 1.0 || (1.0 - c.metallic) * c.base * (1.0 - t) <= 0.0;
        const Expect e = plain ? Expect::Hold : Expect::May;
        push_unique_point(out, {&gltf_transmission_model(), ModelParams{c.alpha, c.metallic, c.base, c.f0, t, 0, 0}, e,
                                plain ? "" : kGltfFresnelMixGain, Expect::Hold, ""});
      }
    return out;
  }
  if (!coat_checked)
    for (auto& c : channels()) {
      const Expect e = gltf_energy_expect(c);
      out.push_back({&gltf_model(), c.params(), e, e == Expect::Hold ? "" : kGltfFresnelMixGain, Expect::Hold, ""});
    }
  for (auto& p : sheen_points()) {  // the sheen layer over the base (gltf_sheen), beside the base's own points
    // Where the sheen lobe alone reflects more than 1 (E_sheen > 1 at grazing,
    // small sheen roughness: mfv energy's table) the layer may gain energy
    double e_max = 0;
    for (int m = 0; m < 64; ++m) e_max = std::max(e_max, ref::sheen_albedo_table((m + 0.5) / 64, p[4]));
    // Any sheen lobe may gain at grazing light: the layer's albedo table is
    // clamped below mu = 1/32 (kGltfSheenTableClamp, the catalog's cases)
    const bool gain = p[5] > 0.0 && e_max > 1.0;
    out.push_back({&gltf_sheen_model(), p, p[5] > 0.0 ? Expect::May : Expect::Hold,
                   gain ? fmt::format("E_sheen reaches {:.3g} at grazing for sheenRoughness {:g} (the Charlie "
                                      "visibility's fitted Lambda under-masks there)",
                                      e_max, p[4])
                        : p[5] > 0.0 ? kGltfSheenTableClamp : "",
                   Expect::Hold, ""});
  }
  if (!coat_checked) return out;
  for (auto& p : coat_aniso_points()) {
    const GltfChannelParams base{p[0], p[1], p[2], p[3], p[3], 1.0, p[6]};
    const Expect e = gltf_energy_expect(base);
    out.push_back({&gltf_clearcoat_aniso_model(), p, e, e == Expect::Hold ? "" : kGltfFresnelMixGain,
                   p[5] > 0.0 ? Expect::May : Expect::Hold,
                   p[5] > 0.0 ? "KHR_materials_clearcoat weights the coat by its Fresnel at n.v, not v.h (the spec's "
                                "Discussion): f(l, v) != f(v, l)"
                              : ""});
  }
  for (auto& p : coat_points()) {
    const GltfChannelParams base{p[0], p[1], p[2], p[3], p[4], 1.0, 0.0};
    const Expect e = gltf_energy_expect(base);  // the coat takes its share from the base: the base's gain may remain
    const bool coated = p[6] > 0.0;             // clearcoat
    out.push_back({&gltf_clearcoat_model(), p, e, e == Expect::Hold ? "" : kGltfFresnelMixGain,
                   // may, not must: where the coat and the base happen to coincide the asymmetry vanishes
                   coated ? Expect::May : Expect::Hold,
                   coated ? "KHR_materials_clearcoat weights the coat by its Fresnel at n.v, not v.h (the spec's "
                            "Discussion): f(l, v) != f(v, l)"
                          : ""});
  }
  return out;
}

std::vector<ModelParams> SceneMaterial::thin_identity_points() const {
  std::vector<ModelParams> out;
  if (!thin_checked || !not_checked.empty()) return out;
  for (double a : alphas()) push_unique(out, ModelParams{a, 0.0, 1.0, f0_of(factors, 1.0), 1.0, 0.0, 0.0});
  return out;
}

void set_factor_ranges(SceneMaterial& m) {
  auto fixed = [](double v) { return ParamRange{v, v, "factor"}; };
  m.roughness = fixed(m.factors.roughness);
  m.metallic = fixed(m.factors.metallic);
  m.specular = fixed(m.factors.specular);
  m.anisotropy_strength = fixed(m.factors.anisotropy_strength);
  m.clearcoat = fixed(0.0);
  m.clearcoat_roughness = fixed(0.0);
  for (auto& c : m.sheen_color) c = fixed(0.0);
  m.sheen_roughness = fixed(0.0);
  m.transmission = fixed(0.0);
  for (size_t k = 0; k < 3; ++k) {
    m.base[k] = fixed(m.factors.base[k]);
    m.specular_color[k] = fixed(m.factors.specular_color[k]);
  }
}

void note_alpha_floor(SceneMaterial& m) {
  const double lo = m.roughness.lo;
  m.alpha = std::max(m.factors.roughness * m.factors.roughness, kSceneMinAlpha);
  if (lo * lo < kSceneMinAlpha)
    m.warnings.push_back(fmt::format(
        "roughness {:g} gives alpha = {:g}, below {:g}, the narrowest lobe the float32 estimators resolve: checked "
        "at alpha = {:g} (roughness 0.01)",
        lo, lo * lo, kSceneMinAlpha, kSceneMinAlpha));
}

}  // namespace mfv
