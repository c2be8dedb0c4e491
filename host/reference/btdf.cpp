// Reference rough dielectric BTDF (Walter et al. 2007 §3-5), in double.
#include "reference/btdf.hpp"

#include "abi/bsdf.h"
#include "reference/reference.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace mfv::ref {

namespace {

// The indices on each side: the medium above the surface has index 1, the
// one below has eta.
double index_of(const glm::dvec3& w, double eta) { return w.z > 0.0 ? 1.0 : eta; }

// Walter et al. 2007 eq. 23: G1(v, m) = χ+((v·m)/(v·n)) G1_smith(v), the
// Smith part of the catalog's G at |v·n|. The planted same-side variant
// drops the χ+ test.
double g1_oriented(const BtdfSpec& s, const glm::dvec3& v, const glm::dvec3& m) {
  if (s.variant != MFV_BTDF_BAD_SAME_SIDE && glm::dot(v, m) * v.z <= 0.0) return 0.0;
  return s.g->ref_g1(std::fabs(v.z), s.pg);
}

// 1 - F (seed 003's Snell form, as ref::F_dielectric): F = (r_perp² + r_par²)/2,
// and 1 - r² = (1 - r)(1 + r) with each factor in closed form
// (1 ± r_perp = 2 {η cosθt, cosθi} / (cosθi + η cosθt), 1 ± r_par likewise),
// so that 1 - F keeps its digits where F -> 1 (grazing, the critical angle).
//
// g2_slack != 0: g² = η² cos²θt known only to ±|g2_slack| (see BtdfSpec).
// With g = η cosθt, 1 - r_perp² = 4 c g / (c + g)² rises with g up to g = c
// and 1 - r_par² = 4 η² c g / (η² c + g)² up to g = η² c, then both fall:
// each half is unimodal in g, so over [g_lo, g_hi] its largest value is at
// its peak clamped into the interval and its smallest at an end. The sum of
// the halves' largest (smallest) values bounds 1 - F from above (below). The
// p half's peak lies inside the rounding interval near the critical angle of
// a small η (η² c ~ 1e-4 at η = 0.01), where the interval's ends miss it.
double transmittance(double cos_i, double eta, double g2_slack = 0.0) {
  if (cos_i <= 0.0) return 0.0;
  const double eta2_cos2_t = (eta - 1.0) * (eta + 1.0) + cos_i * cos_i;
  if (g2_slack != 0.0) {
    const double hi2 = eta2_cos2_t + std::fabs(g2_slack);
    if (hi2 <= 0.0) return 0.0;  // total internal reflection all over the interval
    const double lo = std::sqrt(std::max(0.0, eta2_cos2_t - std::fabs(g2_slack))), hi = std::sqrt(hi2);
    const double c = cos_i, e2c = eta * eta * c;
    const auto t_perp = [&](double g) { return 4.0 * c * g / ((c + g) * (c + g)); };
    const auto t_par = [&](double g) { return 4.0 * e2c * g / ((e2c + g) * (e2c + g)); };
    if (g2_slack > 0.0)
      return 0.5 * (t_perp(std::clamp(c, lo, hi)) + t_par(std::clamp(e2c, lo, hi)));
    return 0.5 * (std::min(t_perp(lo), t_perp(hi)) + std::min(t_par(lo), t_par(hi)));
  }
  if (eta2_cos2_t <= 0.0) return 0.0;  // total internal reflection
  const double eta_cos_t = std::sqrt(eta2_cos2_t), cos_t = eta_cos_t / eta;
  const double perp = (2.0 * eta_cos_t / (cos_i + eta_cos_t)) * (2.0 * cos_i / (cos_i + eta_cos_t));
  const double par = (2.0 * cos_t / (eta * cos_i + cos_t)) * (2.0 * eta * cos_i / (eta * cos_i + cos_t));
  return 0.5 * (perp + par);
}

double d_of(const BtdfSpec& s, const glm::dvec3& m) {
  if (m.z <= 0.0) return 0.0;  // χ+(m·n)
  if (s.h_tilt != 0.0) {
    const double sn = std::max(0.0, std::sqrt(m.x * m.x + m.y * m.y) + s.h_tilt), sn2 = std::min(sn * sn, 1.0);
    return s.d->ref_d_cs ? s.d->ref_d_cs(1.0 - sn2, sn2, s.pd) : s.d->ref_d(std::sqrt(1.0 - sn2), s.pd);
  }
  if (s.d->ref_d_cs) return s.d->ref_d_cs(m.z * m.z, m.x * m.x + m.y * m.y, s.pd);
  return s.d->ref_d(m.z, s.pd);
}

}  // namespace

