#include "energy_quadrature.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <algorithm>
#include <cmath>

namespace mfv::test {
namespace {

using GK = boost::math::quadrature::gauss_kronrod<double, 31>;

// Relative tolerances and bisection depths of the nested adaptive integrals:
// the inner one 100x tighter, so that its own error does not read as roughness
// of the outer integrand. At grazing view (mu = 1e-6) the bisection reaches
// the depth caps; E at depths 6 and 8 agrees to 1e-15 on the table's grazing
// corners (alpha = 1e-7, 1), and Boost's estimates there stay below 1.2e-7.
constexpr double kInnerTol = 1e-12, kOuterTol = 1e-10;
constexpr unsigned kInnerDepth = 6, kOuterDepth = 6;

struct Adaptive {
  double tol;
  unsigned depth;
  double error = 0;  // the sum of Boost's error estimates
};

// ∫_0^X f(x) dx as ∫_0^x0 f dx + ∫_{ln x0}^{ln X} f(e^z) e^z dz: linear up to
// x0, where f's own scale lies, then in ln x (features at x0·10^k on one scale).
template <class F>
double linear_then_log(const F& f, double X, double x0, Adaptive& a) {
  double e1 = 0, e2 = 0, v = GK::integrate(f, 0.0, std::min(X, x0), a.depth, a.tol, &e1);
  if (X > x0)
    v += GK::integrate([&](double z) { return f(std::exp(z)) * std::exp(z); }, std::log(x0), std::log(X), a.depth,
                       a.tol, &e2);
  a.error += e1 + e2;
  return v;
}

}  // namespace

// Half vectors h = (sin θ cos φ, sin θ sin φ, cos θ), the view o = (so, 0, mu).
// The light i = 2(o·h)h - o, and dω_i = 4 (o·h) dω_h (Walter et al. 2007, "Microfacet
// models for refraction through rough surfaces", eq. 14). Radially q = tan θ/α, the
// slope in units of the width (Walter et al. 2007, eq. 33's GGX is 1/(π α² cos⁴θ (1 + q²)²)):
// dω_h = sin θ dθ dφ = α² cos³θ q dq dφ. The light reaches the horizon where
// mu cos 2θ + so cos φ sin 2θ = 0: θ_c = (π/2 + atan2(so cos φ, mu))/2 and
// q_c = tan θ_c/α (the integrand vanishes there with G). q runs linearly over
// [0, 1] (sin θ, hence o·h, is linear in q there: no endpoint singularity) and in
// ln q beyond (q_c reaches 1e13 at alpha = 1e-7). By symmetry about the plane of
// the view, φ ∈ [0, π] twice, as s = |φ - π/2| on each side of π/2: at grazing
// view θ_c swings from π/2 to 0 within s ~ mu/so, so s runs linearly up to
// mu/(100 so) and in ln s beyond, which puts that change on one scale.
QuadratureTruth albedo_by_boost_quadrature(const ref::BrdfSpec& s, double mu, double alpha) {
  const double co = mu, so = std::sqrt((1 - mu) * (1 + mu)), a2 = alpha * alpha;
  QuadratureTruth out;
  Adaptive outer{kOuterTol, kOuterDepth};
  double inner_rel = 0;  // the largest inner error relative to its value
  auto at = [&](double phi) {
    ++out.azimuths;
    const double cp = std::cos(phi);
    const double tc = std::tan((M_PI / 2 + std::atan2(so * cp, co)) / 2);
    auto g = [&](double q) {
      const double t2 = a2 * q * q;
      const double cos2 = 1 / (1 + t2), sin2 = t2 / (1 + t2);
      const double c = std::sqrt(cos2);
      const double oh = so * alpha * q * c * cp + co * c;
      const double iz = 2 * oh * c - co;
      if (!(iz > 0) || !(oh > 0)) return 0.0;
      const ref::Shading sh{iz, co, c, oh, sin2};
      ++out.evaluations;
      return 4 * ref::brdf(s, sh) * iz * oh * a2 * cos2 * c * q;
    };
    Adaptive inner{kInnerTol, kInnerDepth};
    const double v = linear_then_log(g, tc / alpha, 1.0, inner);
    if (v > 0) inner_rel = std::max(inner_rel, inner.error / v);
    return v;
  };
  const double s0 = so > 0 ? std::min(co / (100 * so), 1e-2) : 1e-2;
  double value = 0;
  for (double side : {-1.0, 1.0})
    value += linear_then_log([&](double t) { return at(M_PI / 2 + side * t); }, M_PI / 2, s0, outer);
  out.value = 2 * value;
  // the integrand is positive: the outer rule's weighted sum of the inner
  // errors is at most inner_rel times the value
  out.error = 2 * outer.error + inner_rel * out.value;
  return out;
}

}  // namespace mfv::test
