// The furnace truth's shared-node quadrature (furnace_truth.hpp,
// albedos_by_quadrature): the integrals at one view share the rule's nodes,
// the shading at them and each term's values.
#pragma once

#include "numeric/hemisphere_quadrature.hpp"
#include "reference/brdf.hpp"

#include <glm/vec3.hpp>

#include <vector>

namespace mfv {

// ∫ f(i, o) (n·i) di of each isotropic D x G x F of `brdfs` (no model, no
// second width) at the view o above the horizon by `rule`: for each, the
// bits of integrate_reflected(ref::brdf(s, i, o) * i.z, o, rule).
std::vector<double> albedos_at_view(const glm::dvec3& o, const ProductRule& rule,
                                    const std::vector<ref::BrdfSpec>& brdfs);

}  // namespace mfv
