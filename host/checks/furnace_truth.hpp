// What the catalog knows about a white furnace integral: its value by
// deterministic quadrature of the double reference, so that the furnace's
// pooled test (host/stats/verdict.hpp) is two-sided where the per-integral
// test can only say E <= 1.
#pragma once

#include "checks/suite.hpp"
#include "numeric/hemisphere_quadrature.hpp"

#include <string>
#include <vector>

namespace mfv {

struct KnownValue {
  double value = 0, error = 0;  // error: the larger of |fine - coarse| and |fine - coarser rule|
};

// E(o) = ∫ f(i, o) (n·i) di of the integral's BRDF (ref::brdf on the float
// parameters the device sees) by product Gauss-Legendre over half vectors
// (host/numeric/hemisphere_quadrature.hpp).
KnownValue albedo_by_quadrature(const IntegralSpec& s);
// The same by given rules (value: fine; error: the larger of |fine - coarse|
// and |fine - coarser|), one integral at a time; the truth's own rules are
// furnace_rules().
struct RuleSet {
  ProductRule fine, coarse, coarser;
};
KnownValue albedo_by_rules(const IntegralSpec& s, const RuleSet& rules);
const RuleSet& furnace_rules();
// The same for many integrals, the same bits: those at one view share the
// rule's nodes, the shading at them and each term's values (furnace_views.hpp);
// the views split over `threads` threads, each writing its own slots.
std::vector<KnownValue> albedos_by_quadrature(const std::vector<IntegralSpec>& specs, unsigned threads);
// albedos_by_quadrature's values (the same bits), kept on disk across runs:
// an entry of ProgramCache's format in `dir` under truth_cache_key(specs),
// loaded where one checks out (its size and SHA-256 match), else computed and
// stored. A truncated or corrupt entry is recomputed and replaced, never
// trusted; `dir` "" or a key of "" (the executable unreadable) computes alone.
std::vector<KnownValue> stored_albedos_by_quadrature(const std::vector<IntegralSpec>& specs, unsigned threads,
                                                     const std::string& dir);
// SHA-256 over all the values depend on: the running executable's bytes (the
// reference code, the catalog, the rules and how they were compiled), the C
// library's version (libm), the rules and the specs less their streams.
std::string truth_cache_key(const std::vector<IntegralSpec>& specs);
// The truths' folder: furnace-truth/ in mfv's cache folder
// (ProgramCache::cache_folder()); "" where MFV_TRUTH_CACHE=0 (on where unset
// or 1, any other value an error) or no folder can be named.
std::string truth_cache_dir();
// albedo_by_quadrature, remembered for the process (by the spec less its stream).
KnownValue cached_albedo_by_quadrature(const IntegralSpec& s);

// Sets PointResult::known on the furnace plan's points that must hold
// (`points`: the plan's points in the order of its specs, wherever they are
// kept), first joining a FurnaceTruthAhead's computation (its error rethrown).
void attach_furnace_truth(Plan& plan);
void attach_furnace_truth(const std::vector<IntegralSpec>& specs, PointResult* points);

// The truths attach_furnace_truth will need for `plans` (the check kinds
// that take one), computed beside the run (issue 30: on a cold run PoCL
// compiles on one core, the other mostly idle): constructed before the run
// builds its programs, it starts one thread that loads or computes them as
// attach_furnace_truth would, plan by plan, by the same disk keys; the first
// attach_furnace_truth joins it, taking the views left beside the thread
// (a short run, --check furnace, keeps two cores on it), and rethrows its
// error. The values are the same bits (threads do not change them). The destructor
// stops a thread not joined (at its next view) and joins it, on every path:
// none outlives the run. Nothing starts where another is running (a nested
// run) or no plan takes a truth; MFV_TRUTH_CACHE's error is thrown here.
class FurnaceTruthAhead {
 public:
  explicit FurnaceTruthAhead(const std::vector<Plan>& plans);
  ~FurnaceTruthAhead();
  FurnaceTruthAhead(const FurnaceTruthAhead&) = delete;
  FurnaceTruthAhead& operator=(const FurnaceTruthAhead&) = delete;

 private:
  bool started_ = false;
};

}  // namespace mfv
