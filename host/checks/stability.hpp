// Numerical stability on stiff and extreme inputs (issue 6, `mfv stability`):
// a deterministic sweep (grids, not random draws) of every term, every Smith
// G1, every D x G x F BRDF and a set of alternative formulations over the
// regions where renderers break (roughness near 0, grazing angles, dot
// products that round above 1, opposite light and view, index of refraction
// 1...). Each point is evaluated by the kernel (float32, or float64) and by
// the double reference on identical inputs.
#pragma once

#include "checks/unit_plan.hpp"
#include "runtime/opencl.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace mfv {

struct StabilityOptions {
  bool fp64 = false;              // kernels in double (needs cl_khr_fp64)
  bool combinations = true;       // the D x G x F BRDFs besides terms and variants
  bool models = true;             // the catalog's whole models (catalog/models.hpp)
  std::vector<std::string> only;  // keep cases whose name contains one of these
  bool only_may_match_none = false;  // mfv run --model: `only` matching no case leaves none (else an error)
  // mfv stability --scene (issue 21): whole models at these parameter points
  // (the scene's materials) instead of their catalog cases; model id ->
  // points. Non-empty: no other model is swept (issue 27: a scene of plain
  // metallic-roughness materials sweeps no clearcoat or sheen model).
  std::vector<std::pair<std::string, std::vector<std::array<double, 7>>>> model_points;
  // mfv stability --scene (issue 29): a rough dielectric BSDF's (alpha, eta)
  // points (a refracting material's roughness² and ior, KHR_materials_volume),
  // swept in its case's `scene` region besides its catalog regions; BSDF id ->
  // points.
  std::vector<std::pair<std::string, std::vector<std::array<double, 2>>>> bsdf_points;
};

// One case in one region of the sweep.
struct RegionResult {
  std::string region;
  std::string what;       // one line: which inputs the region holds
  bool in_domain = true;  // counted by the gate (out of domain: reported only)
  std::string expect;     // "0" or "1" where the seeds prescribe the value, else ""
  uint64_t points = 0;
  uint64_t nan = 0;       // kernel NaN
  uint64_t inf = 0;       // kernel ±Inf where the reference is finite
  uint64_t negative = 0;  // kernel < 0 where the reference is >= 0
  uint64_t breaks = 0;    // any of the above, or beyond kBreakUlps (and above the underflow floor)
  uint64_t violations = 0, ref_violations = 0;  // kernel / reference != expect
  // Outside the value's domain where the reference, on the same inputs, is
  // inside: != the prescribed value (0 below the horizon, 1 where tan = 0),
  // negative, or a G or G1 above 1 + kGOvershoot. A stable case fails the gate on any.
  uint64_t out_of_domain = 0;
  std::string first_out_of_domain;
  double max_rel = 0, max_ulps = 0;  // over points where both are finite
  std::string first_break;           // the first breaking input in sweep order, hex-float; "" if none
  std::string worst;                 // the input of max_ulps, hex-float
};

struct StabilityCase {
  std::string
      name;  // "D ggx", "G1 smith_ggx", "BRDF ggx/smith_ggx/schlick", "MODEL ward_004", "variant D_ggx via tan2"
  std::string group;   // "term", "brdf", "model", "variant"
  std::string family;  // variants: the quantity ("D_ggx", "Lambda_ggx", ...); terms: kind
  std::string formula;
  bool stable = false;      // terms, BRDFs: the catalog's flag; variants: false
  bool is_default = false;  // variants: the form the kernels use
  std::vector<RegionResult> regions;
  uint64_t count(uint64_t RegionResult::*field, bool in_domain_only) const;
  double max_ulps() const;
};

// Error curves for the plots: ULPs of one case over θ at one alpha.
struct ScanPoint {
  double theta, alpha, ulps;  // ulps: NaN/Inf/negative results are stored as +inf
};
struct ScanSeries {
  std::string name;  // case name
  std::vector<ScanPoint> points;
};

struct StabilityReport {
  std::string device, platform, driver, precision, build_options;
  std::vector<StabilityCase> cases;
  std::vector<ScanSeries> scans;
  uint64_t points = 0;
  double build_seconds = 0, kernel_seconds = 0, reference_seconds = 0, total_seconds = 0;
  std::vector<std::string> shards;  // mfv stability --merge: one line per shard (index, file, variable, device)
  std::vector<std::string> gate_failures;  // stable cases with NaN/Inf or out-of-domain values in an in-domain region
  bool gate_pass() const { return gate_failures.empty(); }
};

// ULPs beyond which a finite result counts as broken.
inline constexpr double kBreakUlps = 4096;
// How far a G or G1 may exceed 1: seed 000's rational Smith G1 does by up to
// 6.1e-5 near a = 1.59 (its own formula; pinned by a reference test).
inline constexpr double kGOvershoot = 6.1e-5;

// Cases [part.first, part.second) of the whole plan's (mfv stability
// --shard, docs/scale.md), with the whole plan's program: the sweep is a
// grid, so a shard's cases are the whole run's, point for point. The gate
// counts the part's cases; merge_stability judges the whole run's.
StabilityReport run_stability(Runtime& rt, const StabilityOptions& opt,
                              std::pair<size_t, size_t> part = {0, std::numeric_limits<size_t>::max()});
// The whole plan's cases as units, each costing its points, and a digest of
// every case's mode, terms, regions and points.
UnitPlan stability_plan(const StabilityOptions& opt);
// The whole run from its parts (cases in plan order): their cases and scans
// concatenated, the gate judged once over all of them.
StabilityReport merge_stability(const std::vector<StabilityReport>& parts);

}  // namespace mfv
