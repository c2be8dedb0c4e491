#include "reference/estimators.hpp"

#include "rng/philox.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

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

double pdf_m(double c, double s2, double w) { return kMixCos * c / M_PI + (1.0 - kMixCos) * pdf_cauchy(c, s2, w); }

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

// Anisotropic widths (wx, wy) along (t, b) = (+x, +y): the Cauchy slopes
// stretched, slope density (1/(2π wx wy)) (1 + sx²/wx² + sy²/wy²)^(-3/2),
// over solid angle divided by cos³θ (twin of pdf_m_aniso_c in kernels/estimators.cl).
double pdf_slope_aniso(const glm::dvec3& m, double wx, double wy) {
  const double c = m.z, sx = m.x / c, sy = m.y / c;
  const double slope = std::pow(1.0 + sx * sx / (wx * wx) + sy * sy / (wy * wy), -1.5) / (2.0 * M_PI * wx * wy);
  return slope / (c * c * c);
}

double pdf_m_aniso(const glm::dvec3& m, double wx, double wy) {
  return kMixCos * m.z / M_PI + (1.0 - kMixCos) * pdf_slope_aniso(m, wx, wy);
}

glm::dvec3 sample_m_aniso(double u_pick, double u_phi, double u_r, double wx, double wy) {
  double c, s2;
  if (u_pick < kMixCos) return sample_m(u_pick, u_phi, u_r, wx, c, s2);
  const double phi = 2.0 * M_PI * u_phi;
  const double t = std::sqrt(1.0 / ((1.0 - u_r) * (1.0 - u_r)) - 1.0);  // unit-width |slope|, as sample_m
  const double sx = wx * t * std::cos(phi), sy = wy * t * std::sin(phi);
  return glm::normalize(glm::dvec3(sx, sy, 1.0));  // the normal of slope (sx, sy), up to its sign
}

namespace {
// Twin of spec_brdf in kernels/estimators.cl: a whole model is evaluated with
// the fixed direction o as the light and the sampled i as the view.
double spec_brdf(const BrdfSpec& b, const glm::dvec3& i, const glm::dvec3& o) {
  if (b.model) {
    const double p[kModelParams] = {b.pd, b.pg, b.f0, b.f1, b.kd, b.p5, b.pd2};
    return b.model->ref(o, i, p);
  }
  return brdf(b, i, o);
}

// f(i,o) cos / pdf(i), pdf = kMixICos cosine lobe + (1 - kMixICos) o reflected about m ~ pdf_m.
// wy > 0: the Cauchy slopes stretched to (w, wy) (IntegralSpec::width_y).
double albedo_weight(const BrdfSpec& b, const glm::dvec3& i, const glm::dvec3& o, double w, double wy) {
  if (i.z <= 0.0) return 0.0;
  const glm::dvec3 h = glm::normalize(i + o);
  const double oh = glm::dot(o, h);
  if (oh <= 0.0) return 0.0;
  const double hs2 = h.x * h.x + h.y * h.y;
  const double pm = wy > 0 ? pdf_m_aniso(h, w, wy) : pdf_m(h.z, hs2, w);
  const double pdf = kMixICos * i.z / M_PI + (1.0 - kMixICos) * pm / (4.0 * oh);
  return spec_brdf(b, i, o) * i.z / pdf;
}

// Roberts 2018 Kronecker sequence in 2D, g_j = frac(1/φ^j) for the plastic
// number φ³ = φ + 1, in 32-bit fixed point (twin of RQMC_G* in kernels/estimators.cl).
constexpr uint32_t kRqmcG[2] = {3242174889u, 2447445414u};

}  // namespace

