#include "reference/model_gltf.hpp"

#include "abi/sheen_table.h"
#include "reference/reference.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

namespace mfv::ref {

double model_gltf(const glm::dvec3& l, const glm::dvec3& v, const double* p) {
  const double alpha = p[0], metallic = p[1], base = p[2], f0 = p[3], f0_max = p[4], weight = p[5], alpha_b = p[6];
  if (l.z <= 0.0 || v.z <= 0.0) return 0.0;  // χ⁺: no reflection below the horizon
  // cosines that rounded above 1 are the normal itself (seed 000)
  const double NoL = std::min(l.z, 1.0), NoV = std::min(v.z, 1.0);
  // h = (l + v)/|l + v|; v·h = |l + v|/2 for unit l, v (no cancellation where l ≈ -v)
  const glm::dvec3 sum = l + v;
  const double len = glm::length(sum);
  if (!(len > 0.0)) return 0.0;  // l = -v: no half vector; G's χ⁺(v·h) is 0 (twin of the kernel's guard)
  const double NoH = std::min(sum.z / len, 1.0), VoH = std::min(0.5 * len, 1.0);
  const double sin2H = (sum.x * sum.x + sum.y * sum.y) / (len * len);  // 1 − (n·h)², without the cancellation
  const double a2 = alpha * alpha;
  // Appendix B.3.2: D = α² χ⁺(n·h) / (π ((n·h)²(α² − 1) + 1)²), the bracket as
  // (n·h)² α² + (1 − (n·h)²): near the normal 1 − (n·h)² cancels to ~1e-16
  // absolute, which α² = 1e-8 turns into 1e-8 of D even in double
  const double k = NoH * NoH * a2 + sin2H;
  const double D = a2 / (M_PI * k * k);
  // Appendix B.3.2: Vis = G / (4 |n·l| |n·v|) for the height-correlated Smith G
  // = 1 / (2 (|n·v| √(α² + (1 − α²)(n·l)²) + |n·l| √(α² + (1 − α²)(n·v)²)))
  const double vis =
      1.0 / (2.0 * (NoV * std::sqrt(a2 + (1.0 - a2) * NoL * NoL) + NoL * std::sqrt(a2 + (1.0 - a2) * NoV * NoV)));
  double specular = D * vis;
  if (alpha_b > 0.0) {
    // KHR_materials_anisotropy (twin of the kernel's branch): anisotropic GGX
    // D (Heitz 2014; Burley 2012 app. B) with alpha along t = +x and alpha_b
    // along b = +y, height-correlated Smith G2 = 1 / (1 + Λ(l) + Λ(v)) (Heitz
    // 2014 eq. 99) with the anisotropic Λ at the projected widths; Vis = G2 / (4 (n·l)(n·v))
    const double G2 = 1.0 / (1.0 + Lambda_ggx_aniso(l, alpha, alpha_b) + Lambda_ggx_aniso(v, alpha, alpha_b));
    specular = D_ggx_aniso(sum / len, alpha, alpha_b) * G2 / (4.0 * NoL * NoV);
  }
  const double fw = std::pow(1.0 - VoH, 5.0);
  // KHR_materials_specular fresnel_mix: layer weighted by weight·fr, base by 1 − weight·max_rgb(fr)
  const double fr = f0 + (1.0 - f0) * fw;
  const double fr_max = f0_max + (1.0 - f0_max) * fw;
  const double dielectric = (1.0 - weight * fr_max) * base / M_PI + weight * fr * specular;
  // B.3.4 conductor_fresnel with f0 = baseColor
  const double metal = specular * (base + (1.0 - base) * fw);
  // B.3.5 material = mix(dielectric_brdf, metal_brdf, metallic)
  return (1.0 - metallic) * dielectric + metallic * metal;
}

namespace {
// KHR_materials_clearcoat, "Implementation": coated_material = mix(material,
// clearcoat_brdf, clearcoat · (0.04 + 0.96 (1 − |V·Nc|)^5)), Nc = n
double coated(double material, const glm::dvec3& l, const glm::dvec3& v, double ca, double clearcoat) {
  // clearcoat_brdf = specular_brdf(α = clearcoatRoughness²): Appendix B.3.2 D·Vis, the
  // metal with F = 1 (base colour 1: conductor_fresnel = 1) of the glTF model itself
  const double white_metal[7] = {ca, 1.0, 1.0, 0.04, 0.04, 1.0, 0.0};
  const double layer = model_gltf(l, v, white_metal);
  // V = l: the catalog's first direction is the spec's view (kernels/model_gltf.cl explains why)
  const double weight = clearcoat * (0.04 + 0.96 * std::pow(1.0 - std::min(l.z, 1.0), 5.0));
  return (1.0 - weight) * material + weight * layer;
}
}  // namespace

double model_gltf_clearcoat(const glm::dvec3& l, const glm::dvec3& v, const double* p) {
  if (l.z <= 0.0 || v.z <= 0.0) return 0.0;  // χ⁺: no reflection below the horizon
  const double base[7] = {p[0], p[1], p[2], p[3], p[4], 1.0, 0.0};
  return coated(model_gltf(l, v, base), l, v, p[5], p[6]);
}

double model_gltf_clearcoat_aniso(const glm::dvec3& l, const glm::dvec3& v, const double* p) {
  if (l.z <= 0.0 || v.z <= 0.0) return 0.0;  // χ⁺: no reflection below the horizon
  // the anisotropic base (KHR_materials_anisotropy: alpha_t = p[0], alpha_b = p[6]), f0_max = f0
  const double base[7] = {p[0], p[1], p[2], p[3], p[3], 1.0, p[6]};
  return coated(model_gltf(l, v, base), l, v, p[4], p[5]);
}

// The E_sheen table kernels/model_gltf.cl also includes: its float constants
// are the kernel's, read here as doubles.
const std::vector<double>& sheen_table_values() {
  static const std::vector<double> v(std::begin(SHEEN_E), std::end(SHEEN_E));
  return v;
}

int sheen_table_side() { return static_cast<int>(std::lround(std::sqrt(double(sheen_table_values().size())))); }

double sheen_albedo_table(double mu, double alpha) {
  // grid of checks/energy.cpp: mu_m = (m + 0.5)/N, alpha_j = 10^(-3 + 3j/(N - 1))
  const auto& t = sheen_table_values();
  const int n = sheen_table_side();
  const double x = std::clamp(mu * n - 0.5, 0.0, double(n - 1));
  const double y = std::clamp((std::log10(alpha) + 3.0) / 3.0 * (n - 1), 0.0, double(n - 1));
  const int i = std::min(int(x), n - 2), j = std::min(int(y), n - 2);
  const double fx = x - i, fy = y - j;
  auto at = [&](int a, int m) { return t[size_t(a) * size_t(n) + size_t(m)]; };
  const double lo = at(j, i) + fx * (at(j, i + 1) - at(j, i));
  const double hi = at(j + 1, i) + fx * (at(j + 1, i + 1) - at(j + 1, i));
  return lo + fy * (hi - lo);
}

double model_gltf_sheen(const glm::dvec3& l, const glm::dvec3& v, const double* p) {
  if (l.z <= 0.0 || v.z <= 0.0) return 0.0;  // χ⁺: no reflection below the horizon
  // KHR_materials_sheen, "Implementation Notes" (albedo-scaling technique):
  //   f = sheenColor D V + (f_diffuse + f_specular) min(1 − max3 E(n·v), 1 − max3 E(n·l))
  const double base[7] = {p[0], p[1], p[2], p[3], p[3], 1.0, 0.0};
  const double material = model_gltf(l, v, base);
  const glm::dvec3 sum = l + v;
  const double len = glm::length(sum);
  if (!(len > 0.0)) return 0.0;  // l = -v: no half vector
  const double NoL = std::min(l.z, 1.0), NoV = std::min(v.z, 1.0);
  const double NoH = std::min(sum.z / len, 1.0), VoH = std::min(0.5 * len, 1.0);
  const double sin2H = (sum.x * sum.x + sum.y * sum.y) / (len * len);
  // "Sheen distribution" and "Sheen visibility": V = G / (4 (n·l)(n·v))
  const double D = D_charlie_cs(NoH * NoH, sin2H, p[4]);
  const double V = G_charlie_sheen(NoL, NoV, NoH, VoH, p[4]) / (4.0 * NoL * NoV);
  const double max3 = std::max(p[5], p[6]);
  const double scaling =
      std::min(1.0 - max3 * sheen_albedo_table(NoV, p[4]), 1.0 - max3 * sheen_albedo_table(NoL, p[4]));
  return (p[5] > 0.0 ? p[5] * D * V : 0.0) + material * scaling;  // no sheen: no lobe (as the kernel)
}

namespace {
// KHR_materials_transmission (thin-walled), one side of the sphere: the spec's
// fresnel_mix(ior, mix(diffuse, baseColor specular_btdf, transmission),
// specular_brdf), where specular_btdf is specular_brdf at the light reflected
// through the surface plane, L' = L - 2 (n.L) n, and F its Schlick F at V.H'.
double thin_walled(const glm::dvec3& l, const glm::dvec3& v, const double* p) {
  const double alpha = p[0], metallic = p[1], base = p[2], f0 = p[3], transmission = p[4];
  const glm::dvec3 n(0.0, 0.0, 1.0);
  const bool transmitted = glm::dot(v, n) < 0.0;
  const glm::dvec3 light = transmitted ? v - 2.0 * glm::dot(v, n) * n : v;
  // specular_brdf = D Vis: the glTF model as a white metal (conductor_fresnel = 1)
  const double white_metal[7] = {alpha, 1.0, 1.0, 0.04, 0.04, 1.0, 0.0};
  const double specular = model_gltf(l, light, white_metal);
  const double len = glm::length(l + light);
  const double fw = std::pow(1.0 - std::min(0.5 * len, 1.0), 5.0);  // (1 - V.H')^5, V.H' = |V + L'|/2
  const double fr = f0 + (1.0 - f0) * fw;
  if (transmitted) return (1.0 - metallic) * (1.0 - fr) * transmission * base * specular;
  const double dielectric = (1.0 - fr) * ((1.0 - transmission) * base / M_PI) + fr * specular;
  return (1.0 - metallic) * dielectric + metallic * specular * (base + (1.0 - base) * fw);
}
}  // namespace

double model_gltf_transmission(const glm::dvec3& l, const glm::dvec3& v, const double* p) {
  if (l.z <= 0.0 || v.z <= 0.0) return 0.0;
  // the sphere folded onto v's hemisphere: reflected toward v plus transmitted toward v mirrored below
  return thin_walled(l, v, p) + thin_walled(l, glm::dvec3(v.x, v.y, -v.z), p);
}

double albedo_gltf(double, const double* p) {
  if (p[1] == 0.0 && p[5] == 0.0) return p[2];  // (1 - 0) base/π integrated against n·v
  return std::nan("");
}

}  // namespace mfv::ref
