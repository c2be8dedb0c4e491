// Deterministic product rules over the hemisphere for integrands peaked at
// the normal (microfacet lobes down to alpha = 1e-3 and below): the truth
// mfv convergence measures errors against, and its quadrature estimator.
#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <functional>
#include <vector>

namespace mfv {

// Gauss-Legendre of `order` nodes on every panel. In t = 1 - cos θ the
// panels are geometric towards both ends of the range (the lobe's peak at
// t = 0 and, for reflected integrals, the cut where the light reaches the
// horizon), `per_decade` a decade down to 1e-12 of the range; in φ ∈ [0, π]
// (the integrands are symmetric about the plane of the view) `phi_panels`.
struct ProductRule {
  int order = 16;
  int per_decade = 4;
  int phi_panels = 8;
  double t_min = 1e-12;  // the geometric panels stop at t_min of the range (a lobe of alpha >= 0.01 needs 1e-7)
};

struct QuadratureResult {
  double value = 0;
  long evaluations = 0;  // integrand calls
};

// ∫ g(m) dω over the hemisphere of m (D normalization: g = D(m)(m·n)).
QuadratureResult integrate_normals(const std::function<double(const glm::dvec3& m)>& g, const ProductRule& rule);

// The nodes of integrate_normals's rule in its summation order: per φ node,
// `per_phi` t nodes. They do not depend on the integrand, so integrals over
// one rule can share them (checks/transmission_truth.cpp sweeps many views);
// summed as integrate_normals sums, Σ_j phi_weight[j] Σ_k weight[k] g(m[k]),
// they give its bits.
struct NormalNodes {
  size_t per_phi = 0;
  std::vector<double> phi_weight;  // the φ node's weight (times 2 for φ ∈ [π, 2π])
  std::vector<double> weight;      // the t node's weight
  std::vector<glm::dvec3> m;       // the normal
};
NormalNodes normal_nodes(const ProductRule& rule);

// ∫ f(i) dω_i over the upper hemisphere of light directions i, taken over
// half vectors h = (i + o)/|i + o| with dω_i = 4 (o·h) dω_h (Walter et al.
// 2007 eq. 14), so a BRDF lobe is resolved where D peaks. For each φ_h the
// range ends where i = reflect(o, h) reaches the horizon:
// co cos 2θ + so cos φ sin 2θ = 0, θ_c = (π/2 + atan2(so cos φ, co)) / 2,
// so no kink lies inside a panel. The view o must lie in the xz-plane.
QuadratureResult integrate_reflected(const std::function<double(const glm::dvec3& i)>& f, const glm::dvec3& o,
                                     const ProductRule& rule);

// The nodes of integrate_reflected's rule at the view o, in its summation
// order: per φ node, `per_phi` t nodes. Integrals at the same view and rule
// share them (checks/furnace_truth.cpp evaluates the BRDF's geometry once).
struct ReflectedNodes {
  size_t per_phi = 0;
  std::vector<double> phi_weight;  // the φ node's weight (times 2 for φ ∈ [π, 2π])
  std::vector<double> weight;      // the t node's weight
  std::vector<double> oh;          // o·h
  std::vector<glm::dvec3> i;       // the light direction reflect(o, h)
  std::vector<char> live;          // o·h > 0 and i above the horizon; elsewhere the integrand is 0
};
ReflectedNodes reflected_nodes(const glm::dvec3& o, const ProductRule& rule);

// ∫ f(i) dω_i as integrate_reflected sums it (the same bits), from f at the
// nodes (f_values[k] for node k; read only where live).
double sum_reflected(const ReflectedNodes& nodes, const std::vector<double>& f_values);

}  // namespace mfv
