#include "reference/estimators.hpp"

#include "rng/philox.hpp"

#include <glm/geometric.hpp>

#include <cmath>

namespace mfv::ref {
namespace {

constexpr double kMixCos = 0.25;  // cosine lobe share of the microfacet proposal
constexpr double kMixICos = 0.2;  // cosine-weighted share of light directions

// 2D Cauchy (Student-t, one degree of freedom) slopes of width w, as a
// density over solid angle: p(slope) / cos³θ, p = (1/(2πw²)) (1 + tan²/w²)^(-3/2).
double pdf_slope(double c, double s2, double w) {
  const double tan2 = s2 / (c * c);
  return std::pow(1.0 + tan2 / (w * w), -1.5) / (2.0 * M_PI * w * w) / (c * c * c);
}

// w <= 0: equal shares of Cauchy slopes of widths 1, 1/4, ..., 1/256 (a
// defensive mixture for code that declares no roughness; mfv check).
constexpr int kMixWidths = 5;
double mix_width(int k) { return std::ldexp(1.0, -2 * k); }

double pdf_cauchy(double c, double s2, double w) {
  if (w > 0.0) return pdf_slope(c, s2, w);
  double p = 0.0;
  for (int k = 0; k < kMixWidths; ++k) p += pdf_slope(c, s2, mix_width(k));
  return p / kMixWidths;
}

double pdf_m(double c, double s2, double w) {
  return kMixCos * c / M_PI + (1.0 - kMixCos) * pdf_cauchy(c, s2, w);
}

// The microfacet normal for uniforms (pick, phi, r): a Malley cosine lobe,
// or a slope of length w tan from the inverse CDF 1 - (1 + t²/w²)^(-1/2).
glm::dvec3 sample_m(double u_pick, double u_phi, double u_r, double w, double& c, double& s2) {
  const double phi = 2.0 * M_PI * u_phi;
  double theta;
  if (u_pick < kMixCos) {
    theta = std::asin(std::sqrt(u_r));
  } else {
    if (w <= 0.0) w = mix_width(std::min(int((u_pick - kMixCos) / (1.0 - kMixCos) * kMixWidths), kMixWidths - 1));
    const double t = w * std::sqrt(1.0 / ((1.0 - u_r) * (1.0 - u_r)) - 1.0);
    theta = std::atan(t);
  }
  c = std::cos(theta);
  s2 = std::sin(theta) * std::sin(theta);
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), c};
}

// f(i,o) cos / pdf(i), pdf = kMixICos cosine lobe + (1 - kMixICos) o reflected about m ~ pdf_m.
double albedo_weight(const BrdfSpec& b, const glm::dvec3& i, const glm::dvec3& o, double w) {
  if (i.z <= 0.0) return 0.0;
  const glm::dvec3 h = glm::normalize(i + o);
  const double oh = glm::dot(o, h);
  if (oh <= 0.0) return 0.0;
  const double hs2 = h.x * h.x + h.y * h.y;
  const double pdf = kMixICos * i.z / M_PI + (1.0 - kMixICos) * pdf_m(h.z, hs2, w) / (4.0 * oh);
  return brdf(b, i, o) * i.z / pdf;
}

// Roberts 2018 Kronecker sequence, g_j = frac(1/φ^j) for φ⁴ = φ + 1, in
// 32-bit fixed point (twin of RQMC_G* in kernels/integrate.cl).
constexpr uint32_t kRqmcG[3] = {3518319155u, 2882110345u, 2360945575u};

