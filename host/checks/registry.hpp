// The registry of check kinds (docs/adding-a-check.md): one entry per kind of
// check, naming what it integrates (the integrand, its estimator and domain),
// how it is tested (sidedness, expected value or bound), how many samples at
// which grid, the expectation the catalog gives each point, the optional
// truth, which point sources can take it, and the line that says in a report
// what it tests. The plan builders (suite_plans.cpp and the point sources),
// the option checks, the help and the reports read it; no other file lists
// the checks. tests/test_checks_complete.cpp fails with a named message when
// an entry lacks a piece.
#pragma once

#include "catalog/bsdfs.hpp"
#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "runtime/integrator.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace mfv {

// Samples per masking or furnace integral at scale 1; every check's count is
// proportional to the scale.
constexpr uint64_t kSuiteBaseSamples = 4096;

// A closed form's deviation from the expected 1 beyond which a point of a
// default-size integral must fail (about ten standard errors of one: the
// masking of the anisotropic and sheen pairs, checks/suite_aniso.cpp and
// suite_sheen.cpp).
constexpr double kClosedFormMustFail = 0.25;

// Which F terms a grid kind pairs with D x G.
enum class FSet {
  None,     // no F (masking), or F = 1 ("none": the white furnace)
  Real,     // every F of the catalog but "none", at its check points (Term::check_points)
  Schlick,  // Schlick's F alone (the diffuse + specular sum of seed 000)
};

// How mfv runs a kind: Monte Carlo integrals (IntegralSpec, kernels/integrate.cl
// sample_value), reciprocity pairs (a bounded maximum), pointwise passes
// (agree, stability: kernel and reference at identical inputs, a count of
// failures bounded by 0; checks/suite_pointwise.cpp), or mfv energy's tables
// (measured; verdicts for whole models only).
enum class Runner { Integral, Pairs, Pointwise, Table };

// The domain the integrand's sampled direction ranges over.
enum class Domain { Hemisphere, Sphere };

// The point sources (checks/suite_plans.cpp and its siblings): the catalog's
// D x G x F grid, anisotropic pairs, sheen lobes, whole models, a scene's
// materials, a user's BRDF. A kind names those it takes; the others cannot
// take it, for the reason in CheckKind::not_taken.
enum Source : unsigned {
  kSourceGrid = 1u << 0,
  kSourceAniso = 1u << 1,
  kSourceSheen = 1u << 2,
  kSourceModels = 1u << 3,
  kSourceScene = 1u << 4,
  kSourceUser = 1u << 5,
  kSourceBsdf = 1u << 6,  // the catalog's rough dielectric BSDFs (catalog/bsdfs.hpp; checks/suite_bsdf.cpp)
};

// The catalog's prediction for one point: Expect (catalog/models.hpp) says it
// must hold, must fail, or may fail; reason why; tolerance the documented
// approximation tolerance (relative).
struct Expectation {
  Expect expect = Expect::Hold;
  std::string reason;
  double tolerance = 0;
};

// One point of a D/G/F model: alpha is the shared width, f0 the first F
// parameter, kd the diffuse albedo (g is null for d_norm).
struct ExpectPoint {
  const Term *d = nullptr, *g = nullptr;
  double alpha = 0, f0 = 0, kd = 0;
  const Bsdf* bsdf = nullptr;  // a rough dielectric BSDF's point (kSourceBsdf): its entry
};

