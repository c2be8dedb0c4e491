// Roughness conversions, in one place.
//  * alpha: the microfacet width (Beckmann RMS slope, GGX alpha).
//  * perceptual roughness r (seed 002, Burley 2012): alpha = r².
//  * Phong exponent (seed 000): alpha_p = 2/alpha² - 2, alpha = sqrt(2/(alpha_p+2)).
//  * seed 004's rho and seed 001's m are alpha itself (D_blinn_rho with rho is
//    D_phong with alpha_p = 2/rho² - 2; m is the Beckmann RMS slope).
//  * whole models' lobes: a mirror exponent e (about (n.h)^(4e)) and a
//    threshold t on n.h (alpha = tan(acos t)).
// Roughness (catalog.hpp) names these mappings for terms, models and user BRDFs alike.
#pragma once

#include "catalog/catalog.hpp"

#include <algorithm>
#include <cmath>

namespace mfv {

inline double alpha_from_perceptual(double r) { return r * r; }
inline double perceptual_from_alpha(double alpha) { return std::sqrt(alpha); }
inline double phong_exponent_from_alpha(double alpha) { return 2.0 / (alpha * alpha) - 2.0; }
inline double alpha_from_phong_exponent(double alpha_p) { return std::sqrt(2.0 / (alpha_p + 2.0)); }
// A mirror lobe (v.r)^e in half-vector space: v.r = cos 2θ_h, and cos(2θ)^e ~ exp(-2eθ²) ~ cos(θ)^(4e)
// near the peak, so it is about the (n.h)^(4e) lobe.
inline double alpha_from_mirror_exponent(double e) { return alpha_from_phong_exponent(4.0 * e); }
// A threshold t on n.h (a toon lobe): alpha = tan(acos t), t kept in [1e-3, 1 - 1e-7] so the width stays finite and >
// 0.
inline double alpha_from_half_cosine(double t) {
  t = std::min(std::max(t, 1e-3), 1.0 - 1e-7);
  return std::sqrt(1.0 - t * t) / t;
}

// The native parameter of a term for a given shared width alpha, and back.
double native_from_alpha(Roughness r, double alpha);
double alpha_from_native(Roughness r, double native);

}  // namespace mfv
