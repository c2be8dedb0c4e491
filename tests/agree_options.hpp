// mfv agree's options and the per-case verdicts for the agree tests.
#pragma once

#include "checks/agree.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace mfv::test {

// `samples` per case on the cases whose name contains one of `only` (every
// case where empty); the seed and the rest as mfv agree's defaults.
inline AgreeOptions agree_options(std::vector<std::string> only, uint64_t samples) {
  AgreeOptions opt;
  opt.only = std::move(only);
  opt.samples = samples;
  return opt;
}

// Checks that every case agrees, naming a case that does not with its
// largest error in ulps and its worst input.
inline void check_every_case_passes(const AgreeReport& rep) {
  for (auto& r : rep.results) {
    CAPTURE(r.name, r.max_ulps, r.worst);
    CHECK(r.pass());
  }
}

// Checks that every case fails agreement (a planted defect reaches them all).
inline void check_every_case_fails(const AgreeReport& rep) {
  for (auto& r : rep.results) {
    CAPTURE(r.name, r.worst);
    CHECK_FALSE(r.pass());
  }
}

}  // namespace mfv::test
