#include "reference/estimators.hpp"

#include "rng/philox.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace mfv::ref {
namespace {

constexpr double kMixCos = 0.25;  // cosine lobe share of the microfacet proposal
constexpr double kMixICos = 0.2;  // cosine-weighted share of light directions

}  // namespace

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

namespace {
// Twin of spec_brdf in kernels/integrate.cl: a whole model is evaluated with
// the fixed direction o as the light and the sampled i as the view.
double spec_brdf(const BrdfSpec& b, const glm::dvec3& i, const glm::dvec3& o) {
  if (b.model) {
    const double p[kModelParams] = {b.pd, b.pg, b.f0, b.f1, b.kd, b.p5};
    return b.model->ref(o, i, p);
  }
  return brdf(b, i, o);
}

// f(i,o) cos / pdf(i), pdf = kMixICos cosine lobe + (1 - kMixICos) o reflected about m ~ pdf_m.
double albedo_weight(const BrdfSpec& b, const glm::dvec3& i, const glm::dvec3& o, double w) {
  if (i.z <= 0.0) return 0.0;
  const glm::dvec3 h = glm::normalize(i + o);
  const double oh = glm::dot(o, h);
  if (oh <= 0.0) return 0.0;
  const double hs2 = h.x * h.x + h.y * h.y;
  const double pdf = kMixICos * i.z / M_PI + (1.0 - kMixICos) * pdf_m(h.z, hs2, w) / (4.0 * oh);
  return spec_brdf(b, i, o) * i.z / pdf;
}

// Roberts 2018 Kronecker sequence in 2D, g_j = frac(1/φ^j) for the plastic
// number φ³ = φ + 1, in 32-bit fixed point (twin of RQMC_G* in kernels/integrate.cl).
constexpr uint32_t kRqmcG[2] = {3242174889u, 2447445414u};

}  // namespace

// mfv energy's proposal (twin of energy_weight in kernels/integrate.cl): o
// reflected about a visible normal of the GGX shape of width w.
// The GGX shape, written from Walter et al. 2007 eq. 33 as a function of the
// angle: D_w(h) = 1 / (π w² cos⁴θ (1 + tan²θ / w²)²); Smith G1 of Heitz 2014
// eq. 72: 2 / (1 + sqrt(1 + w² tan²θ_o)); visible normals (Heitz 2018 eq. 3):
// G1(o) (o·h) D_w(h) / cos_o, and i = reflect(o, h) has 1 / (4 o·h) of it.
double vis_pdf_i(const glm::dvec3& h, const glm::dvec3& o, double w) {
  const double ch = h.z, th2 = (h.x * h.x + h.y * h.y) / (ch * ch);
  const double d = 1.0 / (M_PI * w * w * ch * ch * ch * ch * (1.0 + th2 / (w * w)) * (1.0 + th2 / (w * w)));
  const double to2 = (o.x * o.x + o.y * o.y) / (o.z * o.z);
  const double g1 = 2.0 / (1.0 + std::sqrt(1.0 + w * w * to2));
  return g1 * d / (4.0 * o.z);
}

// A visible normal of the GGX shape at o, by stretching to w = 1 and drawing
// from the spherical cap (Dupuy & Benyoub 2023, Listing 3).
glm::dvec3 sample_vis(const glm::dvec3& o, double u_phi, double u_r, double w) {
  const glm::dvec3 os = glm::normalize(glm::dvec3(w * o.x, w * o.y, o.z));
  const double phi = 2.0 * M_PI * u_phi;
  const double z = (1.0 - u_r) * (1.0 + os.z) - os.z;
  const double st = std::sqrt(std::clamp(1.0 - z * z, 0.0, 1.0));
  const glm::dvec3 hs = glm::dvec3(st * std::cos(phi), st * std::sin(phi), z) + os;
  const glm::dvec3 h(w * hs.x, w * hs.y, hs.z);
  const double len = glm::length(h);
  return len > 0.0 ? h / len : glm::dvec3(0.0);
}

namespace {

double energy_weight(const BrdfSpec& b, const glm::dvec3& m, const glm::dvec3& o, double w) {
  const glm::dvec3 i = 2.0 * glm::dot(o, m) * m - o;
  if (i.z <= 0.0) return 0.0;
  return spec_brdf(b, i, o) * i.z / vis_pdf_i(glm::normalize(i + o), o, w);
}

// One point of AlbedoRqmc / EavgRqmc.
double albedo_rqmc(const IntegralRef& s, uint64_t seed, uint64_t index) {
  const auto shift = philox(seed, s.stream, 2, 0);
  const uint32_t k = static_cast<uint32_t>(index);
  const double u_phi = u01_open(shift[0] + k * kRqmcG[0]), u_r = u01_open(shift[1] + k * kRqmcG[1]);
  double cos_o = s.cos_o;
  if (s.kind == Integral::EavgRqmc) {  // density 2μ, μ² stratified over `strata` points
    const double u = u01_open(shift[2]) + double(k) / double(s.strata);
    cos_o = std::sqrt(u - std::floor(u));
  }
  const glm::dvec3 o(std::sqrt(1.0 - cos_o * cos_o), 0.0, cos_o);
  const glm::dvec3 m = sample_vis(o, u_phi, u_r, s.width);
  return m.z > 0.0 ? energy_weight(s.brdf, m, o, s.width) : 0.0;
}

}  // namespace

// Twin of the pair draw in kernels/integrate.cl `reciprocity`.
void reciprocity_pair(uint64_t seed, uint32_t stream, uint32_t index, glm::dvec3& a, glm::dvec3& b) {
  const auto r = philox(seed, stream, 1, index);
  double ca = u01_open(r[0]), cb = u01_open(r[2]);
  const double pa = 2.0 * M_PI * u01_open(r[1]), pb = 2.0 * M_PI * u01_open(r[3]);
  const uint32_t kind = index % 4;
  if (kind == 1) {  // both grazing
    ca *= 1e-3;
    cb *= 1e-3;
  }
  const double sa = std::sqrt((1.0 - ca) * (1.0 + ca));
  a = {sa * std::cos(pa), sa * std::sin(pa), ca};
  if (kind == 2 || kind == 3) {  // near-retro or near-mirror
    const glm::dvec3 base = kind == 2 ? a : glm::dvec3(-a.x, -a.y, a.z);
    b = glm::normalize(base + 1e-3 * glm::dvec3(cb - 0.5, u01_open(r[3]) - 0.5, 0.0));
    if (b.z <= 0.0) b.z = -b.z;
  } else {
    const double sb = std::sqrt((1.0 - cb) * (1.0 + cb));
    b = {sb * std::cos(pb), sb * std::sin(pb), cb};
  }
}

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
