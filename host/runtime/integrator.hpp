// The device engine of the batched Monte Carlo integrals (kernels/integrate.cl):
// it owns the program, the kernel file list, the launches (work-group sizes
// from the device's and kernel's limits, runtime/work_group.hpp) and the
// buffers, which start filled with NaN so that a result no kernel wrote
// cannot pass (all but the planes between the parts of a kernel split in
// three, which the first part writes in full before the others read them).
// The integrals themselves are described by IntegralSpec
// (kernels/abi/integral.h); checks/integrate.hpp builds them from the catalog.
#pragma once

#include "abi/integral.h"
#include "runtime/dispatch.hpp"
#include "runtime/opencl.hpp"
#include "runtime/specialize.hpp"
#include "util/progress.hpp"

#include <algorithm>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace mfv {

// AlbedoRqmc/EavgRqmc: the albedo on randomized-QMC uniforms with a
// visible-normal proposal, one randomization per integral (mfv energy;
// kernels/integrate.cl); AlbedoRqmc also yields the split sum's B on the same
// points, which AlbedoRqmcB names for sample_values and the reference.
// AlbedoMis: mfv run's isotropic microfacet albedo, three proposals (one
// of them visible normals of the GGX shape) by multi-sample MIS on
// kMisReplicates randomized-QMC replicates; its standard error comes from the
// replicates' spread (Estimate::dof = kMisReplicates - 1).
enum class IntegralKind : int32_t {
  DNorm = MFV_CHECK_D_NORM,
  Masking = MFV_CHECK_MASKING,
  Albedo = MFV_CHECK_ALBEDO,
  AlbedoRqmc = MFV_CHECK_ALBEDO_RQMC,
  EavgRqmc = MFV_CHECK_EAVG_RQMC,
  AlbedoRqmcB = MFV_CHECK_ALBEDO_RQMC_B,
  AlbedoMis = MFV_CHECK_ALBEDO_MIS,
  BsdfFlux = MFV_CHECK_BSDF_FLUX,  // the rough dielectric BSDF's E_R or E_T over the sphere (kernels/transmission.cl)
  MaskingT = MFV_CHECK_MASKING_T,  // the weak white furnace for o below the surface (kernels/transmission.cl)
  BsdfAvg = MFV_CHECK_BSDF_AVG     // T_avg(1/eta) - T_avg(eta)/eta^2, the averages' reciprocity (transmission.cl)
};

// Replicates of an AlbedoMis integral. The error allowance is t·SE with the
// Student t of R - 1 degrees of freedom; in the N^-1 regime of RQMC,
// SE ~ sqrt(R)/N, so t(R-1)·sqrt(R) is what to minimise. At the default
// run's per-test level (1e-6 / 123182 tests = 8e-12, two-sided) t is 18.7,
// 10.6, 8.4, 7.5 for R = 16, 32, 64, 128 (normal: 6.84), t·sqrt(R) 75, 60,
// 67, 85: R = 32, where an integrand too rough for QMC (SE ~ 1/sqrt(N)
// whatever R) pays 10.6 / 6.84 = 1.55x in allowance.
constexpr uint32_t kMisReplicates = 32;

// IntegralSpec: kernels/abi/integral.h, the one layout kernels and host share.
static_assert(sizeof(IntegralSpec) == 132, "IntegralSpec: thirty-three 4-byte words, no padding (tests/test_abi.cpp)");

struct Estimate {
  double mean = 0, stderr_ = 0;
  uint64_t samples = 0;
  double b_mean = 0;  // AlbedoRqmc: the split sum's B on the same points (no stderr: RQMC errors come from replicates)
  uint32_t dof =
      0;  // stderr_ from replicates: Student t with dof degrees of freedom (0: normal, from a sum of squares)
};

// The kernel file lists, in one place. catalog_sources: the files every
// program with the catalog's terms and models starts with, in build order,
// then `then` (the generated dispatch goes before kDispatchBefore);
// integration_files: the integration kernels and what they need, in build
// order; integrate_sources: the catalog's integration program.
constexpr const char* kDispatchBefore = "brdf.cl";
std::vector<std::string> catalog_sources(const std::vector<std::string>& then);
const std::vector<std::string>& integration_files();
const std::vector<std::string>& integrate_sources();
// integrate.cl with the generated dispatch of `terms` (MFV_ACC_DOUBLE where the device has fp64).
cl::Program build_integrate_program(Runtime& rt, const TermSelection& terms);
// The same with `specializations` in place of generate_specializations(terms.specialized)
// (tests plant a wrong one).
cl::Program build_integrate_program(Runtime& rt, const TermSelection& terms, const std::string& specializations);