struct CheckKind {
  const char* check = "";  // its name: --check, reports, records
  Runner runner = Runner::Integral;
  IntegralKind kind = IntegralKind::Albedo;  // the integrand and estimator (Runner::Integral, Table)
  Domain domain = Domain::Hemisphere;
  int terms_read = 3;         // the catalog terms its integrand reads: 1 D, 2 D and G, 3 D, G and F (stream keys)
  uint64_t base_samples = 0;  // per integral at --scale 1
  int n_alpha = 0;            // widths: n_alpha of suite_alphas(), evenly thinned (0: the D's own d_norm grid)
  int n_view = 0;             // view cosines: view_cosines(n_view) (0: the normal only)
  FSet fs = FSet::None;
  std::vector<double> kds = {0.0};  // Lambertian albedos added (energy_diffuse)
  bool upper_only = false;          // one-sided (estimate <= expected) rather than two-sided (== expected)
  double expected = 1.0;            // the value (or bound) a correct model gives
  bool in_run = true;               // one of mfv run's kinds (--check)
  unsigned sources = 0;             // the point sources that take it (Source)
  const char* not_taken = "";       // why the other sources cannot
  // The catalog's prediction at a D/G/F point (nullptr: every point holds,
  // or the source sets it, as whole models from their cases).
  Expectation (*expect)(const ExpectPoint&) = nullptr;
  bool truth = false;        // the furnace truth (checks/furnace_truth.hpp): the pooled test is two-sided
  const char* verdict = "";  // how the expected verdict follows from the catalog
  const char* summary = "";  // the report's line: what the kind tests
};

// Every kind, in plan order.
const std::vector<CheckKind>& check_kinds();
// The kind named `check`; throws mfv::Error for another name.
const CheckKind& check_kind(const std::string& check);
const CheckKind* find_check_kind(const std::string& check);  // nullptr for another name
// mfv run's kinds (in_run), in plan order, and their names as one list ("d_norm, masking, ...").
const std::vector<std::string>& suite_checks();
std::string suite_check_list();

// What a point source builds for a kind, read from its integrand and fields
// (never its name): D's normalisation at each width; the weak white furnace
// of D and G1 at each width and view; an albedo with F = 1 (FSet::None,
// one-sided); an albedo with the Fs of `fs` (one-sided; with a Lambert kd
// where `kds` has one, diffuse_of); an albedo against the model's own exact
// value (two-sided); reciprocity pairs; a rough dielectric BSDF's reflected
// and transmitted flux over the sphere against the facet-space truth
// (BsdfFlux, two-sided); the weak white furnace for a direction below the
// surface (MaskingT); a BSDF's hemispherical averages from both sides at
// each width and index (BsdfAvg, two-sided against 0); none (pointwise
// passes, tables).
enum class Shape { DNorm, Masking, Furnace, Energy, Exact, Pairs, BsdfFlux, MaskingT, BsdfAvg, None };
Shape shape_of(const CheckKind& k);
bool diffuse_of(const CheckKind& k);  // an Energy kind whose points add a Lambert kd > 0

// The grid kinds of the D x G x F source (kSourceGrid, Runner::Integral), in plan order.
std::vector<const CheckKind*> grid_kinds();
// mfv energy's kinds (Runner::Table), in record order: energy_mu, E(mu) and
// (same points) B at each view cosine of the grid; energy_avg, E_avg with mu
// drawn with density 2 mu. n_alpha and n_view give the default grid; --grid
// replaces it.
const std::vector<CheckKind>& energy_check_rows();

// The former names, for callers that predate the registry.
using CheckRow = CheckKind;
inline const CheckKind& check_row(const std::string& check) { return check_kind(check); }

// The catalog's prediction for one point of `check` (Expect::Hold where the kind has no expect).
Expectation expect(const std::string& check, const Term* d, const Term* g, double alpha, double f0, double kd);

// D's and G's native parameters at the shared width alpha (catalog/roughness.hpp);
// G's is clamped to the top of its range (its G1 is flat beyond).
struct NativeWidths {
  double pd = 0, pg = 0;
};
NativeWidths native_widths(const Term& d, const Term& g, double alpha);

// Whole models (catalog/models.hpp): energy (albedo <= 1, one-sided, at
// kModelLights light directions) and closed_form (the exact albedo, two-sided).
constexpr int kModelLights = 10;
// Their samples: kSuiteBaseSamples at the scale, times these factors.
constexpr uint64_t kModelEnergyFactor = 2;  // spread over the 10 lights
constexpr uint64_t kClosedFormFactor = 8;   // few integrals, two-sided: sharp (standard error ~0.6 %)

}  // namespace mfv
