#include "checks/shard.hpp"

#include "util/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace mfv {
namespace {

// A non-negative decimal that fits uint32_t, or nullopt.
std::optional<uint32_t> parse_count(const std::string& s) {
  if (s.empty() || s.size() > 10) return std::nullopt;
  uint64_t v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
    v = v * 10 + uint64_t(c - '0');
  }
  if (v > UINT32_MAX) return std::nullopt;
  return uint32_t(v);
}

uint32_t env_number(const EnvReader& env, const char* name) {
  const char* v = env(name);
  auto n = parse_count(v ? v : "");
  if (!n) throw Error(fmt::format("{}='{}' is not a non-negative integer", name, v ? v : ""));
  return *n;
}

ShardSpec checked(uint32_t index, uint32_t count, std::string source) {
  if (count == 0) throw Error(fmt::format("{}: the shard count must be at least 1", source));
  if (index >= count)
    throw Error(fmt::format("{}: shard index {} is out of range for {} shards (0-based)", source, index, count));
  return {index, count, std::move(source)};
}

void hash_plan(PlanDigest& f, const Plan& p) {
  f.text(p.check);
  f.value(p.samples);
  f.value(uint64_t(p.specs.size()));
  for (auto& s : p.specs) f.bytes(&s, sizeof s);
  for (auto& q : p.points) {
    f.text(model_name(q));
    for (auto& [k, v] : q.params) f.text(k), f.value(v);
    f.value(q.expected);
    f.value(int(q.expect));
  }
}

}  // namespace

ShardSpec parse_shard_option(const std::string& text) {
  const size_t slash = text.find('/');
  const auto k = parse_count(text.substr(0, slash));
  const auto n = parse_count(slash == std::string::npos ? "" : text.substr(slash + 1));
  const uint32_t kv = k.value_or(0), nv = n.value_or(0);
  if (kv == 0 || nv == 0 || kv > nv)
    throw Error(fmt::format("--shard '{}': expected K/N with 1 <= K <= N (e.g. --shard 2/4)", text));
  return {kv - 1, nv, "--shard"};
}

std::optional<ShardSpec> shard_from_environment(uint32_t count, const EnvReader& env_in) {
  const EnvReader env = env_in ? env_in : EnvReader([](const char* n) { return std::getenv(n); });
  auto set = [&](const char* n) { return env(n) != nullptr; };
  if (set("TEST_TOTAL_SHARDS") || set("TEST_SHARD_INDEX")) {
    return checked(env_number(env, "TEST_SHARD_INDEX"), env_number(env, "TEST_TOTAL_SHARDS"),
                   "TEST_SHARD_INDEX/TEST_TOTAL_SHARDS (Bazel)");
  }
  if (set("GTEST_TOTAL_SHARDS") || set("GTEST_SHARD_INDEX"))
    return checked(env_number(env, "GTEST_SHARD_INDEX"), env_number(env, "GTEST_TOTAL_SHARDS"),
                   "GTEST_SHARD_INDEX/GTEST_TOTAL_SHARDS");
  if (set("SLURM_ARRAY_TASK_ID")) {
    const uint32_t id = env_number(env, "SLURM_ARRAY_TASK_ID");
    const uint32_t lo = set("SLURM_ARRAY_TASK_MIN") ? env_number(env, "SLURM_ARRAY_TASK_MIN") : 0;
    const uint32_t step = set("SLURM_ARRAY_TASK_STEP") ? env_number(env, "SLURM_ARRAY_TASK_STEP") : 1;
    const char* src = "SLURM_ARRAY_TASK_ID/SLURM_ARRAY_TASK_COUNT (Slurm)";
    if (!set("SLURM_ARRAY_TASK_COUNT")) throw Error(fmt::format("{}: SLURM_ARRAY_TASK_COUNT is not set", src));
    if (id < lo || step == 0 || (id - lo) % step != 0)
      throw Error(fmt::format("{}: task id {} is not min {} + a multiple of step {}", src, id, lo, step));
    return checked((id - lo) / step, env_number(env, "SLURM_ARRAY_TASK_COUNT"), src);
  }
  if (set("JOB_COMPLETION_INDEX")) {
    const char* src = "JOB_COMPLETION_INDEX (Kubernetes Indexed Job)";
    if (count == 0 && set("MFV_SHARD_COUNT")) count = env_number(env, "MFV_SHARD_COUNT");
    if (count == 0)
      throw Error(fmt::format("{} is set but not the count: give --shard-count N (the Job's completions) or "
                              "MFV_SHARD_COUNT",
                              src));
    return checked(env_number(env, "JOB_COMPLETION_INDEX"), count, src);
  }
  return std::nullopt;
}

