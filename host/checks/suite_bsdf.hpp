// What the registry's kinds say of one rough dielectric BSDF (checks/suite_bsdf.cpp):
// mfv list's account of its checks; the pointwise pass of bsdf_reciprocity.
#pragma once

#include "catalog/bsdfs.hpp"
#include "checks/registry.hpp"

#include <string>
#include <vector>

namespace mfv {

// A kind that takes the BSDFs (kSourceBsdf) and the verdict the catalog
// expects of one BSDF's group in it: its worst point's over the source's
// widths (a point that must fail makes the group an expected failure).
struct BsdfCheck {
  const CheckKind* kind = nullptr;
  Expect expect = Expect::Hold;
  std::string reason;
};
std::vector<BsdfCheck> bsdf_checks(const Bsdf& b);

// The points of a kind the BSDF source takes (BsdfFlux, MaskingT, BsdfAvg)
// for one BSDF at the given widths and indices, built and judged as the
// catalog's (truths, expectations, the reference's pick): a scene's
// refracting material (KHR_materials_volume, host/scene/scene_checks.cpp).
struct SuiteOptions;
struct Plan;
Plan bsdf_points(const CheckKind& k, const SuiteOptions& opt, const Bsdf& b, const std::vector<double>& alphas,
                 const std::vector<double>& etas);

// The pointwise kind bsdf_reciprocity (checks/bsdf_reciprocity.cpp): its
// points, float kernel and double twin for each BSDF, width and index.
struct SuiteReport;
class Runtime;
void run_bsdf_reciprocity_pass(Runtime& rt, const SuiteOptions& opt, SuiteReport& rep);

}  // namespace mfv
