// Helpers shared by the tests of the scalar reference terms
// (test_reference_terms.cpp: D and F; test_reference_terms_g.cpp: Λ, G1, G2):
// quadrature, directions, independent closed forms and the terms' lists.
#pragma once

#include <catch2/catch.hpp>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "reference/reference.hpp"
#include "util/math_constants.hpp"

namespace reference_terms_test {

namespace ref = mfv::ref;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using Catch::Matchers::WithinULP;

using mfv::kPi;
inline const double kDenormMin = std::numeric_limits<double>::denorm_min();
inline const double kAboveOne = std::nextafter(1.0, 2.0);  // 1 + 2^-52
inline const double kBelowOne = std::nextafter(1.0, 0.0);  // 1 - 2^-53
inline constexpr double kEps = std::numeric_limits<double>::epsilon();

using Scalar2 = double (*)(double, double);
using Term3 = double (*)(double, double, double);
using G2Fn = double (*)(double, double, double, double, double);

struct Named1 {  // a D, Λ or G1 with one parameter value
  std::string name;
  Scalar2 fn;
  double param;
  double width;  // angular width in θ (radians), for the quadrature's grading
};

struct NamedG2 {
  std::string name;
  G2Fn fn;
  double param;
};

// ---- quadrature -----------------------------------------------------------
// Adaptive Simpson on [a, b] with Richardson correction; deterministic.
inline double simpson_step(const std::function<double(double)>& f, double a, double b, double fa, double fm, double fb,
                           double whole, double eps, int depth) {
  const double m = 0.5 * (a + b);
  const double lm = 0.5 * (a + m);
  const double rm = 0.5 * (m + b);
  const double flm = f(lm);
  const double frm = f(rm);
  const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
  const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
  const double delta = left + right - whole;
  if (depth <= 0 || std::fabs(delta) <= 15.0 * eps) return left + right + delta / 15.0;
  return simpson_step(f, a, m, fa, flm, fm, left, 0.5 * eps, depth - 1) +
         simpson_step(f, m, b, fm, frm, fb, right, 0.5 * eps, depth - 1);
}

inline double adaptive_simpson(const std::function<double(double)>& f, double a, double b, double eps) {
  const double fa = f(a);
  const double fm = f(0.5 * (a + b));
  const double fb = f(b);
  const double whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
  return simpson_step(f, a, b, fa, fm, fb, whole, eps, 40);
}

// 2π ∫_0^{π/2} D(cosθ) cosθ sinθ dθ  (= ∫_H D(m)(m·n) dω_m for isotropic D).
// The θ range is cut at width/8 · 2^k so a peak of that width (roughness
// only, never D's formula: docs/design.md §3) is resolved before the tail.
inline double projected_integral(Scalar2 D, double param, double width) {
  const auto integrand = [&](double theta) { return D(std::cos(theta), param) * std::cos(theta) * std::sin(theta); };
  std::vector<double> cuts{0.0};
  for (double t = width / 8.0; t < 0.5 * kPi; t *= 2.0) cuts.push_back(t);
  cuts.push_back(0.5 * kPi);
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) sum += adaptive_simpson(integrand, cuts[i], cuts[i + 1], 1e-13);
  return 2.0 * kPi * sum;
}

inline double phong_width(double alpha_p) { return std::sqrt(2.0 / (alpha_p + 2.0)); }

// ---- geometry: dot products of a real (l, v) pair, formed with GLM --------
struct Dots {
  double NoL, NoV, NoH, VoH;
};

inline Dots dots_from_angles(double theta_l, double theta_v, double phi) {
  const glm::dvec3 n(0.0, 0.0, 1.0);
  const glm::dvec3 l(std::sin(theta_l), 0.0, std::cos(theta_l));
  const glm::dvec3 v(std::sin(theta_v) * std::cos(phi), std::sin(theta_v) * std::sin(phi), std::cos(theta_v));
  const glm::dvec3 h = glm::normalize(l + v);
  return {glm::dot(n, l), glm::dot(n, v), glm::dot(n, h), glm::dot(v, h)};
}

