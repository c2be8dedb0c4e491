// mfv agree's report: one line per case (max and median relative error, max
// ULPs against the budget, failures, verdict), the worst input of each
// failing case and the totals.
#pragma once

#include "checks/agree.hpp"

#include <string>

namespace mfv {

// The table and totals as mfv agree prints them; `device` is the first line's text.
std::string agree_console(const AgreeReport& rep, const std::string& device);
// Cases that failed.
int agree_failures(const AgreeReport& rep);

}  // namespace mfv
