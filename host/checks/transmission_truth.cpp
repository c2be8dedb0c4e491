#include "checks/transmission_truth.hpp"

#include "reference/reference.hpp"

#include <glm/geometric.hpp>

#include <cmath>

namespace mfv {

BsdfFlux bsdf_flux_truth(const ref::BtdfSpec& s, double cos_i, bool from_below, const ProductRule& rule) {
  // Light from below is light from above with the surface turned over: the
  // relative index becomes 1/eta (one flip, as kernels/btdf.cl).
  const double eta = from_below ? 1.0 / s.eta : s.eta;
  const glm::dvec3 i(std::sqrt((1.0 - cos_i) * (1.0 + cos_i)), 0.0, cos_i);
  auto d_of = [&](const glm::dvec3& m) {
    if (s.d->ref_d_cs) return s.d->ref_d_cs(m.z * m.z, m.x * m.x + m.y * m.y, s.pd);
    return s.d->ref_d(m.z, s.pd);
  };
  auto g1 = [&](const glm::dvec3& v) { return s.g->ref_g1(std::fabs(v.z), s.pg); };
  auto facet = [&](const glm::dvec3& m, bool transmitted) {
    const double im = glm::dot(i, m);
    if (im <= 0.0) return 0.0;  // the facet faces away from i: χ+(i·m / i·n)
    const double F = ref::F_dielectric(im, eta, 0.0);
    double share = 0.0;
    glm::dvec3 o;
    if (!transmitted) {
      o = 2.0 * im * m - i;  // the mirror direction (Walter et al. 2007 eq. 39)
      if (o.z <= 0.0) return 0.0;
      share = F;
    } else {
      if (!ref::refract(i, m, 1.0 / eta, o) || o.z >= 0.0) return 0.0;  // TIR cut, or refracted upwards: lost
      share = 1.0 - F;
    }
    // the same G2 form masks the reflected and the refracted direction
    return share * ref::btdf_g2(s.form, g1(i), g1(o)) * d_of(m) * im / i.z;
  };
  BsdfFlux r;
  r.reflected = integrate_normals([&](const glm::dvec3& m) { return facet(m, false); }, rule).value;
  r.transmitted = integrate_normals([&](const glm::dvec3& m) { return facet(m, true); }, rule).value;
  return r;
}

}  // namespace mfv
