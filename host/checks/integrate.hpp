// Batched Monte Carlo integration on the device (kernels/integrate.cl).
#pragma once

#include "catalog/models.hpp"
#include "reference/estimators.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/opencl.hpp"

#include <cstdint>
#include <vector>

namespace mfv {

struct Term;

// AlbedoRqmc/EavgRqmc: the albedo on randomized-QMC uniforms with a
// visible-normal proposal, one randomization per integral (mfv energy;
// kernels/integrate.cl); AlbedoRqmc also yields the split sum's B on the same
// points, which AlbedoRqmcB names for sample_values and the reference.
enum class IntegralKind : int32_t { DNorm = 0, Masking = 1, Albedo = 2, AlbedoRqmc = 3, EavgRqmc = 4, AlbedoRqmcB = 5 };

// Twin of IntegralSpec in kernels/integrate.cl: twenty 4-byte fields.
struct IntegralSpec {
  int32_t check = 0, d = 0, g = 0, f = 0;
  float pd = 0, pg = 0, f0 = 0, f1 = 0;
  float kd = 0, width = 0.1f, cos_o = 1, p5 = 0;  // p5: sixth parameter of a whole model
  uint32_t stream = 0;
  uint32_t strata = 0;  // stratified integrals (d_norm): the sample count, set by run(); 0 = iid
  uint32_t model = 0;  // 0: the microfacet D×G×F BRDF (kernels/integrate.cl spec_brdf)
  uint32_t channel = 0;  // mfv check: the RGB channel (0..2) of the user's BRDF the integral checks
  float pd2 = 0;          // anisotropic D: the second width alpha_y (unused by isotropic terms)
  float phi_o = 0;        // azimuth of the view about n (anisotropic masking and albedo)
  uint32_t estimator = 0;  // mfv convergence: the estimator (0 = the check's own)
  uint32_t spare = 0;
};
static_assert(sizeof(IntegralSpec) == 80, "IntegralSpec must match the kernel's layout");

struct Estimate {
  double mean = 0, stderr_ = 0;
  uint64_t samples = 0;
  double b_mean = 0;  // AlbedoRqmc: the split sum's B on the same points (no stderr: RQMC errors come from replicates)
};

// One microfacet (D x G x F, model 0) integral; g and f may be null.
IntegralSpec make_spec(IntegralKind kind, const Term* d, const Term* g, const Term* f, double pd, double pg, double f0,
                       double f1, double kd, double width, double cos_o);

// integrate.cl with the generated dispatch of `terms` (MFV_ACC_DOUBLE where the device has fp64).
cl::Program build_integrate_program(Runtime& rt, const TermSelection& terms);

// One whole-model integral (catalog/models.hpp): p[0..5] in pd, pg, f0, f1,
// kd, p5, the proposal width from the model's roughness-like parameter; the
// fixed direction at cos_o is the light (kernels/integrate.cl spec_brdf).
IntegralSpec model_spec(IntegralKind kind, const Model& m, const ModelParams& p, double cos_o);

// The same integral for the double reference twin (host/reference/estimators).
ref::IntegralRef reference_of(const IntegralSpec& s);
// A test hook (tests/test_trust_reference.cpp plants reference defects with
// it): while set, reference_of() takes `planted` wherever an integral has the
// catalog term `original`; nullptr removes the plant. Unset in every run of mfv.
void plant_reference_term(const Term* original, const Term* planted);

// The `sample_values` kernel of `program` (kernels/integrate.cl): float, or
// double for a MFV_DOUBLE build (host/checks/reference_compare.cpp).
template <class T>
std::vector<T> program_sample_values(Runtime& rt, const cl::Program& program, const std::vector<IntegralSpec>& specs,
                                     uint32_t n, uint64_t seed);

class Integrator {
 public:
  // Builds one program with the given terms (one build for a whole check).
  Integrator(Runtime& rt, const TermSelection& terms);
  // From a program built elsewhere with integrate.cl in it (mfv check: the user's code).
  Integrator(Runtime& rt, cl::Program program);

  // Samples per integral are rounded up to a whole number of work-group
  // slices; samples_used() tells the count actually taken. d_norm integrals
  // are stratified: run() sets their `strata` and estimates their standard
  // error from neighbouring strata (conservative), the others are iid.
  // first_index > 0 takes samples first_index, first_index + 1, ... (a later
  // pass extending an iid or QMC point set; not for stratified integrals).
  std::vector<Estimate> run(const std::vector<IntegralSpec>& specs, uint64_t samples, uint64_t seed,
                            uint64_t first_index = 0);
  uint64_t samples_used(uint64_t requested) const;
  // Sets `strata` as run() does, for callers that need the same samples
  // elsewhere (sample_values, the reference).
  void stratify(std::vector<IntegralSpec>& specs, uint64_t samples) const;

  // The first n per-sample values of each integral, for the reference.
  std::vector<float> sample_values(const std::vector<IntegralSpec>& specs, uint32_t n, uint64_t seed);

  // Kernel and double reference on the identical n samples of each integral
  // (spread over the strata of a stratified one).
  struct Agreement {
    double disagreement;  // |k - r| / max(sum |r|, n): relative for O(1) integrands, absolute below
    double kernel_mean, reference_mean;
  };
  std::vector<Agreement> compare_with_reference(const std::vector<IntegralSpec>& specs, uint32_t n, uint64_t seed);

  // The `reciprocity` kernel: 64 work-items per integral, each over per_item
  // pairs; the worst asymmetry of each integral (mfv bench times it).
  std::vector<float> reciprocity_worst(const std::vector<IntegralSpec>& specs, uint32_t per_item, uint64_t seed);

  bool double_accumulation() const { return acc_double_; }
  Runtime& runtime() { return rt_; }
  // Isotropic microfacet albedo integrals run through albedo_values +
  // sum_values (kernels/integrate.cl: eight work-items per AVX2 instruction on
  // PoCL), on the samples `integrate` takes; off: `integrate` takes them too
  // (tests compare the two).
  void set_albedo_fast_path(bool on) { fast_albedo_ = on && fast_albedo_available_; }

 private:
  struct Sums {
    double sum = 0, sumsq = 0;
  };
  void layout(uint64_t samples, uint32_t& per_item, uint32_t& slices) const;
  // run()'s two paths: the `integrate` kernel, and albedo_values + sum_values
  // for isotropic microfacet albedo integrals (kernels/integrate.cl)
  std::vector<Sums> sums_integrate(const std::vector<IntegralSpec>& specs, uint32_t per_item, uint32_t slices,
                                   uint64_t seed, uint64_t first_index);
  std::vector<Sums> sums_albedo(const std::vector<IntegralSpec>& specs, uint32_t per_item, uint32_t slices,
                                uint64_t seed, uint64_t first_index);
  void add_sums(const cl::Buffer& sums, size_t count, uint32_t slices, Sums* out);
  Runtime& rt_;
  cl::Program program_;
  bool acc_double_;
  bool fast_albedo_ = false, fast_albedo_available_ = false;
  size_t local_size_ = 64;
  size_t max_work_group_ = 64;
};

}  // namespace mfv
