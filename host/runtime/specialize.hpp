// Kernels specialized per term pair (docs/performance.md, "Kernels
// specialized per term pair"). A program of many terms evaluates every D
// and G of its select chains in each SIMD lane (runtime/dispatch.cpp); for
// each (D, G) pair a run integrates, the program also gets copies of the
// one-sample-per-work-item kernels (kernels/integrate.cl MFV_*_VALUES) with
// the pair's ids as constants, where the chains fold to the one term. The
// samples and their arithmetic are those of the generic kernels, to the bit.
#pragma once

#include "abi/integral.h"
#include "runtime/dispatch.hpp"

#include <string>
#include <vector>

namespace mfv {

// The (D, G) pairs of the isotropic microfacet integrals among `specs` (the
// ones the fast paths take), each once, in a fixed order; d_norm integrals
// give (D, kNoG). A pair's `rqmc` is set where one of its integrals is
// AlbedoRqmc or EavgRqmc (albedo_rqmc_values).
constexpr int kNoG = -1;
std::vector<TermPair> fast_path_pairs(const std::vector<IntegralSpec>& specs);

// OpenCL C that defines the specialized kernels of `pairs` (after
// kernels/integrate.cl): d_norm_values for (D, kNoG); albedo_rqmc_values
// for the other pairs whose `rqmc` is set, and masking's masking_d and AlbedoMis's albedo_mis_df
// per D and masking_values and albedo_mis_values per G of those pairs (each
// once); where there is one such pair (not counting d_norm's), also
// albedo_mis_pair, AlbedoMis's three kernels in one for that pair.
std::string generate_specializations(const std::vector<TermPair>& pairs);

// OpenCL C that defines model_albedo_values (kernels/model_values.cl) and,
// with `reciprocity`, model_reciprocity_values (kernels/reciprocity.cl)
// specialized to each model of `models` (its Model::number() a constant, so
// that eval_model's switch folds to the one model).
std::string generate_model_specializations(const std::vector<const Model*>& models, bool reciprocity);

// Whether a run's whole-model reciprocity (`pairs` pair evaluations over all
// its integrals, of `models` models) pays for the kernels per model: each
// costs a compile on a cold run (0.12-0.3 s of CPU on Zen 4, PoCL 3.1
// skylake-avx512), and saves about 15 ms of CPU a million pairs warm over the
// generic reciprocity_values (mfv run --check reciprocity --model [ --scale 16,
// 6.4e6 pairs: 0.42-0.43 s against 0.51-0.52 s); so from 1e7 pairs a model
// (--scale of about 500; the default run has 4e5 in all; docs/performance.md,
// "Cold start").
constexpr double kModelReciprocityPairsPerKernel = 1e7;
bool model_reciprocity_per_model_pays(uint64_t pairs, size_t models);

// From how many microfacet pairs in one reciprocity launch (all its
// integrals) reciprocity_values_microfacet takes them rather than the generic
// reciprocity_values (the same floats): the kernel costs a compile on a cold
// run, 1.15 s of CPU (AMD EPYC Zen 4, AVX2, PoCL 3.1 pthread-haswell: mfv run
// --check reciprocity cold, 3.90 s against 2.75 s), and saves 77 ms of CPU a
// million pairs warm where it is 8 wide (mfv bench --integrand reciprocity,
// a one-pair program: 6.5e7 pairs per CPU-second against 1.09e7 for the
// generic kernel); so from 1.5e7 pairs, about --scale 6 of the default run's
// 594 microfacet integrals (2.4e6 pairs). In a program of many terms, such
// as the default run's, the kernel is scalar on haswell and saves about
// 12 ms a million pairs (warm --check reciprocity: 0.58 s against 0.61 s),
// so there it pays only from ~1e8: the threshold is the lower of the two
// (docs/performance.md, "Cold start at 1.93x warm").
constexpr uint64_t kMicrofacetReciprocityPairs = 15000000;

// OpenCL C that defines `integrate` for the iid integrals of one check
// (kernels/integrate.cl MFV_INTEGRATE_IID) for the checks that have one
// (the transmission checks' masking_t and bsdf_avg): the generic kernel's
// loop and reduction on the check's case of sample_value alone, the same sums
// to the bit, a fraction of its compile (docs/performance.md, "Cold start").
std::string generate_check_kernels();
// That kernel's name for `s` (iid: strata 0, estimator 0), or "" where none.
std::string check_kernel_name(const IntegralSpec& s);
// The names of all those kernels.
std::vector<std::string> check_kernel_names();

// The name of the kernel `base` specialized to the terms of `s`
// (d_norm_values, albedo_mis_df: D only; albedo_mis_values: G only;
// model_albedo_values, model_reciprocity_values: s's model).
std::string specialized_name(const std::string& base, const IntegralSpec& s);

}  // namespace mfv
