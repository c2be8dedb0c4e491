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

// Every node of the product rule in summation order: node(h, w) for the
// direction h and weight w of each t node, then phi_end(W) with the weight W
// of the φ node they belong to (times 2 for φ ∈ [π, 2π]). dω = dt dφ with
// t = 1 - cos θ, t ∈ [0, t_c(φ)], φ ∈ [0, π].
template <class Tc, class Node, class PhiEnd>
void visit_nodes(const Tc& t_c, const ProductRule& rule, Node node, PhiEnd phi_end) {
  const GaussRule gl = gauss_legendre(rule.order);
  const std::vector<double> edges = two_sided_edges(rule.per_decade, rule.t_min);
  const double hp = 0.5 * M_PI / rule.phi_panels;
  for (int b = 0; b < rule.phi_panels; ++b)
    for (int j = 0; j < rule.order; ++j) {
      const double phi = hp * (2 * b + 1 + gl.x[j]);
      const double tc = t_c(phi), cos_phi = std::cos(phi), sin_phi = std::sin(phi);  // once per φ node
      for (size_t a = 0; a + 1 < edges.size(); ++a) {
        const double t0 = tc * edges[a], ht = 0.5 * tc * (edges[a + 1] - edges[a]);
        for (int i = 0; i < rule.order; ++i) {
          const double t = t0 + ht * (gl.x[i] + 1.0);
          const double st = std::sqrt(t * (2.0 - t));  // sin θ from t without cancellation
          node(glm::dvec3(st * cos_phi, st * sin_phi, 1.0 - t), gl.w[i] * ht);
        }
      }
      phi_end(2.0 * gl.w[j] * hp);
    }
}

// ∫_0^π dφ ∫_0^{t_c(φ)} g(θ(t), φ) dt, times 2 for φ ∈ [π, 2π].
template <class G, class Tc>
QuadratureResult product(const G& g, const Tc& t_c, const ProductRule& rule) {
  QuadratureResult r;
  double inner = 0;
  visit_nodes(
      t_c, rule,
      [&](const glm::dvec3& h, double w) {
        inner += w * g(h);
        ++r.evaluations;
      },
      [&](double phi_weight) {
        r.value += phi_weight * inner;
        inner = 0;
      });
  return r;
}

// 1 - cos θ_c where i = reflect(o, h) reaches the horizon at φ (integrate_reflected).
double horizon_cut(const glm::dvec3& o, double phi) {
  const double theta_c = 0.5 * (0.5 * M_PI + std::atan2(o.x * std::cos(phi), o.z));
  return 2.0 * std::sin(0.5 * theta_c) * std::sin(0.5 * theta_c);  // 1 - cos θ_c without cancellation
}

}  // namespace

QuadratureResult integrate_normals(const std::function<double(const glm::dvec3&)>& g, const ProductRule& rule) {
  return product(
      g, [](double) { return 1.0; }, rule);
}

NormalNodes normal_nodes(const ProductRule& rule) {
  NormalNodes n;
  visit_nodes([](double) { return 1.0; }, rule,
              [&](const glm::dvec3& m, double w) {
                n.weight.push_back(w);
                n.m.push_back(m);
              },
              [&](double phi_weight) {
                if (n.phi_weight.empty()) n.per_phi = n.weight.size();
                n.phi_weight.push_back(phi_weight);
              });
  return n;
}

ReflectedNodes reflected_nodes(const glm::dvec3& o, const ProductRule& rule) {
  ReflectedNodes n;
  visit_nodes([&](double phi) { return horizon_cut(o, phi); }, rule,
              [&](const glm::dvec3& h, double w) {
                const double oh = glm::dot(o, h);
                const glm::dvec3 i = 2.0 * oh * h - o;
                n.weight.push_back(w);
                n.oh.push_back(oh);
                n.i.push_back(i);
                n.live.push_back(oh > 0.0 && i.z > 0.0);
              },
              [&](double phi_weight) {
                if (n.phi_weight.empty()) n.per_phi = n.weight.size();
                n.phi_weight.push_back(phi_weight);
              });
  return n;
}

double sum_reflected(const ReflectedNodes& n, const std::vector<double>& f_values) {
  double value = 0;
  for (size_t j = 0, k = 0; j < n.phi_weight.size(); ++j) {
    double inner = 0;
    for (size_t end = k + n.per_phi; k < end; ++k)
      inner += n.weight[k] * (n.live[k] ? f_values[k] * 4.0 * n.oh[k] : 0.0);  // dω_i = 4 (o·h) dω_h
    value += n.phi_weight[j] * inner;
  }
  return value;
}

QuadratureResult integrate_reflected(const std::function<double(const glm::dvec3&)>& f, const glm::dvec3& o,
                                     const ProductRule& rule) {
  const ReflectedNodes n = reflected_nodes(o, rule);
  std::vector<double> values(n.i.size(), 0.0);
  for (size_t k = 0; k < values.size(); ++k)
    if (n.live[k]) values[k] = f(n.i[k]);
  return {sum_reflected(n, values), long(values.size())};
}

}  // namespace mfv
