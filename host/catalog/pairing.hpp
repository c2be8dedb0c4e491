// The pairing mfv run checks a term engines ship in (issue 28): such a term is
// own_lobe (out of the shared D x G x F grids) and is checked under the D
// (a G's or an F's) and the G (an F's) engines use it with
// (host/checks/suite_sheen.cpp). Declared in host/catalog/catalog.cpp beside
// the terms' entries.
#pragma once

#include "catalog/catalog.hpp"

#include <string>

namespace mfv {

struct Pairing {
  std::string d, g;  // catalog ids; g empty for a G's own pairing
};

// The term's pairing, or null for every term that is not an engine's.
const Pairing* engine_pairing(const Term& t);

}  // namespace mfv
