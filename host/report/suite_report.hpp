// Console table, results.json, report.md and junit.xml for mfv run.
#pragma once

#include "checks/suite.hpp"

#include <string>

namespace mfv {

void print_suite_console(const SuiteReport& rep, const Runtime& rt, const SuiteOptions& opt);
void write_suite_outputs(const SuiteReport& rep, const Runtime& rt, const SuiteOptions& opt, const std::string& dir);

// results.json as a string (schema_version 1), also used by tests.
std::string suite_json(const SuiteReport& rep, const Runtime& rt, const SuiteOptions& opt);

}  // namespace mfv