// The `sample_values` kernel of `program` (kernels/integrate.cl): float, or
// double for a MFV_DOUBLE build (host/checks/reference_compare.cpp).
template <class T>
std::vector<T> program_sample_values(Runtime& rt, const cl::Program& program, const std::vector<IntegralSpec>& specs,
                                     uint32_t n, uint64_t seed);

// A device buffer of `bytes` filled with NaN (0x7fffffff: a float NaN, and a
// double NaN twice over): a value no kernel wrote reads as NaN and fails its check.
cl::Buffer nan_filled_buffer(Runtime& rt, cl_mem_flags flags, size_t bytes);
// Up to this size nan_filled_buffer copies NaN in (integrator_samples.cpp), above it fills.
inline constexpr size_t kNanCopyBytes = size_t(1) << 20;

// The worst of n asymmetries v[0 .. n) and its index, as a scan keeping the
// running worst would find them (`if (!(v[p] <= worst)) worst = isnan(v[p]) ?
// inf : v[p], where = p`, from worst = 0): the first greatest value above 0,
// or infinity at the last NaN where there is one; 0 at 0 where none is above
// 0. (Integrator::worst_of; in two passes, the first of which vectorizes.)
void worst_of_values(const float* v, uint32_t n, float& worst, uint32_t& where);

// The worst asymmetry of each integral's reciprocity pairs 0 .. pairs - 1
// and the pair where it was (Integrator::reciprocity). NaN counts as the
// worst (infinity).
struct WorstPairs {
  std::vector<float> worst;
  std::vector<uint32_t> at;
};

class Integrator {
 public:
  // Builds one program with the given terms (one build for a whole check).
  Integrator(Runtime& rt, const TermSelection& terms);
  // From a program built elsewhere with integrate.cl in it (mfv check: the
  // user's code); `catalog`: a build_integrate_program program (fast paths on).
  Integrator(Runtime& rt, cl::Program program, bool catalog = false);

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
  // samples: the largest 5·2^(m-2) <= samples_used / kMisReplicates, at
  // least 20 (the kernel's shares 2^m, 2^(m-3), 2^(m-3), each a whole net).
  uint32_t mis_points(uint64_t requested) const;
  // Replicates per AlbedoMis or BsdfFlux integral (default kMisReplicates).
  // mfv energy takes 1: its own R streams are the replicates, and each then
  // holds one Sobol net of up to the whole point budget.
  void set_mis_replicates(uint32_t r) { mis_replicates_ = std::max<uint32_t>(1, r); }
  // Sets `strata` as run() does, for callers that need the same samples
  // elsewhere (sample_values, the reference).
  void stratify(std::vector<IntegralSpec>& specs, uint64_t samples) const;

  // The first n per-sample values of each integral, for the reference.
  std::vector<float> sample_values(const std::vector<IntegralSpec>& specs, uint32_t n, uint64_t seed);

  // The one reciprocity launch (mfv run, run --scene, check and bench):
  // pairs 0 .. pairs - 1 of each integral (kernels/integrate.cl
  // reciprocity_values: one pair per work-item; the microfacet kernel where
  // the program has it and the spec is an isotropic model-0 BRDF).
  WorstPairs reciprocity(const std::vector<IntegralSpec>& specs, uint32_t pairs, uint64_t seed);
  // The microfacet reciprocity kernel takes a launch's isotropic microfacet
  // integrals only where they hold at least `pairs` pairs in all (default
  // kMicrofacetReciprocityPairs: where its compile pays); 0: always (mfv
  // bench, tests of that kernel). The floats are the same either way.
  void set_microfacet_reciprocity_from(uint64_t pairs) { microfacet_reciprocity_from_ = pairs; }

  Runtime& runtime() { return rt_; }
  const cl::Program& program() const { return program_; }
  // Isotropic microfacet albedo and masking integrals (iid) and d_norm
  // (stratified) run through albedo_values, masking_values, d_norm_values +
  // sum_values / sum_pairs (kernels/integrate.cl: eight work-items per AVX2
  // instruction on PoCL where the program holds one term of each kind), on
  // the samples `integrate` takes; off: `integrate` takes them (tests compare).
  void set_albedo_fast_path(bool on) { fast_albedo_ = on && fast_albedo_available_; }
  // The fast-path kernels launched so far, by name (the specialized ones
  // carry their term ids: runtime/specialize.hpp).
  const std::set<std::string>& launched_kernels() const { return launched_; }
  // Compile-ahead (checks/compile_ahead.hpp): run() and reciprocity() launch
  // each kernel once, as the first launch of the whole run would (the same
  // work-group size and grid class, so PoCL compiles the same variant),
  // taking one integral of each specialized kernel's group, and launch
  // run()'s groups in reverse order. Their results are then meaningless.
  void set_compile_ahead(bool on) { compile_ahead_ = on; }

