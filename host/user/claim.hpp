// mfv check --as D/G/F --map NAME=EXPR: the claim that the user's code
// implements a catalog model, and how its parameters map onto the model's;
// the double reference (host/reference/brdf.cpp) then judges it pointwise.
#pragma once

#include "catalog/catalog.hpp"
#include "reference/brdf.hpp"
#include "user/user_brdf.hpp"

#include <string>
#include <vector>

namespace mfv {

struct Claim {
  std::string spec;  // "ggx/smith_ggx_correlated/schlick"
  const Term *d = nullptr, *g = nullptr, *f = nullptr;
  // Where each reference slot (D param, G param, F p0, F p1, kd) comes from:
  // a user parameter (optionally squared: perceptual roughness to alpha) or a constant.
  struct Source {
    int param = -1;
    bool squared = false;
    double constant = 0;
  };
  Source slot[5];
  // The reference BRDF at the user's parameter values; throws mfv::Error
  // when a mapped value leaves the catalog range of its term.
  ref::BrdfSpec at(const std::vector<double>& values) const;
  std::string mapping(const UserBrdf& u) const;  // "alpha=roughness^2 f0=f0 kd=0"
  // The estimators' proposal width of the claimed D at the user's values
  // (catalog proposal_width of its alpha); 0 without a D of a width, or
  // where the mapped value leaves the D's range.
  double proposal(const std::vector<double>& values) const;
};

// `as` names a D/G/F of the catalog; `map` holds NAME=EXPR entries (comma
// lists allowed), EXPR a user parameter, PARAM^2 or a number. A model
// parameter without an entry takes the user parameter of the same name
// (kd: 0). Throws mfv::Error naming what is missing or unknown.
Claim parse_claim(const std::string& as, const std::vector<std::string>& map, const UserBrdf& u);

}  // namespace mfv