double btdf_g2(int form, double g1i, double g1o) {
  if (form == MFV_BTDF_SEPARABLE) return g1i * g1o;  // Walter et al. 2007 eq. 23
  if (!(g1i > 0.0 && g1o > 0.0)) return 0.0;
  // height-correlated Smith: 1 / (1 + Λ(i) + Λ(o)), Λ = 1/G1 - 1 (Heitz 2014 eq. 99)
  return 1.0 / (1.0 + (1.0 / g1i - 1.0) + (1.0 / g1o - 1.0));
}

glm::dvec3 half_vector_t(const glm::dvec3& i, const glm::dvec3& o, double eta) {
  // Walter et al. 2007 eq. 16: h_t = -(η_i i + η_o o) / |η_i i + η_o o|
  glm::dvec3 h = -(index_of(i, eta) * i + index_of(o, eta) * o);
  const double len = glm::length(h);
  if (!(len > 0.0)) return glm::dvec3(0.0);
  h /= len;
  return h.z < 0.0 ? -h : h;  // the microfacet normal faces n
}

bool refract(const glm::dvec3& i, const glm::dvec3& m, double r, glm::dvec3& t) {
  // Walter et al. 2007 eq. 40: t = (r c - sign(i·n) sqrt(1 + r² (c² - 1))) m - r i, c = i·m, r = η_i/η_o
  const double c = glm::dot(i, m);
  const double k = 1.0 + r * r * (c * c - 1.0);
  if (k < 0.0) return false;  // total internal reflection
  const double sign = i.z >= 0.0 ? 1.0 : -1.0;
  t = (r * c - sign * std::sqrt(k)) * m - r * i;
  return true;
}

double btdf(const BtdfSpec& s, const glm::dvec3& i, const glm::dvec3& o) {
  // Walter et al. 2007 eq. 21:
  //   f_t = |i·h_t| |o·h_t| / (|i·n| |o·n|) η_o² (1 - F(i, h_t)) G(i, o, h_t) D(h_t) / (η_i (i·h_t) + η_o (o·h_t))²
  if (i.z * o.z >= 0.0) return 0.0;  // both on one side (or grazing): reflection, not transmission
  const double eta_i = index_of(i, s.eta), eta_o = index_of(o, s.eta);
  const glm::dvec3 h = half_vector_t(i, o, s.eta);
  if (h.z <= 0.0) return 0.0;  // degenerate (η_i i + η_o o = 0) or h in the surface: D = 0
  const double ih = glm::dot(i, h), oh = glm::dot(o, h);
  // Refraction puts i and o on opposite sides of the facet; a pair with
  // (i·h)(o·h) >= 0 is no refraction through h (the χ+ of G1 says the same).
  if (s.variant != MFV_BTDF_BAD_SAME_SIDE && ih * oh >= 0.0) return 0.0;
  const double G = btdf_g2(s.form, g1_oriented(s, i, h), g1_oriented(s, o, h));
  // Fresnel at the facet, from i's side into o's: relative index η = η_o/η_i
  const double eta = eta_o / eta_i;
  const double T = transmittance(
      std::min(1.0, std::fabs(s.variant == MFV_BTDF_BAD_F_AT_N ? i.z : ih) * (1.0 + s.f_cos_bump)), eta, s.g2_slack);
  // eq. 21 is homogeneous of degree 0 in (η_i, η_o): divided through by η_i²,
  // η_o² / (η_i i·h + η_o o·h)² = η² / (i·h + η o·h)². The planted variants
  // are the bugs in this relative form.
  const double jac = s.variant == MFV_BTDF_BAD_JACOBIAN ? (ih + oh) * (ih + oh) : (ih + eta * oh) * (ih + eta * oh);
  const double num = s.variant == MFV_BTDF_BAD_NO_ETA2 ? 1.0 : eta * eta;
  return std::fabs(ih) * std::fabs(oh) / (std::fabs(i.z) * std::fabs(o.z)) * num * T * G * d_of(s, h) / jac;
}

}  // namespace mfv::ref