 private:
  struct Sums {
    double sum = 0, sumsq = 0;
  };
  void layout(uint64_t samples, uint32_t& per_item, uint32_t& slices) const;
  // run()'s paths: the `integrate` kernel; for isotropic microfacet integrals
  // albedo_values, masking_values or d_norm_values with sum_values or
  // sum_pairs; albedo_mis_values for AlbedoMis (kernels/integrate.cl)
  // `kernel`: `integrate` or a check's own (integrate_kernel_for)
  std::vector<Sums> sums_integrate(const std::vector<IntegralSpec>& specs, const std::string& kernel,
                                   uint32_t per_item, uint32_t slices, uint64_t seed, uint64_t first_index);
  // `integrate`, or the kernel of s's check (runtime/specialize.hpp check_kernel_name) where the
  // program has it and the fast paths are on
  std::string integrate_kernel_for(const IntegralSpec& s) const;
  // `kernel`: `base` or its specialization to the specs' term pair (or G); `d_kernel`:
  // masking_d (generic or by D) where `kernel` is a masking_values, which then runs after
  // masking_geometry and it (kernels/integrate.cl), else empty
  std::vector<Sums> sums_values(const std::vector<IntegralSpec>& specs, const std::string& base,
                                const std::string& kernel, const std::string& d_kernel, uint32_t per_item,
                                uint32_t slices, uint64_t seed, uint64_t first_index);
  // AlbedoMis: the sums of each replicate (kMisReplicates per integral, integral-major),
  // through one kernel per term pair where the program specializes it
  std::vector<Sums> sums_mis(const std::vector<IntegralSpec>& specs, uint64_t seed);
  // `kernel` the values kernel; `df_kernel` albedo_mis_df (generic or by D) where `kernel` is an
  // albedo_mis_values, which then runs after albedo_mis_geometry and it (kernels/integrate.cl)
  std::vector<Sums> sums_mis(const std::vector<IntegralSpec>& specs, const std::string& kernel,
                             const std::string& df_kernel, uint64_t seed);
  // `base` specialized to s's term pair where the program has that kernel, else `base`
  std::string kernel_for(const std::string& base, const IntegralSpec& s) const;
  cl::Kernel launched(const std::string& kernel);  // the kernel, noted in launched_
  // sum_values over `rows` runs of `per_row` values in `values`, added to out[0 .. rows)
  void sum_rows(const cl::Buffer& values, size_t rows, uint64_t per_row, Sums* out);
  void add_sums(const cl::Buffer& sums, size_t count, uint32_t slices, Sums* out);
  cl::Buffer nan_buffer(cl_mem_flags flags, size_t bytes);
  // A buffer of the asymmetries a launch stores, kept from call to call where
  // one exceeds nan_filled_buffer's copy size: a fresh 16 MiB buffer each
  // call cost page faults and zeroing (docs/performance.md, issue 31; for
  // sums_values' samples the same change moved no bench median).
  // kept_nan_buffer fills it with NaN before every use, so a value no kernel
  // wrote still reads as NaN; smaller ones are nan_buffer's.
  struct KeptBuffer {
    cl::Buffer buffer;
    size_t bytes = 0;
  };
  cl::Buffer kept_nan_buffer(KeptBuffer& kept, cl_mem_flags flags, size_t bytes);
  KeptBuffer worst_values_;  // worst_of's
  // One launch of a reciprocity kernel over specs[at[..]] into out.
  void worst_of(cl::Kernel& k, const std::vector<IntegralSpec>& specs, const std::vector<size_t>& at, uint32_t pairs,
                uint64_t seed, WorstPairs& out, uint32_t per_item = 1);
  Runtime& rt_;
  cl::Program program_;
  bool acc_double_;
  bool fast_albedo_ = false, fast_albedo_available_ = false;
  std::set<std::string> kernel_names_, launched_;
  // the checks' own `integrate` kernels (runtime/specialize.hpp) of the program that take
  // `integrate`'s work-group size, local_size_
  std::set<std::string> check_kernels_;
  bool compile_ahead_ = false;
  uint64_t microfacet_reciprocity_from_ = kMicrofacetReciprocityPairs;
  uint32_t mis_replicates_ = kMisReplicates;
  size_t local_size_ = 64;          // of `integrate`: 64, or less where the device or kernel allows less
  progress::Task* task_ = nullptr;  // run()'s progress, advanced as each batch's sums are read
  uint64_t group_samples_ = 0;      // samples per work-group slice in the current run()
};

}  // namespace mfv