uint64_t integral_cost(const Plan& plan, double scale) {
  // reciprocity: 64 x per-item pairs, each evaluated both ways (record_reciprocity)
  if (plan.check == "reciprocity") return 2 * 64 * std::max<uint64_t>(1, uint64_t(64 * scale));
  return std::max<uint64_t>(plan.samples, 1);
}

std::string PlanDigest::hex() const { return fmt::format("{:016x}", h); }

std::string plan_hash(const SuitePlans& sp, const SuiteOptions& opt) {
  PlanDigest f;
  for (auto& p : sp.plans) hash_plan(f, p);
  hash_plan(f, sp.reciprocity);
  f.value(opt.scale);
  f.value(opt.family_alpha);
  f.value(opt.reference_samples);
  f.value(opt.reference_every);
  f.value(opt.density);
  for (auto& c : opt.checks) f.text(c);
  f.text("|");
  for (auto& m : opt.models) f.text(m);
  return f.hex();
}

size_t plan_integrals(const SuitePlans& sp) {
  size_t n = sp.reciprocity.specs.size();
  for (auto& p : sp.plans) n += p.specs.size();
  return n;
}

namespace {

// The cost is uniform within a plan (one sample count), so the shard's 1/N
// of the plan's cost is its integrals [n k / N, n (k + 1) / N).
std::pair<size_t, size_t> share(size_t n, const ShardSpec& s) {
  return {size_t(uint64_t(n) * s.index / s.count), size_t(uint64_t(n) * (s.index + 1) / s.count)};
}

}  // namespace

std::pair<size_t, size_t> cut_by_cost(const std::vector<uint64_t>& cost, const ShardSpec& s) {
  uint64_t total = 0;
  for (uint64_t c : cost) total += c;
  // the boundary whose cost before it is nearest C j / N (the lower on a tie; unsigned __int128: no overflow)
  using u128 = unsigned __int128;
  auto start = [&](uint32_t j) {
    if (j >= s.count) return cost.size();
    const u128 goal = u128(total) * j;
    uint64_t before = 0, prev = 0;
    size_t i = 0;
    while (i < cost.size() && u128(before) * s.count < goal) prev = before, before += cost[i++];
    if (i > 0 && goal - u128(prev) * s.count <= u128(before) * s.count - goal) --i;
    return i;
  };
  return {start(s.index), start(s.index + 1)};
}

std::vector<size_t> shard_positions(const SuitePlans& sp, const ShardSpec& s) {
  std::vector<size_t> positions;
  size_t offset = 0;
  auto add = [&](const Plan& p) {
    auto [lo, hi] = share(p.specs.size(), s);
    for (size_t i = lo; i < hi; ++i) positions.push_back(offset + i);
    offset += p.specs.size();
  };
  for (auto& p : sp.plans) add(p);
  add(sp.reciprocity);
  return positions;
}

std::vector<size_t> cut_to_shard(SuitePlans& sp, const SuiteOptions& opt, const ShardSpec& s) {
  std::vector<size_t> positions = shard_positions(sp, s);
  auto cut = [&](Plan& p, bool pick) {
    auto [lo, hi] = share(p.specs.size(), s);
    std::vector<size_t> ref;
    // the whole plan's pick: its own where the plan chose one (bsdf_plan
    // leaves out the known-bad entries and the index-matched points)
    if (pick)
      for (size_t i : p.reference_pick ? *p.reference_pick : reference_subset(p, opt.reference_every))
        if (i >= lo && i < hi) ref.push_back(i - lo);
    p.specs = std::vector<IntegralSpec>(p.specs.begin() + long(lo), p.specs.begin() + long(hi));
    p.points = std::vector<PointResult>(p.points.begin() + long(lo), p.points.begin() + long(hi));
    if (pick) p.reference_pick = ref;
  };
  for (auto& p : sp.plans) cut(p, true);
  cut(sp.reciprocity, false);
  return positions;
}

}  // namespace mfv
