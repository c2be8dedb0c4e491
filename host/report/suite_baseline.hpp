// mfv run --baseline OLD.json: the estimates of this run against an earlier
// results.json, integral by integral, with the family-wise control of
// mfv energy --baseline (checks/baseline.hpp).
#pragma once

#include "checks/baseline.hpp"
#include "checks/suite.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace mfv {

// The text of an earlier results.json, parsed and checked before the run;
// throws mfv::Error when it is not one.
nlohmann::json parse_run_baseline(const std::string& baseline_json);

// Throws mfv::Error when no integral of `now` is in the baseline.
BaselineDiff compare_run_baseline(const SuiteReport& now, const nlohmann::json& baseline, double alpha_fw);

}  // namespace mfv
