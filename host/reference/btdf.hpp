// The rough dielectric BTDF in double (twin of kernels/btdf.cl), written
// plainly from Walter et al. 2007, independently of the kernel.
// Convention (docs/transmission.md): the radiance form of eq. 21, with η_o².
#pragma once

#include "reference/twins.hpp"

#include <glm/vec3.hpp>

namespace mfv::ref {

struct BtdfSpec {
  const TermTwins* d = nullptr;  // a D (ref_d, ref_d_cs where it has one)
  const TermTwins* g = nullptr;  // a Smith G: its ref_g1
  int form = 0;                  // MFV_BTDF_SEPARABLE or MFV_BTDF_CORRELATED (kernels/abi/bsdf.h)
  int variant = 0;               // MFV_BTDF_OK or a planted known-bad variant
  double pd = 0, pg = 0;
  double eta = 1.5;              // η_below / η_above
  // D's argument moved: sinθ of h_t plus h_tilt, clamped at 0 (mfv agree's
  // conditioning allowance: what the kernel's rounding of h_t can do to D)
  double h_tilt = 0;
  // F's facet cosine |i·h| scaled by (1 + f_cos_bump) (the same allowance:
  // what the kernel's rounding of i·h does to 1 - F near the critical angle)
  double f_cos_bump = 0;
  // The TIR test g² = η² - 1 + c² moved by up to |g2_slack| (mfv agree's
  // conditioning allowance near the critical angle: the float rounding of the
  // kernel's g², checks/agree.cpp): 1 - F taken at its largest over
  // g² ± |g2_slack| where g2_slack > 0, at its smallest where < 0.
  double g2_slack = 0;
};

// f_t(i, o), i = incident, o = outgoing, both pointing away, n = +z: 0 unless
// they lie on opposite sides of the surface.
double btdf(const BtdfSpec& s, const glm::dvec3& i, const glm::dvec3& o);

// The G2 of the form from the two oriented G1 (0 where either is 0).
double btdf_g2(int form, double g1i, double g1o);

// The generalized half vector h_t = -(η_i i + η_o o)/|...| turned to n's side
// (Walter et al. 2007 eq. 16); η_i, η_o from the sides of i and o.
glm::dvec3 half_vector_t(const glm::dvec3& i, const glm::dvec3& o, double eta);

// Walter et al. 2007 eq. 40: the refraction of i through the facet m (i·m > 0)
// from index η_i into η_o: false under total internal reflection.
bool refract(const glm::dvec3& i, const glm::dvec3& m, double eta_i_over_o, glm::dvec3& t);

}  // namespace mfv::ref
