// The one catalog (docs/design.md §1): every term is declared here once, with its
// parameters and valid ranges, its source, its kernel function and reference
// twin, its agreement tolerance and the physical properties it is expected to
// have. Kernels (through generated dispatch), reference, checks, CLI listing
// and reports all read these declarations.
#pragma once

#include "reference/twins.hpp"

#include <optional>
#include <string>
#include <vector>

namespace mfv {

enum class Kind { D, G, F };
const char* kind_name(Kind k);

// The one width mapping: how the shared microfacet width alpha (GGX/Beckmann
// slope RMS) maps onto a native roughness parameter, of a term, of a whole
// model's lobe (Model::width) and of a user BRDF (mfv check). The formulas
// are roughness.hpp's alpha_from_native and native_from_alpha.
enum class Roughness {
  None,            // no width (a G without parameter; a diffuse model, whose proposal is the cosine lobe's)
  Alpha,           // alpha itself
  PhongExponent,   // (n.h)^e lobe: alpha = sqrt(2/(e+2)) (Walter et al. 2007)
  Rho,             // seed 004's rho (= alpha)
  BeckmannM,       // seed 001's m, the Beckmann RMS slope (= alpha)
  Perceptual,      // r with alpha = r² (Burley 2012)
  MirrorExponent,  // (v.r)^e lobe: about (n.h)^(4e) in half-vector space
  HalfCosine,      // threshold t on n.h: alpha = tan(acos t)
};

// One parameter point of a term that mfv run checks (F: F0 or eta, and a
// conductor's k), with the label its points show.
struct ParamPoint {
  double p0 = 0, p1 = 0;
  std::string label;
};

struct Param {
  std::string name;  // alpha, alpha_p, rho, m, f0, eta, n, k
  double lo, hi;     // valid closed range [lo, hi]
  double fallback;   // default when a command needs one value
  std::string doc;
};

// A D whose masking a Smith G1 reproduces (Heitz 2014 eq. 43: the weak
// white furnace), exactly or within `tol` up to the width `alpha_max`.
struct SmithFit {
  std::string d;
  double tol = 0;            // documented relative approximation tolerance
  double alpha_max = 1e300;  // beyond this width the fit is known not to hold
  std::string why;           // the source of the fit, or of its limit
};

// The reference twins' signatures (reference/twins.hpp), by their catalog names.
using ref::RefD;
using ref::RefDAniso;
using ref::RefDcs;
using ref::RefF;
using ref::RefG;
using ref::RefG1;
using ref::RefG1Aniso;
using ref::RefGAniso;

// One term: its declaration, and (from ref::TermTwins) its reference twins.
struct Term : ref::TermTwins {
  std::string id;  // catalog name: ggx, smith_ggx_correlated, schlick...
  Kind kind;
  std::string kernel_fn;      // function in kernels/terms_*.cl
  std::string source;         // seed file and formula, or paper and equation
  std::string formula;        // one line, for the listing
  std::vector<Param> params;  // D and G: one (roughness), two for anisotropic terms; F: up to two
  Roughness roughness = Roughness::None;
  // F terms: the points of F's parameters mfv run checks each D x G at
  // (none: one point, no parameters).
  std::vector<ParamPoint> check_points = {{0, 0, ""}};

  // Smith G terms: the kernel G1 they are built from (its reference twin is
  // ref_g1), used by the masking check; empty for G terms that are no Smith G1 of any D.
  std::string g1_kernel_fn;
  // Smith G1 = 1 at normal incidence (Λ(tan θ = 0) = 0), as every analytic
  // Λ gives and the stability sweep expects; a fitted Λ may not
  std::string g1_not_one_at_normal;  // empty, or why not
  // Anisotropic D and Smith G (aniso, see ref::TermTwins): their kernel functions
  // take the tangent components (kernels/terms_d.cl, terms_g.cl). terms_of()
  // leaves them out: its callers pass one width.

  // A lobe of its own (the Charlie sheen D and its visibility): D and G pair
  // only with each other (smith_for), one width, and are left out of the
  // shared-width D x G grids (terms_of); d_norm, masking and furnace check
  // them in host/checks/suite_sheen.cpp, agree and stability as every term.
  bool own_lobe = false;
  // The importance proposal's Cauchy-slope width at width alpha (null:
  // alpha itself, right for lobes peaked at the normal); see proposal_width.
  double (*proposal)(double alpha) = nullptr;

  // Agreement budget (kernel float vs double reference, identical inputs):
  // ULPs of the float result, and an absolute floor for results near zero.
  double ulp_budget = 8;
  double abs_floor = 1e-30;

  // Expected properties, used by the conformance checks.
  std::string known_bad;  // non-empty: why this term is kept as a known-bad model
  // G terms, for the masking, furnace and energy checks:
  std::vector<SmithFit> smith_for;       // Smith G: the Ds its G1 belongs to
  std::vector<std::string> under_masks;  // Smith G: Ds whose heavier tails its G1 under-masks (albedo > 1)
  std::string masking_exact;             // non-Smith G normalised against every D anyway: why
  const SmithFit* fit_for(const std::string& d) const;

  // Numerical stability (mfv stability): true for terms that must never give
  // NaN or Inf on in-domain inputs (parameters in range, any direction,
  // dot products that rounded above 1); the stability gate fails when one does.
  bool stable = true;
};

const std::vector<Term>& catalog();
const Term& find_term(const std::string& id);  // throws mfv::Error naming the known ids
const Term* try_find_term(const std::string& id, Kind k);
std::vector<const Term*> terms_of(Kind k);           // the isotropic terms (one width) of kind k
std::vector<const Term*> aniso_terms_of(Kind k);     // the anisotropic ones (alpha_x, alpha_y)
std::vector<const Term*> all_terms_of(Kind k);       // both
std::vector<const Term*> own_lobe_terms_of(Kind k);  // Term::own_lobe (the sheen)
// The proposal width the estimators take for D at width alpha (Term::proposal).
double proposal_width(const Term& d, double alpha);

// Parameter values checked at the boundary: NaN and out-of-range values are
// rejected with a message naming the term, the parameter and its range.
void validate_param(const Term& t, size_t index, double value);
// The same check for one parameter of any catalog entry named `owner`.
void validate_value(const std::string& owner, const Param& p, double value);

}  // namespace mfv
