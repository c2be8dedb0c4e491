#include "checks/transmission_truth.hpp"

#include "reference/reference.hpp"

#include <glm/geometric.hpp>

#include <cmath>

namespace mfv {

BsdfFluxQuadrature::BsdfFluxQuadrature(const ref::BtdfSpec& s, const ProductRule& rule)
    : s_(s), nodes_(normal_nodes(rule)) {
  d_.reserve(nodes_.m.size());
  for (const glm::dvec3& m : nodes_.m)
    d_.push_back(s.d->ref_d_cs ? s.d->ref_d_cs(m.z * m.z, m.x * m.x + m.y * m.y, s.pd) : s.d->ref_d(m.z, s.pd));
}

BsdfFlux BsdfFluxQuadrature::flux(double cos_i, bool from_below, double eta_spec) const {
  // Light from below is light from above with the surface turned over: the
  // relative index becomes 1/eta (one flip, as kernels/btdf.cl).
  const double eta = from_below ? 1.0 / eta_spec : eta_spec;
  const glm::dvec3 i(std::sqrt((1.0 - cos_i) * (1.0 + cos_i)), 0.0, cos_i);
  auto g1 = [&](const glm::dvec3& v) { return s_.g->ref_g1(std::fabs(v.z), s_.pg); };
  const double g1i = g1(i);
  BsdfFlux r;
  // integrate_normals's sum (numeric/hemisphere_quadrature.cpp), for the two
  // lobes at once: per φ node the inner sum over t, then its weight
  for (size_t j = 0, k = 0; j < nodes_.phi_weight.size(); ++j) {
    double inner_r = 0, inner_t = 0;
    for (size_t end = k + nodes_.per_phi; k < end; ++k) {
      const glm::dvec3& m = nodes_.m[k];
      const double im = glm::dot(i, m), d = d_[k];
      // The facet faces away from i (χ+(i·m / i·n)), or D is 0 there (a sharp
      // lobe's far nodes): both terms are +0 (every factor is finite and
      // >= 0), which leaves the sums' bits as they are.
      if (im <= 0.0 || d == 0.0) continue;
      // A facet reflects F(i·m) and refracts 1 - F(i·m) of what it receives,
      // D(m) (i·m)/(i·n); the same G2 form masks the reflected and the
      // refracted direction.
      const double F = ref::F_dielectric(im, eta, 0.0), w = nodes_.weight[k];
      const glm::dvec3 o = 2.0 * im * m - i;  // the mirror direction (Walter et al. 2007 eq. 39)
      if (o.z > 0.0) inner_r += w * (F * ref::btdf_g2(s_.form, g1i, g1(o)) * d * im / i.z);
      glm::dvec3 t;  // none under total internal reflection; refracted upwards: lost
      if (ref::refract(i, m, 1.0 / eta, t) && t.z < 0.0)
        inner_t += w * ((1.0 - F) * ref::btdf_g2(s_.form, g1i, g1(t)) * d * im / i.z);
    }
    r.reflected += nodes_.phi_weight[j] * inner_r;
    r.transmitted += nodes_.phi_weight[j] * inner_t;
  }
  return r;
}

BsdfFlux bsdf_flux_truth(const ref::BtdfSpec& s, double cos_i, bool from_below, const ProductRule& rule) {
  return BsdfFluxQuadrature(s, rule).flux(cos_i, from_below, s.eta);
}

}  // namespace mfv
