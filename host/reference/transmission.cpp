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

// The BSDF under test at (i, o) in the surface's frame: the reflection lobe
// where o lies on i's side, the BTDF (MFV_BTDF_CODE s.bsdf) on the other.
double bsdf_value(const IntegralRef& s, const glm::dvec3& i, const glm::dvec3& o) {
  if (i.z * o.z > 0.0) return reflection(s, i, o);
  BtdfSpec b;
  b.d = s.brdf.d;
  b.g = s.brdf.g;
  b.form = s.bsdf & 1;
  b.variant = s.bsdf >> 1;
  b.pd = s.brdf.pd;
  b.pg = s.brdf.pg;
  b.eta = s.eta;
  return btdf(b, i, o);
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
  return bsdf_value(s, i, o) * std::fabs(o.z) / p;
}

// The exact dielectric Fresnel in Snell's form (Born & Wolf; twin of the
// estimator's flux_fresnel, not of the BSDF's): c = cos of incidence on the
// facet, eta = η_t / η_i; 1 under total internal reflection.
double fresnel_snell(double c, double eta) {
  const double sin_t2 = (1.0 - c * c) / (eta * eta);
  if (sin_t2 >= 1.0) return 1.0;
  const double ct = std::sqrt(1.0 - sin_t2);
  const double rs = (c - eta * ct) / (c + eta * ct), rp = (eta * c - ct) / (eta * c + ct);
  return 0.5 * (rs * rs + rp * rp);
}

// GGX of width w as a shape (Walter et al. 2007 eq. 33) and its Smith G1
// (eq. 34): the visible normals' density G1(i) max(0, i·h) D(h) / (i·n)
// (Heitz 2018 eq. 3), in the frame where i is above.
double visible_normal_pdf(const glm::dvec3& h, const glm::dvec3& i, double w) {
  const double ih = glm::dot(i, h);
  if (h.z <= 0.0 || ih <= 0.0) return 0.0;
  const double c2 = h.z * h.z, t2 = (h.x * h.x + h.y * h.y) / c2, w2 = w * w;
  const double d = 1.0 / (M_PI * w2 * c2 * c2 * (1.0 + t2 / w2) * (1.0 + t2 / w2));
  const double ti2 = (i.x * i.x + i.y * i.y) / (i.z * i.z);
  const double g1 = 2.0 / (1.0 + std::sqrt(1.0 + w2 * ti2));
  return g1 * ih * d / i.z;
}

}  // namespace

// The chance of the reflected side at a facet with i·m = cm, by share (as
// flux_p_reflect): the visible normals reflect with fresnel_snell, the
// defensive pair with 1/2, where the integral takes both lobes.
double flux_reflect_chance(uint32_t lobe, bool visible, double cm, double eta) {
  if (lobe == MFV_LOBE_REFLECT) return 1.0;
  if (lobe == MFV_LOBE_TRANSMIT) return 0.0;
  return visible ? fresnel_snell(cm, eta) : 0.5;
}

bool flux_mis_direction(bool vis, bool cosine, double u_phi, double u_r, double u_c, const glm::dvec3& i, double w,
                        double eta, uint32_t lobe, glm::dvec3& o) {
  if (cosine) {
    const double st = std::sqrt(u_r), phi = 2.0 * M_PI * u_phi;
    o = {st * std::cos(phi), st * std::sin(phi), std::sqrt(1.0 - u_r)};
    if (!(u_c < flux_reflect_chance(lobe, false, 1.0, eta))) o.z = -o.z;
    return true;
  }
  double cm, s2;
  const glm::dvec3 m = vis ? sample_vis(i, u_phi, u_r, w) : sample_m(1.0, u_phi, u_r, w, cm, s2);
  const double im = glm::dot(i, m);
  if (!(im > 0.0)) return false;
  if (u_c < flux_reflect_chance(lobe, vis, im, eta)) {
    o = 2.0 * im * m - i;  // eq. 39
    return o.z > 0.0;
  }
  return refract(i, m, 1.0 / eta, o) && o.z < 0.0;  // eq. 40; none under total internal reflection
}

