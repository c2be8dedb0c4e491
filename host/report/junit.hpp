// junit.xml for mfv run, mfv run --scene and mfv check: one testcase per
// model x check verdict plus one for the kernel/reference comparison.
#pragma once

#include "checks/suite.hpp"

#include <string>
#include <vector>

namespace mfv {

// names: the testcase name of each group (rep.groups order), e.g. material
// names for a scene; empty: "MODEL × CHECK" from the group.
std::string suite_junit(const SuiteReport& rep, const SuiteOptions& opt, const std::vector<std::string>& names = {});

// A group's share of its check's integration time: the check's seconds (every
// CheckStats row of that check) times the group's share of its integrals.
double group_seconds(const SuiteReport& rep, const GroupResult& g);

}  // namespace mfv
