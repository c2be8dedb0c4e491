// The furnace truth of a rough dielectric BSDF (flux form): E_R and E_T of
// the power arriving from one direction, by quadrature over the microfacet
// normals, with the refracted-side rule and the total-internal-reflection cut.
#pragma once

#include "numeric/hemisphere_quadrature.hpp"
#include "reference/btdf.hpp"

namespace mfv {

struct BsdfFlux {
  double reflected = 0, transmitted = 0;  // E_R, E_T
  double loss() const { return 1.0 - reflected - transmitted; }
};

// E_R(i) and E_T(i) for light arriving from the direction at cosine cos_i in
// the xz-plane, from above (from_below = false: index 1 -> s.eta) or from
// below (s.eta -> 1). Over the facets m (Walter et al. 2007 eq. 38-41): a
// facet reflects F(i·m) and refracts 1 - F(i·m) of the power D(m) G1(i, m)
// (i·m)/(i·n) it receives, the outgoing direction then masked by G2/G1(i);
// the refracted direction is Walter's eq. 40, none under total internal
// reflection (F = 1 there), and a reflected or refracted direction on the
// wrong side of the surface is lost (the single-scattering model's loss).
BsdfFlux bsdf_flux_truth(const ref::BtdfSpec& s, double cos_i, bool from_below, const ProductRule& rule);

// bsdf_flux_truth's view-independent part at one BSDF (D, G, form, widths;
// s.eta is not read) and one rule: the rule's nodes and D at each, computed
// once for every view, index and side (the suite sweeps 96 of them per BSDF
// and width). flux() walks the nodes once for E_R and E_T together and gives
// bsdf_flux_truth's bits (the same terms summed in the same order).
class BsdfFluxQuadrature {
 public:
  BsdfFluxQuadrature(const ref::BtdfSpec& s, const ProductRule& rule);
  BsdfFlux flux(double cos_i, bool from_below, double eta) const;  // eta: as BtdfSpec::eta

 private:
  ref::BtdfSpec s_;
  NormalNodes nodes_;
  std::vector<double> d_;  // D(m) at each node
};

}  // namespace mfv