// Owen-scrambled 2D Sobol points (twin of owen_sobol_2d in
// kernels/estimators.cl, written from the definitions): Sobol's digits from
// its direction numbers (first dimension v_j = 2^(31-j), the van der Corput
// sequence; second v_0 = 2^31, v_j = v_(j-1) ^ (v_(j-1) >> 1)), then Burley
// 2020's nested uniform scramble (Listing 2: reverse, hash, reverse) with
// Vegdahl 2021's hash.
namespace {

uint32_t reverse_bits(uint32_t x) {
  uint32_t r = 0;
  for (int b = 0; b < 32; ++b) r |= ((x >> b) & 1u) << (31 - b);
  return r;
}

uint32_t owen_scramble(uint32_t x, uint32_t seed) {
  uint32_t v = reverse_bits(x);
  v ^= v * 0x3d20adeau;
  v += seed;
  v *= (seed >> 16) | 1u;
  v ^= v * 0x05526c56u;
  v ^= v * 0x53a22864u;
  return reverse_bits(v);
}

}  // namespace

void owen_sobol_2d(uint32_t k, uint32_t s0, uint32_t s1, double& u0, double& u1) {
  uint32_t x = 0, y = 0, v = 0x80000000u;
  for (int j = 0; j < 32; ++j, v ^= v >> 1)
    if ((k >> j) & 1u) x ^= 0x80000000u >> j, y ^= v;
  u0 = u01_open(owen_scramble(x, s0));
  u1 = u01_open(owen_scramble(y, s1));
}

double owen_sobol_dim3(uint32_t k, uint32_t s) {
  // Sobol's third dimension (Joe & Kuo 2008: primitive polynomial x² + x + 1,
  // m_1 = 1, m_2 = 3, m_j = 2 m_{j-1} ^ 4 m_{j-2} ^ m_{j-2}), digit j of k
  // adding m_{j+1} / 2^{j+1}
  uint64_t m[34] = {0, 1, 3};
  for (int j = 3; j <= 32; ++j) m[j] = (2 * m[j - 1]) ^ (4 * m[j - 2]) ^ m[j - 2];
  uint32_t x = 0;
  for (int j = 0; j < 32; ++j)
    if ((k >> j) & 1u) x ^= uint32_t(m[j + 1] << (31 - j));
  return u01_open(owen_scramble(x, s));
}

// mfv energy's proposal (twin of energy_weight in kernels/albedo.cl): o
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

// The anisotropic GGX shape of widths (wx, wy) along (+x, +y), from its
// slopes (Heitz 2014, anisotropic distributions): D = 1 / (π wx wy cos⁴θ
// (1 + sx²/wx² + sy²/wy²)²) with (sx, sy) = -(h.x, h.y) / h.z up to sign,
// Smith G1(o) = 2 / (1 + sqrt(1 + (wx² o.x² + wy² o.y²) / o.z²)) (eq. 72 at
// the view's projected width); the pdf of i as above.
double vis_pdf_i(const glm::dvec3& h, const glm::dvec3& o, double wx, double wy) {
  const double ch = h.z, sx = h.x / ch, sy = h.y / ch;
  const double k = 1.0 + sx * sx / (wx * wx) + sy * sy / (wy * wy);
  const double d = 1.0 / (M_PI * wx * wy * ch * ch * ch * ch * k * k);
  const double a2t2 = (wx * wx * o.x * o.x + wy * wy * o.y * o.y) / (o.z * o.z);
  const double g1 = 2.0 / (1.0 + std::sqrt(1.0 + a2t2));
  return g1 * d / (4.0 * o.z);
}

// A visible normal of the GGX shape at o, by stretching to w = 1 and drawing
// from the spherical cap (Dupuy & Benyoub 2023, Listing 3).
// sample_vis_v takes v_r = 1 - u_r (mfv run's albedo forms it without rounding).
namespace {
glm::dvec3 sample_vis_v(const glm::dvec3& o, double u_phi, double v_r, double wx, double wy) {
  const glm::dvec3 os = glm::normalize(glm::dvec3(wx * o.x, wy * o.y, o.z));
  const double phi = 2.0 * M_PI * u_phi;
  const double z = v_r * (1.0 + os.z) - os.z;
  const double st = std::sqrt(std::clamp(1.0 - z * z, 0.0, 1.0));
  const glm::dvec3 hs = glm::dvec3(st * std::cos(phi), st * std::sin(phi), z) + os;
  const glm::dvec3 h(wx * hs.x, wy * hs.y, hs.z);
  const double len = glm::length(h);
  return len > 0.0 ? h / len : glm::dvec3(0.0);
}
}  // namespace