// Multi-sample MIS: each component of the albedo proposal once per point,
// weighted by its share (cosine light 0.2; reflection 0.8 x (cosine m 0.2, Cauchy m 0.8)).
double albedo_rqmc(const IntegralRef& s, uint64_t seed, uint64_t index) {
  const auto shift = philox(seed, s.stream, 2, 0);
  const uint32_t k = static_cast<uint32_t>(index);
  const double u_phi = u01_open(shift[0] + k * kRqmcG[0]), u_r = u01_open(shift[1] + k * kRqmcG[1]);
  double cos_o = s.cos_o;
  if (s.kind == Integral::EavgRqmc) cos_o = std::sqrt(u01_open(shift[2] + k * kRqmcG[2]));  // density 2μ
  const glm::dvec3 o(std::sqrt(1.0 - cos_o * cos_o), 0.0, cos_o);
  const double w = s.width;
  const double phi = 2.0 * M_PI * u_phi;
  const glm::dvec3 light(std::sqrt(u_r) * std::cos(phi), std::sqrt(u_r) * std::sin(phi), std::sqrt(1.0 - u_r));
  double v = kMixICos * albedo_weight(s.brdf, light, o, w);
  double c, s2;
  glm::dvec3 m = sample_m(0.0, u_phi, u_r, w, c, s2);
  v += (1.0 - kMixICos) * kMixCos * albedo_weight(s.brdf, 2.0 * glm::dot(o, m) * m - o, o, w);
  m = sample_m(1.0, u_phi, u_r, w, c, s2);
  v += (1.0 - kMixICos) * (1.0 - kMixCos) * albedo_weight(s.brdf, 2.0 * glm::dot(o, m) * m - o, o, w);
  return v;
}

}  // namespace

double sample_value(const IntegralRef& s, uint64_t seed, uint64_t index) {
  if (s.kind == Integral::AlbedoRqmc || s.kind == Integral::EavgRqmc) return albedo_rqmc(s, seed, index);
  auto r = philox(seed, s.stream, 0, index);
  const double u_branch = u01_open(r[0]), u_phi = u01_open(r[2]);
  double u_pick = u01_open(r[1]), u_r = u01_open(r[3]);
  const double w = s.width;
  const BrdfSpec& b = s.brdf;
  if (s.kind == Integral::DNorm) {
    // stratified radial uniform, as in the kernel: stratum `index` of `strata`
    // picks the component and, rescaled, drives it
    if (s.strata > 0) {
      const uint64_t n_cos = s.strata / 4;
      const bool cosine = index < n_cos;
      const uint64_t k = cosine ? index : index - n_cos, n = cosine ? n_cos : s.strata - n_cos;
      u_pick = cosine ? 0.0 : 1.0;
      u_r = std::min((double(k) + u_r) / double(n), 1.0 - 0x1p-24);
    }
    double c, s2;
    sample_m(u_pick, u_phi, u_r, w, c, s2);
    return b.d->ref_d(c, b.pd) * c / pdf_m(c, s2, w);
  }
  const glm::dvec3 o(std::sqrt(1.0 - s.cos_o * s.cos_o), 0.0, s.cos_o);
  if (s.kind == Integral::Masking) {
    // Heitz 2014 eq. 19 with G1(o,m) = G2(n, o, m)
    double c, s2;
    const glm::dvec3 m = sample_m(u_pick, u_phi, u_r, w, c, s2);
    const double om = glm::dot(o, m);
    if (om <= 0.0) return 0.0;
    const double g1 = b.g->ref_g(1.0, s.cos_o, c, om, b.pg);
    return g1 * b.d->ref_d(c, b.pd) * om / (pdf_m(c, s2, w) * s.cos_o);
  }
  glm::dvec3 i;
  if (u_branch < kMixICos) {
    const double st = std::sqrt(u_r), phi = 2.0 * M_PI * u_phi;
    i = {st * std::cos(phi), st * std::sin(phi), std::sqrt(1.0 - u_r)};
  } else {
    double c, s2;
    const glm::dvec3 m = sample_m(u_pick, u_phi, u_r, w, c, s2);
    i = 2.0 * glm::dot(o, m) * m - o;
  }
  return albedo_weight(b, i, o, w);
}

}  // namespace mfv::ref
