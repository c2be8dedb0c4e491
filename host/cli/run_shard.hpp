// mfv run's shards (host/cli/cmd_merge.cpp, docs/scale.md).
#pragma once

#include "checks/shard.hpp"
#include "cli/shared_options.hpp"
#include "report/shard_file.hpp"
#include "runtime/opencl.hpp"

#include <functional>
#include <optional>
#include <string>
#include <utility>

namespace mfv::cli {

// The shard to run: --shard K/N where given ("off": none), else the first
// engine protocol set in the environment (checks/shard.hpp), printed to
// stderr; Bazel's TEST_SHARD_STATUS_FILE is touched. nullopt: the whole run.
std::optional<ShardSpec> shard_of(const std::string& option, uint32_t count);

// A shard of a command whose plan is cut into whole units (energy, agree,
// stability: report/shard_file.hpp): prints the shard's line, creates
// out_dir, runs `run` on the device for the shard's units [lo, hi) and
// writes what it returns to out_dir/FILE (u.kind.file), then says how to
// merge. Exit code 0.
int run_unit_shard(const Globals& g, const UnitShard& u, const ShardSpec& s, const std::string& out_dir,
                   const std::function<std::string(Runtime&, std::pair<size_t, size_t>)>& run);

// Runs shard s of the plan of `opt` and writes out_dir/shard.json; exit code 0.
int run_shard(const Globals& g, const SuiteOptions& opt, const ShardSpec& s, const std::string& out_dir);

// mfv run --dry-run: prints "N integrals, M samples, estimated time on this
// device" for the plan of `opt` (the shard's part where given), from a short
// calibration launch (host/cli/dry_run.cpp); exit code 0.
int dry_run(const Globals& g, const SuiteOptions& opt, const std::optional<ShardSpec>& shard);

}  // namespace mfv::cli
