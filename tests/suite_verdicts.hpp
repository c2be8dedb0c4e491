// Verdict look-ups in a SuiteReport, shared by the suite tests.
#pragma once

#include "checks/suite.hpp"

#include <catch2/catch.hpp>

#include <string>

namespace mfv::test {

inline const GroupResult* group(const SuiteReport& rep, const std::string& check, const std::string& model) {
  for (auto& g : rep.groups)
    if (g.check == check && g.model == model) return &g;
  return nullptr;
}

inline Verdict verdict_of(const SuiteReport& rep, const std::string& check, const std::string& model) {
  const GroupResult* g = group(rep, check, model);
  REQUIRE(g != nullptr);
  return g->verdict;
}

}  // namespace mfv::test
