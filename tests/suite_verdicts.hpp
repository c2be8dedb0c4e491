// Verdict look-ups in a SuiteReport, and the suite run with a defect planted in
// a kernel, shared by the suite tests.
#pragma once

#include "checks/suite.hpp"
#include "kernel_dir.hpp"
#include "runtime/opencl.hpp"

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

// The suite run with one defect planted in a kernel file: `from` replaced by
// `to` in `file`.
inline SuiteReport planted_suite(const std::string& file, const std::string& from, const std::string& to,
                                 const SuiteOptions& opt) {
  const PlantedKernelDir dir(file, from, to);
  Runtime planted = dir.runtime();
  return run_suite(planted, opt);
}

// Checks that a defect planted in a kernel file makes `check` FAIL on
// `model` and the whole run fail the gate.
inline void check_planted_fails(const std::string& file, const std::string& from, const std::string& to,
                                const SuiteOptions& opt, const std::string& check, const std::string& model) {
  CAPTURE(file, to, check, model);
  const SuiteReport bad = planted_suite(file, from, to, opt);
  CHECK(verdict_of(bad, check, model) == Verdict::Fail);
  CHECK_FALSE(bad.gate_ok());
}

}  // namespace mfv::test