double flux_mis_pdf(const glm::dvec3& i, const glm::dvec3& o, double w, double eta, uint32_t lobe) {
  // the mixture's density of o: c = (15/16, 1/32, 1/32), each share times its chance of o's side
  const double c_vis = 15.0 / 16.0, c_def = 1.0 / 32.0;
  double q;
  if (o.z > 0.0) {
    const glm::dvec3 h = glm::normalize(i + o);
    const double ih = glm::dot(i, h), chance = flux_reflect_chance(lobe, false, ih, eta);
    q = c_vis * flux_reflect_chance(lobe, true, ih, eta) * visible_normal_pdf(h, i, w) / (4.0 * ih) +
        c_def * chance * pdf_slope(h.z, h.x * h.x + h.y * h.y, w) / (4.0 * glm::dot(o, h)) + c_def * chance * o.z / M_PI;
  } else {
    q = c_def * (1.0 - flux_reflect_chance(lobe, false, 1.0, eta)) * -o.z / M_PI;
    glm::dvec3 h = -(i + eta * o);  // eq. 16 with η_i = 1, η_o = eta
    const double len = glm::length(h);
    if (len > 0.0) {
      h /= len;
      if (h.z < 0.0) h = -h;
      const double ih = glm::dot(i, h), oh = glm::dot(o, h);
      if (ih > 0.0 && oh < 0.0) {
        const double jac = eta * eta * -oh / ((ih + eta * oh) * (ih + eta * oh));  // eq. 17
        q += (c_vis * (1.0 - flux_reflect_chance(lobe, true, ih, eta)) * visible_normal_pdf(h, i, w) +
              c_def * (1.0 - flux_reflect_chance(lobe, false, ih, eta)) * pdf_slope(h.z, h.x * h.x + h.y * h.y, w)) *
             jac;
      }
    }
  }
  return q;
}

namespace {

// bsdf_furnace's flux (twin of bsdf_flux_mis in kernels/transmission.cl):
// point k of replicate r (index = r n + k, n = s.points), the shares and
// scramble seeds of albedo_mis above (4n/5 visible normals at i, n/10 Cauchy
// slopes, n/10 cosine lobe; Philox draw 3 at counter r) and Sobol's third
// dimension (scrambled by words 2, 0, 1 of the shares) that picks the side where the
// integral takes both lobes: the visible normals reflect with the chance
// fresnel_snell, the defensive pair with 1/2. Written in the frame where i
// is above (relative index seen from i), o mirrored back for the BSDF.
double flux_mis(const IntegralRef& s, uint64_t seed, uint64_t index) {
  const MisPoint p = mis_point(s, seed, index);
  const bool vis = p.vis, cosine = p.cosine;
  const uint32_t n = s.points, n_def = n / 10, n_vis = n - 2 * n_def;
  const bool below = s.side == MFV_SIDE_BELOW;
  const double eta = below ? 1.0 / s.eta : s.eta, w = s.width;
  const glm::dvec3 i(std::sqrt((1.0 - s.cos_o) * (1.0 + s.cos_o)), 0.0, s.cos_o);
  glm::dvec3 o;
  if (!flux_mis_direction(vis, cosine, p.u_phi, p.u_r, p.u_c, i, w, eta, s.lobe, o)) return 0.0;
  const double q = flux_mis_pdf(i, o, w, eta, s.lobe);
  if (!(q > 0.0)) return 0.0;
  // the BSDF in the surface's frame: i and o mirrored when the light comes from below
  const double up = below ? -1.0 : 1.0;
  const glm::dvec3 is(i.x, i.y, up * i.z), os(o.x, o.y, up * o.z);
  const double f = bsdf_value(s, is, os);
  const double c_vis = 15.0 / 16.0, c_def = 1.0 / 32.0;
  const double share = vis ? c_vis * n / n_vis : c_def * n / n_def;
  return share * f * std::fabs(o.z) / q;
}

}  // namespace

double bsdf_flux(const IntegralRef& s, uint64_t seed, uint64_t index) { return flux_mis(s, seed, index); }

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
