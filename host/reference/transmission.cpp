// The transmission checks' estimators in double (twin of kernels/transmission.cl),
// on the same Philox uniforms, written from Walter et al. 2007 in the
// surface's own frame (absolute indices by side, no flip).
#include "abi/bsdf.h"
#include "reference/btdf.hpp"
#include "reference/estimators.hpp"
#include "reference/reference.hpp"
#include "rng/philox.hpp"

#include <glm/geometric.hpp>

#include <array>
#include <cmath>

namespace mfv::ref {

namespace {

constexpr double kBsdfCos = 0.1;      // each side's cosine lobe (BSDF_COS)
constexpr double kBsdfReflect = 0.4;  // reflected normals (BSDF_REFLECT); refracted: the rest
constexpr double kBsdfRefract = 1.0 - 2.0 * kBsdfCos - kBsdfReflect;

double d_at(const IntegralRef& s, const glm::dvec3& m) {
  if (m.z <= 0.0) return 0.0;
  const TermTwins& d = *s.brdf.d;
  return d.ref_d_cs ? d.ref_d_cs(m.z * m.z, m.x * m.x + m.y * m.y, s.brdf.pd) : d.ref_d(m.z, s.brdf.pd);
}

// Walter et al. 2007 eq. 20 with the exact dielectric F (seed 003's form) at
// the relative index seen from i, and the BTDF's G2 form.
double reflection(const IntegralRef& s, const glm::dvec3& i, const glm::dvec3& o) {
  if (i.z * o.z <= 0.0) return 0.0;
  const double up = i.z > 0.0 ? 1.0 : -1.0;
  const double eta_rel = i.z > 0.0 ? s.eta : 1.0 / s.eta;  // η_t / η_i
  glm::dvec3 h = glm::normalize(i + o) * up;               // on the normal's side
  const double ih = glm::dot(i, h) * up;
  const double g1i = s.brdf.g->ref_g1(std::fabs(i.z), s.brdf.pg), g1o = s.brdf.g->ref_g1(std::fabs(o.z), s.brdf.pg);
  const double F = F_dielectric(ih, eta_rel, 0.0);
  return F * btdf_g2(s.bsdf & 1, g1i, g1o) * d_at(s, h) / (4.0 * std::fabs(i.z) * std::fabs(o.z));
}

// The density of o under the proposal (twin of bsdf_proposal_pdf), in the
// surface's frame: η_i, η_o the absolute indices of i's and o's sides.
double proposal_pdf(const IntegralRef& s, const glm::dvec3& i, const glm::dvec3& o) {
  double p = kBsdfCos * std::fabs(o.z) / M_PI;
  const double up = i.z > 0.0 ? 1.0 : -1.0;
  // the mixture's normals about the normal on i's side: m_up = m mirrored to +z
  auto pdf_normal = [&](const glm::dvec3& m_side) {
    const glm::dvec3 m(m_side.x, m_side.y, m_side.z * up);
    return m.z > 0.0 ? pdf_m(m.z, m.x * m.x + m.y * m.y, s.width) : 0.0;
  };
  if (o.z * up > 0.0) {
    const glm::dvec3 h = glm::normalize(i + o);
    const double oh = glm::dot(o, h);
    if (oh > 0.0) p += kBsdfReflect * pdf_normal(h) / (4.0 * oh);
    return p;
  }
  const double eta_i = i.z > 0.0 ? 1.0 : s.eta, eta_o = o.z > 0.0 ? 1.0 : s.eta;
  glm::dvec3 h = -(eta_i * i + eta_o * o);  // Walter et al. 2007 eq. 16
  const double len = glm::length(h);
  if (!(len > 0.0)) return p;
  h /= len;
  if (h.z * up < 0.0) h = -h;  // on i's side
  const double ih = glm::dot(i, h), oh = glm::dot(o, h);
  if (ih > 0.0 && oh < 0.0) {
    const double den = eta_i * ih + eta_o * oh;
    p += kBsdfRefract * pdf_normal(h) * eta_o * eta_o * std::fabs(oh) / (den * den);  // eq. 17
  }
  return p;
}

// One sample of the flux from i at cos_i on `side` into `lobe`, from the uniforms r.
double flux_sample(const IntegralRef& s, const std::array<uint32_t, 4>& r, double cos_i, int side, uint32_t lobe) {
  const double u_branch = u01_open(r[0]), u_pick = u01_open(r[1]), u_phi = u01_open(r[2]), u_r = u01_open(r[3]);
  const double up = side == MFV_SIDE_BELOW ? -1.0 : 1.0;
  const glm::dvec3 i(std::sqrt((1.0 - cos_i) * (1.0 + cos_i)), 0.0, up * cos_i);
  const double eta_i = up > 0 ? 1.0 : s.eta, eta_t = up > 0 ? s.eta : 1.0;
  glm::dvec3 o;
  if (u_branch < 2.0 * kBsdfCos) {
    const double st = std::sqrt(u_r), phi = 2.0 * M_PI * u_phi;
    o = {st * std::cos(phi), st * std::sin(phi), std::sqrt(1.0 - u_r)};
    if (u_branch < kBsdfCos) o.z = -o.z;  // the lobe on the side away from the light above
    o.z *= up;
  } else {
    double c, s2;
    const glm::dvec3 mz = sample_m(u_pick, u_phi, u_r, s.width, c, s2);
    const glm::dvec3 m(mz.x, mz.y, mz.z * up);  // about the normal on i's side
    const double im = glm::dot(i, m);
    if (im <= 0.0) return 0.0;
    if (u_branch < 2.0 * kBsdfCos + kBsdfReflect) {
      o = 2.0 * im * m - i;  // eq. 39
      if (o.z * up <= 0.0) return 0.0;
    } else {
      // eq. 40 (its m faces n: -m when i is below), none under total internal reflection
      if (!refract(i, up * m, eta_i / eta_t, o) || o.z * up >= 0.0) return 0.0;
    }
  }
  const bool reflected = o.z * up > 0.0;
  if (lobe != MFV_LOBE_ALL && reflected != (lobe == MFV_LOBE_REFLECT)) return 0.0;
  const double p = proposal_pdf(s, i, o);
  if (!(p > 0.0)) return 0.0;
  BtdfSpec b;
  b.d = s.brdf.d;
  b.g = s.brdf.g;
  b.form = s.bsdf & 1;
  b.variant = s.bsdf >> 1;
  b.pd = s.brdf.pd;
  b.pg = s.brdf.pg;
  b.eta = s.eta;
  const double f = reflected ? reflection(s, i, o) : btdf(b, i, o);
  return f * std::fabs(o.z) / p;
}

}  // namespace

double bsdf_flux(const IntegralRef& s, uint64_t seed, uint64_t index) {
  return flux_sample(s, philox(seed, s.stream, draw_word(s, 0), index), s.cos_o, s.side, s.lobe);
}

double bsdf_avg(const IntegralRef& s, uint64_t seed, uint64_t index) {
  // Hemispherical averages T_avg = 2 ∫ E_T(μ) μ dμ of the light from below
  // (relative index 1/η) and from above (η), μ drawn with density 2μ for
  // each: generalized reciprocity (Walter et al. 2007 eq. 21's η_o²; Veach
  // 1997 §5.2) integrated over both directions gives T_avg(1/η) = T_avg(η)/η².
  const auto u = philox(seed, s.stream, draw_word(s, 2), index);
  const double mu_below = std::sqrt(u01_open(u[0])), mu_above = std::sqrt(u01_open(u[1]));
  const double leaving =
      flux_sample(s, philox(seed, s.stream, draw_word(s, 0), index), mu_below, MFV_SIDE_BELOW, MFV_LOBE_TRANSMIT);
  const double entering =
      flux_sample(s, philox(seed, s.stream, draw_word(s, 1), index), mu_above, MFV_SIDE_ABOVE, MFV_LOBE_TRANSMIT);
  return leaving - entering / (s.eta * s.eta);
}

double masking_t(const IntegralRef& s, uint64_t seed, uint64_t index) {
  // Heitz 2014 eq. 19 for o below: ∫ G1(o, m) max(0, -o·m) D(m) dm / |o·n| = 1,
  // G1 the Smith G1 at |o·n| with Walter et al. 2007 eq. 23's orientation test
  const auto r = philox(seed, s.stream, draw_word(s, 0), index);
  const double u_pick = u01_open(r[1]), u_phi = u01_open(r[2]), u_r = u01_open(r[3]);
  const glm::dvec3 o(std::sqrt((1.0 - s.cos_o) * (1.0 + s.cos_o)), 0.0, -s.cos_o);
  double c, s2;
  const glm::dvec3 m = sample_m(u_pick, u_phi, u_r, s.width, c, s2);
  const double om = glm::dot(o, m);
  if (om * o.z <= 0.0) return 0.0;  // χ+((o·m)/(o·n))
  return s.brdf.g->ref_g1(s.cos_o, s.brdf.pg) * d_at(s, m) * std::fabs(om) / (pdf_m(c, s2, s.width) * s.cos_o);
}

}  // namespace mfv::ref
