#include "numeric/hemisphere_quadrature.hpp"

#include "numeric/quadrature.hpp"

#include <glm/geometric.hpp>

#include <cmath>
#include <vector>

namespace mfv {
namespace {

// Panel edges on [0, 1], geometric towards 0 and towards 1 (mirrored at 1/2).
std::vector<double> two_sided_edges(int per_decade, double t_min) {
  const std::vector<double> g = geometric_panels(t_min, per_decade);  // 0, t_min, ..., 1
  std::vector<double> e;
  for (double x : g) e.push_back(0.5 * x);
  for (size_t k = g.size() - 1; k-- > 0;) e.push_back(1.0 - 0.5 * g[k]);
  return e;
}

// ∫_0^π dφ ∫_0^{t_c(φ)} g(θ(t), φ) dt, times 2 for φ ∈ [π, 2π]; dω = dt dφ with t = 1 - cos θ.
template <class G, class Tc>
QuadratureResult product(const G& g, const Tc& t_c, const ProductRule& rule) {
  const GaussRule gl = gauss_legendre(rule.order);
  const std::vector<double> edges = two_sided_edges(rule.per_decade, rule.t_min);
  QuadratureResult r;
  const double hp = 0.5 * M_PI / rule.phi_panels;
  for (int b = 0; b < rule.phi_panels; ++b)
    for (int j = 0; j < rule.order; ++j) {
      const double phi = hp * (2 * b + 1 + gl.x[j]);
      const double tc = t_c(phi);
      double inner = 0;
      for (size_t a = 0; a + 1 < edges.size(); ++a) {
        const double t0 = tc * edges[a], ht = 0.5 * tc * (edges[a + 1] - edges[a]);
        for (int i = 0; i < rule.order; ++i) {
          const double t = t0 + ht * (gl.x[i] + 1.0);
          const double st = std::sqrt(t * (2.0 - t));  // sin θ from t without cancellation
          inner += gl.w[i] * ht * g(glm::dvec3(st * std::cos(phi), st * std::sin(phi), 1.0 - t));
          ++r.evaluations;
        }
      }
      r.value += 2.0 * gl.w[j] * hp * inner;
    }
  return r;
}

}  // namespace

QuadratureResult integrate_normals(const std::function<double(const glm::dvec3&)>& g, const ProductRule& rule) {
  return product(
      g, [](double) { return 1.0; }, rule);
}

QuadratureResult integrate_reflected(const std::function<double(const glm::dvec3&)>& f, const glm::dvec3& o,
                                     const ProductRule& rule) {
  const double co = o.z, so = o.x;
  auto t_c = [&](double phi) {
    const double theta_c = 0.5 * (0.5 * M_PI + std::atan2(so * std::cos(phi), co));
    return 2.0 * std::sin(0.5 * theta_c) * std::sin(0.5 * theta_c);  // 1 - cos θ_c without cancellation
  };
  auto g = [&](const glm::dvec3& h) {
    const double oh = glm::dot(o, h);
    if (oh <= 0.0) return 0.0;
    const glm::dvec3 i = 2.0 * oh * h - o;
    return i.z > 0.0 ? f(i) * 4.0 * oh : 0.0;
  };
  return product(g, t_c, rule);
}

}  // namespace mfv
