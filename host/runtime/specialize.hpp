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
// give (D, kNoG).
constexpr int kNoG = -1;
std::vector<TermPair> fast_path_pairs(const std::vector<IntegralSpec>& specs);

// OpenCL C that defines the specialized kernels of `pairs` (after
// kernels/integrate.cl): d_norm_values for (D, kNoG); albedo_rqmc_values
// for the other pairs, and masking's masking_d and AlbedoMis's albedo_mis_df
// per D and masking_values and albedo_mis_values per G of those pairs (each
// once); where there is one such pair (not counting d_norm's), also
// albedo_mis_pair, AlbedoMis's three kernels in one for that pair.
std::string generate_specializations(const std::vector<TermPair>& pairs);

// OpenCL C that defines model_albedo_values (kernels/model_values.cl) and
// model_reciprocity_values (kernels/reciprocity.cl) specialized to each model of `models` (its Model::number() a constant, so
// that eval_model's switch folds to the one model).
std::string generate_model_specializations(const std::vector<const Model*>& models);

// OpenCL C that defines `integrate` for the iid integrals of one check
// (kernels/integrate.cl MFV_INTEGRATE_IID) for the checks that have one
// (the transmission checks' masking_t and bsdf_avg): the generic kernel's
// loop and reduction on the check's case of sample_value alone, the same sums
// to the bit, a fraction of its compile (docs/performance.md, "Cold start").
std::string generate_check_kernels();
// That kernel's name for `s` (iid: strata 0, estimator 0), or "" where none.
std::string check_kernel_name(const IntegralSpec& s);

// The name of the kernel `base` specialized to the terms of `s`
// (d_norm_values, albedo_mis_df: D only; albedo_mis_values: G only;
// model_albedo_values, model_reciprocity_values: s's model).
std::string specialized_name(const std::string& base, const IntegralSpec& s);

}  // namespace mfv
