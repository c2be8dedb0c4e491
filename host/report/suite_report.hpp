// Console table, results.json, report.md and junit.xml for mfv run.
#pragma once

#include "checks/suite.hpp"

#include <string>
#include <utility>
#include <vector>

namespace mfv {

void print_suite_console(const SuiteReport& rep, const Runtime& rt, const SuiteOptions& opt);
void write_suite_outputs(const SuiteReport& rep, const Runtime& rt, const SuiteOptions& opt, const std::string& dir);
// The (path, contents) of results.json, report.md and junit.xml, unwritten
// (mfv run --scene adds its sections before writing them).
std::vector<std::pair<std::string, std::string>> suite_output_files(const SuiteReport& rep, const Runtime& rt,
                                                                    const SuiteOptions& opt, const std::string& dir);

// results.json as a string (schema_version 1), also used by tests.
std::string suite_json(const SuiteReport& rep, const Runtime& rt, const SuiteOptions& opt);

}  // namespace mfv
