// The one place that turns an exception into mfv's one-line error and exit
// code 2 (README "exit codes"): main and the child process of mfv check
// (user/time_limit.hpp) both run their work through it.
#pragma once

#include <functional>

namespace mfv::cli {

// Runs `work`; returns its exit code, or 2 after printing `mfv: error: ...`
// when it throws (CLI11's help requests pass through to the caller).
int run_reporting_errors(const std::function<int()>& work);

}  // namespace mfv::cli