glm::dvec3 sample_vis(const glm::dvec3& o, double u_phi, double u_r, double wx, double wy) {
  return sample_vis_v(o, u_phi, 1.0 - u_r, wx, wy);
}

glm::dvec3 sample_vis(const glm::dvec3& o, double u_phi, double u_r, double w) { return sample_vis(o, u_phi, u_r, w, w); }

MisPoint mis_point(const IntegralRef& s, uint64_t seed, uint64_t index) {
  const uint32_t n = s.points, k = uint32_t(index % n), n_def = n / 10, n_vis = n - 2 * n_def;
  const auto shift = philox(seed, s.stream, draw_word(s, 3), index / n);
  MisPoint p;
  p.vis = k < n_vis, p.cosine = k >= n_vis + n_def;
  const uint32_t j = p.vis ? k : p.cosine ? k - n_vis - n_def : k - n_vis;
  // scramble seeds (u_phi, u_r, the third dimension): words (0, 1, 2), (2, 3, 0), (3, 2, 1) by share
  const uint32_t a = p.vis ? 0 : p.cosine ? 3 : 2, b = p.vis ? 1 : p.cosine ? 2 : 3, c = p.vis ? 2 : p.cosine ? 1 : 0;
  owen_sobol_2d(j, shift[a], shift[b], p.u_phi, p.u_r);
  p.u_c = owen_sobol_dim3(j, shift[c]);
  return p;
}

namespace {

double energy_weight(const BrdfSpec& b, const glm::dvec3& m, const glm::dvec3& o, double w) {
  const glm::dvec3 i = 2.0 * glm::dot(o, m) * m - o;
  if (i.z <= 0.0) return 0.0;
  return spec_brdf(b, i, o) * i.z / vis_pdf_i(glm::normalize(i + o), o, w);
}

// Korobov's degree-3 periodizing transform (Sloan & Joe 1994, "Lattice
// Methods for Multiple Integration", §2.12) of the radial lattice
// coordinate: u_r = t²(3 - 2t), weight du_r/dt = 6t(1 - t). Twin of
// rqmc_radial in kernels/albedo.cl.
double rqmc_radial(double t, double& jac) {
  jac = 6.0 * t * (1.0 - t);
  return t * t * (3.0 - 2.0 * t);
}

// One point of AlbedoRqmc / EavgRqmc.
double albedo_rqmc(const IntegralRef& s, uint64_t seed, uint64_t index) {
  const auto shift = philox(seed, s.stream, draw_word(s, 2), 0);
  const uint32_t k = static_cast<uint32_t>(index);
  double jac;
  const double u_phi = u01_open(shift[0] + k * kRqmcG[0]), u_r = rqmc_radial(u01_open(shift[1] + k * kRqmcG[1]), jac);
  double cos_o = s.cos_o, jv = 1.0;
  if (s.kind == Integral::EavgRqmc) {  // density 2μ, μ² stratified over `strata` points, periodized as u_r
    const double u = u01_open(shift[2]) + double(k) / double(s.strata);
    cos_o = std::sqrt(rqmc_radial(u - std::floor(u), jv));
  }
  const glm::dvec3 o(std::sqrt(1.0 - cos_o * cos_o), 0.0, cos_o);
  const glm::dvec3 m = sample_vis(o, u_phi, u_r, s.width);
  return m.z > 0.0 ? energy_weight(s.brdf, m, o, s.width) * jac * jv : 0.0;
}

// mfv run's albedo (twin of albedo_mis_microfacet and albedo_mis_general in
// kernels/albedo.cl): point k of replicate r (index = r n + k, n = s.points
// = 5·2^(m-2)); the first 4n/5 points take o reflected about a visible
// normal of the GGX shape (scramble seeds: Philox draw 3 at counter r, words
// 0 and 1), the next n/10 a Cauchy slope (words 2, 3), the last n/10 the
// cosine lobe (words 3, 2), each on Owen-scrambled Sobol points from its own
// index 0 (the visible normals at the rim-dense 1 - u_r = (1 - t)^1.5); the
// shape and the slopes stretched to (width, width_y) where the spec has a
// second width, the view at its azimuth phi_o. Balance heuristic
// over the mixture c = (61/64, 1/64, 1/32) (Veach 1997 eq. 9.13), each point
// weighted c_t n / n_t: f cos / (Σ c_t p_t).
double albedo_mis(const IntegralRef& s, uint64_t seed, uint64_t index) {
  const MisPoint p = mis_point(s, seed, index);
  const bool vis = p.vis, cosine = p.cosine;
  const uint32_t n = s.points, n_def = n / 10, n_vis = n - 2 * n_def;
  const double u_phi = p.u_phi, u_r = p.u_r;
  const double wx = s.width, wy = s.width_y > 0 ? s.width_y : s.width;
  const double so = std::sqrt(1.0 - s.cos_o * s.cos_o);
  const glm::dvec3 o(so * std::cos(s.phi_o), so * std::sin(s.phi_o), s.cos_o);
  glm::dvec3 i;
  // the visible normals at 1 - u_r = (1 - t)^1.5, weight du_r/dt =
  // 1.5 (1 - t)^0.5, t the net's coordinate (rim-dense (a) in kernels/albedo.cl)
  const double jac = vis ? 1.5 * std::sqrt(1.0 - u_r) : 1.0;
  if (cosine) {
    const double st = std::sqrt(u_r), phi = 2.0 * M_PI * u_phi;
    i = {st * std::cos(phi), st * std::sin(phi), std::sqrt(1.0 - u_r)};
  } else {
    const glm::dvec3 m =
        vis ? sample_vis_v(o, u_phi, std::pow(1.0 - u_r, 1.5), wx, wy) : sample_m_aniso(1.0, u_phi, u_r, wx, wy);
    i = 2.0 * glm::dot(o, m) * m - o;
  }
  if (i.z <= 0.0) return 0.0;
  const glm::dvec3 h = glm::normalize(i + o);
  const double c_vis = 61.0 / 64.0, c_slope = 1.0 / 64.0, c_cos = 1.0 / 32.0;
  const double p_slope = pdf_slope_aniso(h, wx, wy) / (4.0 * glm::dot(o, h));
  const double q = c_vis * vis_pdf_i(h, o, wx, wy) + c_slope * p_slope + c_cos * i.z / M_PI;
  const double share = vis ? c_vis * n / n_vis : (cosine ? c_cos : c_slope) * n / n_def;
  return share * jac * spec_brdf(s.brdf, i, o) * i.z / q;
}

}  // namespace

