// The conformance estimators in double (twin of kernels/integrate.cl):
// the same Philox uniforms, the same proposal, written from the formulas.
#pragma once

#include "reference/brdf.hpp"

#include <cstdint>

namespace mfv::ref {

// AlbedoRqmc and EavgRqmc (mfv energy) are Albedo on randomized-QMC uniforms;
// EavgRqmc also draws the view cosine per sample with density 2μ.
enum class Integral { DNorm = 0, Masking = 1, Albedo = 2, AlbedoRqmc = 3, EavgRqmc = 4 };

struct IntegralRef {
  Integral kind = Integral::DNorm;
  BrdfSpec brdf;         // D, G, F and their native parameters, kd
  double width = 0.1;    // proposal width (equivalent alpha)
  double cos_o = 1.0;    // view for masking and albedo, in the xz-plane
  uint32_t stream = 0;   // Philox stream = integral id
  uint32_t strata = 0;   // d_norm: stratified over this many samples (0 = iid)
};

// The index-th sample of the estimator: its mean over samples is the integral.
double sample_value(const IntegralRef& s, uint64_t seed, uint64_t index);

}  // namespace mfv::ref
