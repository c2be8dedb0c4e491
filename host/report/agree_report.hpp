// mfv agree's report: one line per case (max and median relative error, max
// ULPs against the budget, failures, verdict), the worst input of each
// failing case and the totals.
#pragma once

#include "checks/agree.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace mfv {

// The table and totals as mfv agree prints them; `device` is the first line's text.
std::string agree_console(const AgreeReport& rep, const std::string& device);
// Cases that failed.
int agree_failures(const AgreeReport& rep);
// One case's result, every field at full precision (agree.json, agree_shard.json), and back.
nlohmann::json agree_result_json(const AgreeResult& r);
AgreeResult agree_result_of(const nlohmann::json& j);
// agree.json (schema mfv-agree/1): the run's options, device, times and every case's result.
std::string agree_json(const AgreeReport& rep, const AgreeOptions& opt, const std::string& device);

}  // namespace mfv