// Twin of the pair draw in kernels/reciprocity.cl reciprocity_pair_c.
void reciprocity_pair(uint64_t seed, uint32_t stream, uint32_t stream_hi, uint32_t index, glm::dvec3& a,
                      glm::dvec3& b) {
  const auto r = philox(seed, stream, 1u | stream_hi << 8, index);
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

namespace {

// mfv convergence's estimators, written from the formulas (twin of
// convergence_value in kernels/integrate.cl, on the same uniforms).
glm::dvec3 direction_of(double c, double phi) {
  const double st = std::sqrt(std::max(0.0, (1.0 - c) * (1.0 + c)));
  return {st * std::cos(phi), st * std::sin(phi), c};
}

// D of the proposal's shape: GGX 1/(π w² cos⁴ (1 + tan²/w²)²), Beckmann
// exp(-tan²/w²)/(π w² cos⁴) (Walter et al. 2007 eq. 33, 28).
double shape_d(Estimator e, double c, double w) {
  const double t2 = (1.0 - c) * (1.0 + c) / (c * c), c4 = c * c * c * c;
  if (e == Estimator::DSampleBeckmann) return std::exp(-t2 / (w * w)) / (M_PI * w * w * c4);
  return 1.0 / (M_PI * w * w * c4 * (1.0 + t2 / (w * w)) * (1.0 + t2 / (w * w)));
}

double convergence_value(const IntegralRef& s, uint64_t seed, uint64_t index) {
  const auto est = static_cast<Estimator>(s.estimator);
  const double w = s.width;
  double u_phi, u_r;
  if (est == Estimator::Rqmc) {
    if (s.kind != Integral::DNorm) return albedo_rqmc(s, seed, index);
    const auto shift = philox(seed, s.stream, draw_word(s, 2), 0);
    const uint32_t k = static_cast<uint32_t>(index);
    u_phi = u01_open(shift[0] + k * kRqmcG[0]);
    u_r = u01_open(shift[1] + k * kRqmcG[1]);
  } else {
    const auto r = philox(seed, s.stream, draw_word(s, 0), index);
    u_phi = u01_open(r[2]);
    u_r = u01_open(r[3]);
  }
  const double phi = 2.0 * M_PI * u_phi;
  const BrdfSpec& b = s.brdf;
  if (s.kind == Integral::DNorm) {
    // uniform: pdf 1/(2π); cosine: pdf cos/π; RQMC: the Cauchy slopes alone.
    // Never D or visible-normal sampling: D c / (D c) = 1 by construction.
    if (est == Estimator::Uniform) return b.d->ref_d(u_r, b.pd) * u_r * 2.0 * M_PI;
    if (est == Estimator::Cosine) return b.d->ref_d(std::sqrt(1.0 - u_r), b.pd) * M_PI;
    if (est == Estimator::Rqmc) {
      double c, s2;
      sample_m(1.0, u_phi, u_r, w, c, s2);
      return eval_d_cs(b, c, s2) * c / pdf_slope(c, s2, w);
    }
    return std::nan("");
  }
  const glm::dvec3 o(std::sqrt(1.0 - s.cos_o * s.cos_o), 0.0, s.cos_o);
  if (est == Estimator::Uniform) {
    const glm::dvec3 i = direction_of(u_r, phi);
    return spec_brdf(b, i, o) * i.z * 2.0 * M_PI;
  }
  if (est == Estimator::Cosine) {
    const glm::dvec3 i = direction_of(std::sqrt(1.0 - u_r), phi);
    return i.z > 0.0 ? spec_brdf(b, i, o) * M_PI : 0.0;
  }
  if (est == Estimator::DSampleGgx || est == Estimator::DSampleBeckmann) {
    // inverse CDFs of the slope length: GGX tan² = w² u/(1-u) (eq. 35), Beckmann -w² log(1-u) (eq. 28)
    const double t2 = est == Estimator::DSampleBeckmann ? -w * w * std::log(1.0 - u_r) : w * w * u_r / (1.0 - u_r);
    const double c = 1.0 / std::sqrt(1.0 + t2);
    const glm::dvec3 h = direction_of(c, phi);
    const double oh = glm::dot(o, h);
    if (oh <= 0.0) return 0.0;
    const glm::dvec3 i = 2.0 * oh * h - o;
    if (i.z <= 0.0) return 0.0;
    return spec_brdf(b, i, o) * i.z / (shape_d(est, c, w) * c / (4.0 * oh));  // pdf_i = D_w (h·n) / (4 o·h)
  }
  if (est == Estimator::Vndf) {
    const glm::dvec3 m = sample_vis(o, u_phi, u_r, w);
    return m.z > 0.0 ? energy_weight(b, m, o, w) : 0.0;
  }
  return std::nan("");
}

}  // namespace

namespace {

// d_norm, masking and the iid albedo from Philox draw 0 (twin of iid_sample_value in kernels/integrate.cl).
double iid_sample_value(const IntegralRef& s, uint64_t seed, uint64_t index) {
  auto r = philox(seed, s.stream, draw_word(s, 0), index);
  const double u_branch = u01_open(r[0]), u_phi = u01_open(r[2]);
  double u_pick = u01_open(r[1]), u_r = u01_open(r[3]);
  const double w = s.width, wy = s.width_y;
  const BrdfSpec& b = s.brdf;
  const bool stretched = wy > 0;
  if (s.kind == Integral::DNorm) {
    // stratified radial uniform, as in the kernel: stratum `index` of `strata`
    // picks the component and, rescaled, drives it
    double u_phi_s = u_phi;
    if (s.strata > 0) {
      const uint64_t n_cos = s.strata / 4;
      const bool cosine = index < n_cos;
      const uint64_t k = cosine ? index : index - n_cos, n = cosine ? n_cos : s.strata - n_cos;
      u_pick = cosine ? 0.0 : 1.0;
      if (stretched) {
        // n_phi columns x n / n_phi rows of equal cells (twin of stratum_2d)
        uint64_t n_phi = 1;
        while (4 * n_phi * n_phi <= n && n % (2 * n_phi) == 0) n_phi *= 2;
        u_r = std::min((double(k / n_phi) + u_r) / double(n / n_phi), 1.0 - 0x1p-24);
        u_phi_s = (double(k % n_phi) + u_phi) / double(n_phi);
      } else {
        u_r = std::min((double(k) + u_r) / double(n), 1.0 - 0x1p-24);
      }
    }
    if (stretched) {
      const glm::dvec3 m = sample_m_aniso(u_pick, u_phi_s, u_r, w, wy);
      return eval_d(b, m) * m.z / pdf_m_aniso(m, w, wy);
    }
    double c, s2;
    sample_m(u_pick, u_phi, u_r, w, c, s2);
    return eval_d_cs(b, c, s2) * c / pdf_m(c, s2, w);
  }
  const double so = std::sqrt(1.0 - s.cos_o * s.cos_o);
  const glm::dvec3 o(so * std::cos(s.phi_o), so * std::sin(s.phi_o), s.cos_o);
  if (s.kind == Integral::Masking && stretched) {
    // Heitz 2014 eq. 19 with the view's own Smith G1(o), Λ at α(φ_o)
    const glm::dvec3 m = sample_m_aniso(u_pick, u_phi, u_r, w, wy);
    const double om = glm::dot(o, m);
    if (om <= 0.0) return 0.0;
    return eval_g1(b, o) * eval_d(b, m) * om / (pdf_m_aniso(m, w, wy) * s.cos_o);
  }
  if (s.kind == Integral::Masking) {
    // Heitz 2014 eq. 19 with G1(o,m) = G2(n, o, m)
    double c, s2;
    const glm::dvec3 m = sample_m(u_pick, u_phi, u_r, w, c, s2);
    const double om = glm::dot(o, m);
    if (om <= 0.0) return 0.0;
    const double g1 = b.g->ref_g(1.0, s.cos_o, c, om, b.pg);
    return g1 * eval_d_cs(b, c, s2) * om / (pdf_m(c, s2, w) * s.cos_o);
  }
  glm::dvec3 i;
  if (u_branch < kMixICos) {
    const double st = std::sqrt(u_r), phi = 2.0 * M_PI * u_phi;
    i = {st * std::cos(phi), st * std::sin(phi), std::sqrt(1.0 - u_r)};
  } else {
    double c, s2;
    const glm::dvec3 m =
        stretched ? sample_m_aniso(u_pick, u_phi, u_r, w, wy) : sample_m(u_pick, u_phi, u_r, w, c, s2);
    i = 2.0 * glm::dot(o, m) * m - o;
  }
  return albedo_weight(b, i, o, w, wy);
}

}  // namespace

// A closed dispatch (twin of sample_value in kernels/integrate.cl): no
// default, so that -Werror=switch refuses a kind without its case, and an id
// outside the enum (a planted one, tests/test_checks_complete.cpp) throws.
double sample_value(const IntegralRef& s, uint64_t seed, uint64_t index) {
  if (s.estimator != 0) return convergence_value(s, seed, index);
  switch (s.kind) {
    case Integral::DNorm:
    case Integral::Masking:
    case Integral::Albedo: return iid_sample_value(s, seed, index);
    case Integral::AlbedoRqmc:
    case Integral::EavgRqmc: return albedo_rqmc(s, seed, index);
    case Integral::AlbedoMis: return albedo_mis(s, seed, index);
    case Integral::BsdfFlux: return bsdf_flux(s, seed, index);
    case Integral::MaskingT: return masking_t(s, seed, index);
    case Integral::BsdfAvg: return bsdf_avg(s, seed, index);
  }
  throw Error(fmt::format("reference: check id {} has no integrand (ref::sample_value)", int(s.kind)));
}

}  // namespace mfv::ref