// ---- independent closed forms (tests only) --------------------------------
// seed 000, "The exact formulation": F = ½ (g−c)²/(g+c)² (1 + (c(g+c)−1)²/(c(g−c)+1)²),
// g = sqrt(η² − 1 + c²), valid outside total internal reflection.
inline double fresnel_seed000(double c, double eta) {
  const double g = std::sqrt(eta * eta - 1.0 + c * c);
  const double q1 = (g - c) / (g + c);
  const double q2 = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
  return 0.5 * q1 * q1 * (1.0 + q2 * q2);
}

// Born & Wolf's real form of the conductor Fresnel reflectance (a², b² of
// eta² − sin²θ = (a + i b)²), written independently of the complex form.
inline double fresnel_conductor_born_wolf(double c, double n, double k) {
  const double s2 = 1.0 - c * c;
  const double t0 = n * n - k * k - s2;
  const double a2b2 = std::sqrt(t0 * t0 + 4.0 * n * n * k * k);
  const double a = std::sqrt(0.5 * (a2b2 + t0));
  const double rs = (a2b2 - 2.0 * a * c + c * c) / (a2b2 + 2.0 * a * c + c * c);
  const double st = s2 / c;  // sinθ tanθ
  const double rp = rs * (a2b2 - 2.0 * a * st + st * st) / (a2b2 + 2.0 * a * st + st * st);
  return 0.5 * (rs + rp);
}

inline std::vector<Named1> all_g1() {
  std::vector<Named1> v;
  for (double a : {0.001, 0.05, 0.3, 1.0, 2.0}) {
    v.push_back({"G1_smith_beckmann", ref::G1_smith_beckmann, a, a});
    v.push_back({"G1_smith_beckmann_approx", ref::G1_smith_beckmann_approx, a, a});
    v.push_back({"G1_smith_ggx", ref::G1_smith_ggx, a, a});
  }
  for (double ap : {0.0, 1.0, 10.0, 1000.0, 1e6})
    v.push_back({"G1_smith_phong", ref::G1_smith_phong, ap, phong_width(ap)});
  return v;
}

inline std::vector<NamedG2> all_g2() {
  std::vector<NamedG2> v{{"G_implicit", ref::G_implicit, 0.0},
                         {"G_kelemen", ref::G_kelemen, 0.0},
                         {"G_cook_torrance", ref::G_cook_torrance, 0.0}};
  for (double a : {0.05, 0.3, 1.0}) {
    v.push_back({"G_smith_beckmann_approx", ref::G_smith_beckmann_approx, a});
    v.push_back({"G_smith_beckmann", ref::G_smith_beckmann, a});
    v.push_back({"G_smith_ggx", ref::G_smith_ggx, a});
    v.push_back({"G_smith_ggx_correlated", ref::G_smith_ggx_correlated, a});
    v.push_back({"G_hammon_002", ref::G_hammon_002, a});
    v.push_back({"G_hammon_clamped", ref::G_hammon_clamped, a});
  }
  v.push_back({"G_neubelt_sheen", ref::G_neubelt_sheen, 0.0});
  for (double ap : {10.0, 1000.0}) v.push_back({"G_smith_phong", ref::G_smith_phong, ap});
  return v;
}

inline std::vector<Named1> all_d() {
  std::vector<Named1> v;
  for (double a : {0.05, 0.3, 1.0}) {
    v.push_back({"D_ggx", ref::D_ggx, a, a});
    v.push_back({"D_beckmann", ref::D_beckmann, a, a});
    v.push_back({"D_blinn_rho", ref::D_blinn_rho, a, a});
    v.push_back({"D_beckmann_ct82", ref::D_beckmann_ct82, a, a});
  }
  for (double ap : {10.0, 1000.0}) v.push_back({"D_phong", ref::D_phong, ap, phong_width(ap)});
  return v;
}

}  // namespace reference_terms_test
