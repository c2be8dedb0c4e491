// An independent truth for mfv energy's E(mu, alpha): the directional albedo
// of an isotropic D x G (F = none) by Boost.Math's adaptive Gauss-Kronrod
// quadrature of the double reference BRDF (reference/brdf.hpp), nested over
// the half vector's azimuth and a radial coordinate. It shares no code with
// the estimator under test (RQMC over visible normals) nor with mfv's own
// product rule (numeric/hemisphere_quadrature: fixed Gauss-Legendre panels).
#pragma once

#include "reference/brdf.hpp"

namespace mfv::test {

struct QuadratureTruth {
  double value = 0;
  double error = 0;      // Boost's error estimates: the outer ones plus the largest inner one relative to its value, times E
  long evaluations = 0;  // BRDF evaluations
  long azimuths = 0;     // inner integrals
};

// E(mu) = ∫ f(i, o)(n·i) dω_i at the view cosine mu (0 < mu <= 1) for s
// (isotropic, F = none or any F), with the radial coordinate of the half
// vectors shaped by a GGX of width `alpha` (its CDF in projected area; see
// energy_quadrature.cpp), which resolves lobes of that width down to 1e-7.
QuadratureTruth albedo_by_boost_quadrature(const ref::BrdfSpec& s, double mu, double alpha);

}  // namespace mfv::test
