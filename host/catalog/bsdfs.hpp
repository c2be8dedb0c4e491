// The rough dielectric BSDFs (Walter et al. 2007) in the one catalog
// (docs/design.md §1, docs/transmission.md): reflection is the catalog's
// BRDF with the exact dielectric F (as today); transmission is the BTDF of
// eq. 21, declared here once per D that has a Smith G, in the separable and
// the height-correlated G2, with its kernel (kernels/btdf.cl) and reference
// (host/reference/btdf.cpp) selected by the code of kernels/abi/bsdf.h.
//
// Convention, stated once: the BTDF is in the radiance form of eq. 21, which
// carries η_o² (radiance across the interface scales as (η_o/η_i)²). The flux
// form, the fraction of the power arriving from i that is transmitted, is
// E_T(i) = ∫ f_t(i, o) |o·n| do; integrated over the incident direction
// instead, the radiance form gives (η_o/η_i)² E_T. Every check names its form.
#pragma once

#include "catalog/catalog.hpp"

#include <string>
#include <vector>

namespace mfv {

struct Bsdf {
  std::string id;              // walter_ggx_correlated, ...
  const Term* d = nullptr;     // the D
  const Term* g = nullptr;     // the Smith G whose G1 masks both directions
  int form = 0;                // MFV_BTDF_SEPARABLE or MFV_BTDF_CORRELATED
  int variant = 0;             // MFV_BTDF_OK, or the planted bug of a known-bad entry
  std::string source;          // paper and equation
  std::string formula;         // one line, for the listing
  std::string known_bad;       // non-empty: why this entry must fail its checks
  std::string g1_fit;          // where G1 is an approximation of D's Smith G1: the fit (SmithFit::why)
  double ulp_budget = 64;      // kernel float vs double reference, identical inputs (mfv agree)
  double abs_floor = 1e-30;
  // The relative index eta = η_below/η_above, both sides: > 1 entering from
  // above, < 1 leaving (total internal reflection beyond the critical angle).
  // [0.01, 100]: issue 29's glass tables (a renderer's 16x16x16 table spans
  // eta ~1.01..100 on each side); bsdf_furnace's float kernel gives E_R = F(mu)
  // and E_T = 1 - F(mu) within total SE at eta = 100 and 1/100
  // (tests/test_bsdf_flux_mis.cpp). The dielectric F term alone keeps [0.1, 10].
  Param eta{"eta", 0.01, 100.0, 1.5, "index below / index above (1/eta: the other side)"};
  int code() const;  // MFV_BTDF_CODE(form, variant)
};

// The radiance/flux convention, one line (mfv list --json, docs/transmission.md).
extern const char* const kBtdfConvention;

const std::vector<Bsdf>& bsdfs();
const Bsdf* try_find_bsdf(const std::string& id);
const char* btdf_form_name(int form);  // "separable", "correlated"

}  // namespace mfv
