// Roughness conversions, in one place.
//  * alpha: the microfacet width (Beckmann RMS slope, GGX alpha).
//  * perceptual roughness r (seed 002, Burley 2012): alpha = r².
//  * Phong exponent (seed 000): alpha_p = 2/alpha² - 2, alpha = sqrt(2/(alpha_p+2)).
//  * seed 004's rho and seed 001's m are alpha itself (D_blinn_rho with rho is
//    D_phong with alpha_p = 2/rho² - 2; m is the Beckmann RMS slope).
#pragma once

#include "catalog/catalog.hpp"

#include <cmath>

namespace mfv {

inline double alpha_from_perceptual(double r) { return r * r; }
inline double perceptual_from_alpha(double alpha) { return std::sqrt(alpha); }
inline double phong_exponent_from_alpha(double alpha) { return 2.0 / (alpha * alpha) - 2.0; }
inline double alpha_from_phong_exponent(double alpha_p) { return std::sqrt(2.0 / (alpha_p + 2.0)); }

// The native parameter of a term for a given shared width alpha, and back.
double native_from_alpha(Roughness r, double alpha);
double alpha_from_native(Roughness r, double native);

}  // namespace mfv
