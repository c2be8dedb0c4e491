// Batched Monte Carlo integration on the device (kernels/integrate.cl).
#pragma once

#include "catalog/models.hpp"
#include "reference/estimators.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/opencl.hpp"
#include "util/progress.hpp"

#include <cstdint>
#include <vector>

namespace mfv {

struct Term;

// AlbedoRqmc/EavgRqmc: the albedo on randomized-QMC uniforms with a
// visible-normal proposal, one randomization per integral (mfv energy;
// kernels/integrate.cl); AlbedoRqmc also yields the split sum's B on the same
// points, which AlbedoRqmcB names for sample_values and the reference.
// AlbedoMis: mfv run's isotropic microfacet albedo, three proposals (one
// of them visible normals of the GGX shape) by multi-sample MIS on
// kMisReplicates randomized-QMC replicates; its standard error comes from the
// replicates' spread (Estimate::dof = kMisReplicates - 1).
enum class IntegralKind : int32_t {
  DNorm = 0, Masking = 1, Albedo = 2, AlbedoRqmc = 3, EavgRqmc = 4, AlbedoRqmcB = 5, AlbedoMis = 6
};

// Replicates of an AlbedoMis integral. The error allowance is t·SE with the
// Student t of R - 1 degrees of freedom; in the N^-1 regime of RQMC,
// SE ~ sqrt(R)/N, so t(R-1)·sqrt(R) is what to minimise. At the default
// run's per-test level (1e-6 / 123182 tests = 8e-12, two-sided) t is 18.7,
// 10.6, 8.4, 7.5 for R = 16, 32, 64, 128 (normal: 6.84), t·sqrt(R) 75, 60,
// 67, 85: R = 32, where an integrand too rough for QMC (SE ~ 1/sqrt(N)
// whatever R) pays 10.6 / 6.84 = 1.55x in allowance.
constexpr uint32_t kMisReplicates = 32;

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
  uint32_t dof = 0;   // stderr_ from replicates: Student t with dof degrees of freedom (0: normal, from a sum of squares)
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

// The worst asymmetry of each integral's reciprocity pairs 0 .. pairs - 1
// and the pair where it was (kernels/integrate.cl reciprocity_values: one
// pair per work-item; the microfacet kernel where `prog` has it and the spec
// is an isotropic model-0 BRDF). NaN counts as the worst (infinity).
struct WorstPairs {
  std::vector<float> worst;
  std::vector<uint32_t> at;
};
WorstPairs reciprocity_worst_pairs(Runtime& rt, const cl::Program& prog, const std::vector<IntegralSpec>& specs,
                                   uint32_t pairs, uint64_t seed);

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
  // Points per replicate of an AlbedoMis integral run with `requested`
  // samples: samples_used / kMisReplicates, rounded up to a multiple of 4
  // (the kernel's shares 1/2, 1/4, 1/4 and sum_values' runs).
  uint32_t mis_points(uint64_t requested) const;
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

  // reciprocity_worst_pairs over 64 x per_item pairs: the worst asymmetry
  // of each integral (mfv bench times it).
  std::vector<float> reciprocity_worst(const std::vector<IntegralSpec>& specs, uint32_t per_item, uint64_t seed);

  bool double_accumulation() const { return acc_double_; }
  Runtime& runtime() { return rt_; }
  // Isotropic microfacet albedo and masking integrals (iid) and d_norm
  // (stratified) run through albedo_values, masking_values, d_norm_values +
  // sum_values / sum_pairs (kernels/integrate.cl: eight work-items per AVX2
  // instruction on PoCL where the program holds one term of each kind), on
  // the samples `integrate` takes; off: `integrate` takes them (tests compare).
  void set_albedo_fast_path(bool on) { fast_albedo_ = on && fast_albedo_available_; }

 private:
  struct Sums {
    double sum = 0, sumsq = 0;
  };
  void layout(uint64_t samples, uint32_t& per_item, uint32_t& slices) const;
  // run()'s paths: the `integrate` kernel; for isotropic microfacet integrals
  // albedo_values, masking_values or d_norm_values with sum_values or
  // sum_pairs; albedo_mis_values for AlbedoMis (kernels/integrate.cl)
  std::vector<Sums> sums_integrate(const std::vector<IntegralSpec>& specs, uint32_t per_item, uint32_t slices,
                                   uint64_t seed, uint64_t first_index);
  std::vector<Sums> sums_values(const std::vector<IntegralSpec>& specs, const char* kernel, uint32_t per_item,
                                uint32_t slices, uint64_t seed, uint64_t first_index);
  // AlbedoMis: the sums of each replicate (kMisReplicates per integral, integral-major)
  std::vector<Sums> sums_mis(const std::vector<IntegralSpec>& specs, uint64_t seed);
  // sum_values over `rows` runs of `per_row` values in `values`, added to out[0 .. rows)
  void sum_rows(const cl::Buffer& values, size_t rows, uint64_t per_row, Sums* out);
  void add_sums(const cl::Buffer& sums, size_t count, uint32_t slices, Sums* out);
  Runtime& rt_;
  cl::Program program_;
  bool acc_double_;
  bool fast_albedo_ = false, fast_albedo_available_ = false;
  size_t local_size_ = 64;  // of `integrate`: 64, or less where the device or kernel allows less
  progress::Task* task_ = nullptr;  // run()'s progress, advanced as each batch's sums are read
  uint64_t group_samples_ = 0;      // samples per work-group slice in the current run()
};


}  // namespace mfv
