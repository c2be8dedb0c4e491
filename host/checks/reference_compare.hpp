// The same-sample reference comparison of mfv run with a derived bound
// (docs/trust-reference.md). On a device with cl_khr_fp64 every compared
// integral is evaluated three times on identical Philox samples:
//   kf  the float kernel (what the verdicts integrate),
//   kd  the same kernel source built with MFV_DOUBLE (its double twin),
//   r   the double reference (host/reference, written from the papers).
// kf - kd is float rounding, nothing else: the source is the same. kd - r is
// formula error: two double evaluations of the same formula agree to double
// rounding, which is 2^-29 of the float rounding kf - kd shows on the same
// samples (the same conditioning, a unit roundoff 2^-53 instead of 2^-24).
#pragma once

#include "checks/integrate.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/opencl.hpp"

#include <cstdint>
#include <vector>

namespace mfv {

struct TwinAgreement {
  double float_mean = 0, double_mean = 0, reference_mean = 0;  // over the n compared samples
  // Upper bound on the float estimator's rounding bias E[kf - kd] for this
  // integral: |mean(kf - kd)| + 3 sd(kf - kd) / sqrt(n).
  double rounding_bound = 0;
  double formula_gap = 0;    // sum |kd - r| / n: per sample, so errors of either sign add
  double formula_bound = 0;  // the derived bound on formula_gap (reference_compare.cpp)
  bool ok = true;
  // the sample where |kd - r| was largest (for the failure's message)
  uint64_t worst_index = 0;
  double worst_twin = 0, worst_reference = 0;
};

// Unit roundoffs and the safety factors of the bound (derivation in reference_compare.cpp).
constexpr double kFloatRoundoff = 0x1p-24, kDoubleRoundoff = 0x1p-53;

class ReferenceTwin {
 public:
  // The MFV_DOUBLE program of `terms` where the device has fp64, built at
  // the first compare() (a run whose plans compare nothing builds none).
  ReferenceTwin(Runtime& rt, const TermSelection& terms);
  bool available() const { return available_; }
  int builds() const { return program_() ? 1 : 0; }
  // kf from `in` (the float program), kd from the twin, r from the reference;
  // n samples per integral as Integrator::sample_values takes them.
  std::vector<TwinAgreement> compare(Integrator& in, const std::vector<IntegralSpec>& specs, uint32_t n, uint64_t seed);
  // Builds the twin now, and launches its sample_values once on `spec` (so
  // PoCL compiles it as compare() launches it): what a run does while a
  // compile-ahead child builds the float program (checks/compile_ahead.hpp).
  // Returns the builds it made (0 where there is no twin or it was built).
  int build_ahead(const IntegralSpec& spec, uint64_t seed);

 private:
  void build();

  Runtime& rt_;
  TermSelection terms_;
  cl::Program program_;
  bool available_ = false;
};

// The bound on sum |kd - r| given the float rounding sum |kf - kd| and the
// scale sum |r| of the same samples.
// mu: the integral's fixed direction cosine (view or light; 1 for d_norm);
// lobe_width: the narrowest width of the lobe read at a half vector formed
// from a sampled light and the view (lobe_width_of; 0: none).
double derived_formula_bound(double float_rounding_l1, double reference_l1, double mu, double lobe_width);
double lobe_width_of(const IntegralSpec& s);

}  // namespace mfv
