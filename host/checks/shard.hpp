// mfv run --shard K/N: a deterministic part of the whole run's plan
// (docs/scale.md). Streams are keyed by identity (checks/streams.hpp) and the
// reference's integrals picked over each whole plan before the plan is cut,
// so a shard computes, integral for integral, what the whole run computes;
// mfv merge (host/cli/cmd_merge.cpp) judges the merged records once.
#pragma once

#include "checks/suite.hpp"
#include "checks/unit_plan.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mfv {

struct ShardSpec {
  uint32_t index = 0;  // 0-based
  uint32_t count = 1;
  std::string source;  // "--shard" or the environment variables it came from
};

// "K/N" with 1 <= K <= N (1-based, as jest and playwright count); throws mfv::Error.
ShardSpec parse_shard_option(const std::string& text);

// The sharding protocols of the engines that run mfv, read through `env`
// (getenv where absent): Bazel's TEST_TOTAL_SHARDS/TEST_SHARD_INDEX,
// GoogleTest's GTEST_TOTAL_SHARDS/GTEST_SHARD_INDEX, Slurm's
// SLURM_ARRAY_TASK_ID/SLURM_ARRAY_TASK_COUNT (less SLURM_ARRAY_TASK_MIN), a
// Kubernetes Indexed Job's JOB_COMPLETION_INDEX with the count given
// (`count`, --shard-count, else MFV_SHARD_COUNT). None set: nullopt. A
// variable that is set but malformed or out of range throws mfv::Error.
using EnvReader = std::function<const char*(const char*)>;
std::optional<ShardSpec> shard_from_environment(uint32_t count = 0, const EnvReader& env = nullptr);

// The estimated cost of each of the plan's integrals: its samples (pairs x 2 for reciprocity).
uint64_t integral_cost(const Plan& plan, double scale);

// A digest of everything that fixes the run's records but the seed: each
// plan's check, samples, integrals (their specs, streams included) and
// points, and the options that change records (scale, filters, reference
// settings, family-wise rate). 16 hex digits.
std::string plan_hash(const SuitePlans& sp, const SuiteOptions& opt);

// Items [lo, hi) of shard s of a list cut into N contiguous parts of equal
// estimated cost (`cost` per item): the items whose cumulative cost before
// them is in [C k / N, C (k + 1) / N). mfv energy --shard cuts its units so.
std::pair<size_t, size_t> cut_by_cost(const std::vector<uint64_t>& cost, const ShardSpec& s);

// Integrals in the whole run (every plan, then reciprocity).
size_t plan_integrals(const SuitePlans& sp);

// Cuts `sp` to shard s: each plan keeps a contiguous share of its integrals,
// 1/N of its estimated cost, so every shard gets a like share of every
// check. Sets reference_pick (picked over the whole plan). Returns each kept
// integral's position in the whole run (plans in order, then reciprocity),
// in the order run_suite_plans records them.
std::vector<size_t> cut_to_shard(SuitePlans& sp, const SuiteOptions& opt, const ShardSpec& s);
// The positions cut_to_shard returns for shard s, without cutting.
std::vector<size_t> shard_positions(const SuitePlans& sp, const ShardSpec& s);

}  // namespace mfv
