// Integrals described from the catalog: IntegralSpec (kernels/abi/integral.h)
// from named fields, for a microfacet D x G x F BRDF or a whole model, and
// their double-precision twins for the reference (host/reference/estimators).
// The device engine that runs them is runtime/integrator.hpp.
#pragma once

#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "reference/estimators.hpp"
#include "runtime/integrator.hpp"

#include <cstdint>
#include <vector>

namespace mfv {

// One microfacet (D x G x F, model 0) integral by name; g and f may be null.
struct MicrofacetIntegral {
  IntegralKind kind = IntegralKind::Albedo;
  const Term *d = nullptr, *g = nullptr, *f = nullptr;
  double pd = 0, pg = 0;        // D's and G's native parameters
  double pd2 = 0, pg2 = 0;      // anisotropic D's and G's second widths (0: isotropic)
  double f0 = 0, f1 = 0;        // F's parameters
  double kd = 0;                // Lambertian albedo added to the BRDF
  double width = 0.1;           // the proposal's width (an alpha)
  double cos_o = 1, phi_o = 0;  // the view: cosine and azimuth about n
};
IntegralSpec spec_of(const MicrofacetIntegral& m);

// One whole-model integral (catalog/models.hpp): p[0..6] in pd, pg, f0, f1,
// kd, p5, pd2, the proposal width from the model's roughness-like parameter;
// the fixed direction at cos_o is the light (kernels/estimators.cl spec_brdf).
IntegralSpec model_spec(IntegralKind kind, const Model& m, const ModelParams& p, double cos_o);

// The same integral for the double reference twin (host/reference/estimators).
ref::IntegralRef reference_of(const IntegralSpec& s);
// A test hook (tests/test_trust_reference.cpp plants reference defects with
// it): while set, reference_of() takes `planted` wherever an integral has the
// catalog term `original`; nullptr removes the plant. Unset in every run of mfv.
void plant_reference_term(const Term* original, const Term* planted);
bool reference_planted();  // any plant set (the furnace truth then stays off disk)

// The float kernel and the double reference on the identical n samples of
// each integral (spread over the strata of a stratified one): where no fp64
// twin runs (checks/reference_compare.hpp).
struct Agreement {
  double disagreement;  // |k - r| / max(sum |r|, n): relative for O(1) integrands, absolute below
  double kernel_mean, reference_mean;
};
std::vector<Agreement> compare_with_reference(Integrator& in, const std::vector<IntegralSpec>& specs, uint32_t n,
                                              uint64_t seed);
// The same from kernel values already read: n per integral, integral-major
// (a float or, mfv energy --fp64, a double program's sample_values).
std::vector<Agreement> agreement_with_reference(const std::vector<IntegralSpec>& specs,
                                                const std::vector<double>& kernel_values, uint32_t n, uint64_t seed);

}  // namespace mfv
