// Verdict look-ups in a SuiteReport, and the verdict with a defect planted in
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

// The verdict of `check` on `model` with one replacement planted in a kernel
// file; gate_ok: whether the whole run still passed the gate.
inline Verdict planted_verdict(const char* file, const char* from, const char* to, const SuiteOptions& opt,
                               const char* check, const char* model, bool& gate_ok) {
  PlantedKernelDir dir;
  REQUIRE(dir.replace(file, from, to));
  Runtime planted("", dir.path());
  const SuiteReport bad = run_suite(planted, opt);
  gate_ok = bad.gate_ok();
  return verdict_of(bad, check, model);
}

}  // namespace mfv::test
