// Console table, results.json, report.md and junit.xml for mfv run.
#pragma once

#include "checks/suite.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace mfv {

// What the outputs say of where the run ran: the device, its build options
// and build count, the provenance (runtime/provenance.hpp). mfv merge
// (report/shard_file.hpp) takes them from the shards' files.
struct OutputContext {
  DeviceInfo device;
  std::string build_options;
  int builds = 0;
  nlohmann::json provenance;
};
OutputContext output_context(const Runtime& rt);

void print_suite_console(const SuiteReport& rep, const Runtime& rt, const SuiteOptions& opt);
void print_suite_console(const SuiteReport& rep, const DeviceInfo& device, const SuiteOptions& opt);
std::vector<std::pair<std::string, std::string>> suite_output_files(const SuiteReport& rep, const OutputContext& ctx,
                                                                    const SuiteOptions& opt, const std::string& dir);
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

// The compact JSON array of point_record(p) for every point: the bytes of
// nlohmann's dump of that array, built on the host's threads.
std::string results_array_json(const std::vector<PointResult>& points);
// j.dump(), except that the key "results" (if j has it) takes the given JSON text as its value.
std::string dump_with_results(const nlohmann::json& j, const std::string& results);

// results.json as a string (schema mfv-run/1, schemas/mfv-run-1.schema.json), also used by tests.
std::string suite_json(const SuiteReport& rep, const Runtime& rt, const SuiteOptions& opt);
std::string suite_json(const SuiteReport& rep, const OutputContext& ctx, const SuiteOptions& opt);

}  // namespace mfv
