// mfv stability's options for the stability tests.
#pragma once

#include "checks/stability.hpp"

#include <string>

namespace mfv::test {

// The sweep of the one term case `only` (e.g. "D ggx"): no D x G x F
// combinations, no whole models.
inline StabilityOptions one_term(const std::string& only) {
  StabilityOptions opt;
  opt.combinations = false;
  opt.models = false;
  opt.only = {only};
  return opt;
}

}  // namespace mfv::test
