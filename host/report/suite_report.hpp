// Console table, results.json, report.md and junit.xml for mfv run.
#pragma once

#include "checks/suite.hpp"

#include <nlohmann/json.hpp>

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

// A group's worst case in words: "0.998 ± 1.2e-02 vs 1 at alpha=0.1 cos_o=0.5".
std::string worst_text(const SuiteReport& rep, const GroupResult& g);

// A group's pooled test in words (stats/verdict.hpp).
std::string pooled_text(const GroupResult& g);
// The same-sample reference comparison in one line.
std::string reference_line(const SuiteReport& rep);

// One record of results.json's "results": one integral or measured maximum.
nlohmann::json point_record(const PointResult& p);

// results.json as a string (schema mfv-run/1, schemas/mfv-run-1.schema.json), also used by tests.
std::string suite_json(const SuiteReport& rep, const Runtime& rt, const SuiteOptions& opt);

}  // namespace mfv
