// mfv agree --shard K/N and mfv stability --shard K/N with their --merge
// (docs/scale.md): three shards, each a process, with their index from
// --shard and from Bazel's, Slurm's and Kubernetes' variables, merged, equal
// the single run case for case in every output less its times and dates;
// each bad merge input exits 2 with one line naming the shard.
#include "bad_shards.hpp"
#include "device_fixture.hpp"
#include "run_mfv.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <sstream>

using namespace mfv;
using namespace mfv::test;
using nlohmann::json;

namespace {

// A JSON output less what a run measures of itself or of its machine.
json values_of(const std::string& path) {
  json j = json::parse(slurp(path));
  for (const char* k : {"created", "provenance", "seconds", "device", "tool"}) j.erase(k);
  return j;
}

// A text output less its lines of times, devices and output folders.
std::string text_of(const std::string& text) {
  std::string out, line;
  std::istringstream in(text);
  while (std::getline(in, line))
    if (line.find(" s, kernel ") == std::string::npos && line.rfind("device: ", 0) != 0 &&
        line.rfind("Device **", 0) != 0 && line.rfind("shard ", 0) != 0 && line.rfind("wrote ", 0) != 0 &&
        line.rfind("plots: ", 0) != 0)
      out += line + "\n";
  return out;
}

// The command's three shards (with their index from --shard, Bazel's,
// Slurm's or Kubernetes' variables as `how` says), merged in another order,
// against the single run: the same exit code, console (less times) and files;
// the merged `output` names each shard and its variable in its provenance.
// Returns the shards' folders.
std::array<std::string, 3> require_merge_equals_single(const Scratch& s, const std::string& options,
                                                       const std::string& file, const std::string& output,
                                                       const std::array<int, 3>& how) {
  const Run single = run_mfv(options + " --out " + s / "single");
  INFO(single.out);
  REQUIRE(single.code <= 1);
  const std::string status = s / "bazel_status";
  std::array<std::string, 3> dirs;
  for (int k = 0; k < 3; ++k) {
    const std::string n = std::to_string(k + 1), i = std::to_string(k);
    // 0: --shard; 1: Bazel; 2: Slurm (ids from 1); 3: a Kubernetes Indexed Job (count given)
    const std::string env[] = {"", "TEST_TOTAL_SHARDS=3 TEST_SHARD_INDEX=" + i + " TEST_SHARD_STATUS_FILE=" + status,
                               "SLURM_ARRAY_TASK_ID=" + n + " SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_COUNT=3",
                               "JOB_COMPLETION_INDEX=" + i};
    const std::string from[] = {"shard " + n + "/3 (from --shard)", "shard " + n + "/3 from TEST_SHARD_INDEX",
                                "shard " + n + "/3 from SLURM_ARRAY_TASK_ID",
                                "shard " + n + "/3 from JOB_COMPLETION_INDEX"};
    const std::string args[] = {" --shard " + n + "/3", "", "", " --shard-count 3"};
    dirs[size_t(k)] = s / ("s" + n);
    auto r = run_mfv(options + args[how[size_t(k)]] + " --out " + dirs[size_t(k)], env[how[size_t(k)]]);
    INFO(r.out);
    REQUIRE(r.code == 0);
    CHECK(r.out.find(from[how[size_t(k)]]) != std::string::npos);
    CHECK(std::filesystem::exists(dirs[size_t(k)] + "/" + file));
    if (how[size_t(k)] == 1) CHECK(std::filesystem::exists(status));  // Bazel's sign that the test shards
  }
  const Run m = run_mfv(options + " --merge " + dirs[2] + " " + dirs[0] + " " + dirs[1] + " --out " + s / "merged");
  INFO(m.out);
  REQUIRE(m.code == single.code);
  CHECK(text_of(m.out) == text_of(single.out));
  size_t files = 0;
  for (auto& e : std::filesystem::recursive_directory_iterator(s / "single")) {
    if (!e.is_regular_file()) continue;
    const std::string rel = std::filesystem::relative(e.path(), s / "single").string();
    const std::string other = s / ("merged/" + rel);
    INFO(rel);
    REQUIRE(std::filesystem::exists(other));
    ++files;
    if (e.path().extension() == ".json")
      CHECK(values_of(e.path().string()) == values_of(other));
    else if (e.path().extension() == ".md")
      CHECK(text_of(slurp(e.path())) == text_of(slurp(other)));
    else  // plot data, scripts and the plots where gnuplot is found
      CHECK(slurp(e.path()) == slurp(other));
  }
  CHECK(files >= 1);
  // each shard, with the variable its index came from, in the merged output's provenance
  const json shards = json::parse(slurp(s / ("merged/" + output))).at("provenance").at("shards");
  REQUIRE(shards.size() == 3);
  for (int k = 0; k < 3; ++k) {
    const std::string source[] = {"from --shard", "from TEST_SHARD_INDEX", "from SLURM_ARRAY_TASK_ID",
                                  "from JOB_COMPLETION_INDEX"};
    CHECK(shards[size_t(k)].get<std::string>().find(source[how[size_t(k)]]) != std::string::npos);
  }
  return dirs;
}

}  // namespace

TEST_CASE(
    "three mfv agree shards merged equal the single run case for case, with their index from --shard, Bazel's "
    "and Slurm's variables, and each bad merge input exits 2 naming the shard",
    "[shard][agree][device]") {
  if (!device_runtime()) return;
  Scratch s("mfv_agree_shard");
  const std::string opts = "--quiet agree --only 'D ' --only 'G1 ' --only 'BRDF ggx/' --only MODEL";
  const std::string run = opts + " --samples 2000 --seed 5";
  const auto [s1, s2, s3] = require_merge_equals_single(s, run, "agree_shard.json", "agree.json", {0, 1, 2});
  CHECK(values_of(s / "single/agree.json").at("results").size() >= 20);

  const BadMerges bad{s, run, "agree_shard.json", "agree.json"};
  bad.common(s1, s2, s3);
  bad.foreign(s1, s2, s3, opts + " --samples 2000 --seed 6", "ran seed 6", "ran seed 5");
  bad.foreign(s1, s2, s3, opts + " --samples 1000 --seed 5", "ran another plan", "ran another plan");
}

TEST_CASE(
    "three mfv stability shards merged equal the single run case for case, with their index from Kubernetes', "
    "--shard and Slurm's variables, and each bad merge input exits 2 naming the shard",
    "[shard][stability][device]") {
  if (!device_runtime()) return;
  Scratch s("mfv_stability_shard");
  const std::string run = "--quiet stability --terms-only";
  const auto [s1, s2, s3] = require_merge_equals_single(s, run, "stability_shard.json", "stability.json", {3, 0, 2});
  CHECK(values_of(s / "single/stability.json").at("cases").size() >= 20);

  const BadMerges bad{s, run, "stability_shard.json", "stability.json"};
  bad.common(s1, s2, s3);
  bad.foreign(s1, s2, s3, run + " --only 'D '", "ran another plan", "ran another plan");
}

TEST_CASE(
    "mfv agree and mfv stability --shard: a bad K/N, no --out, --merge with --shard, or a bad engine variable "
    "is a one-line error",
    "[shard][agree][stability][cli]") {
  for (const char* args : {"agree --shard 0/2 --out /tmp/x", "agree --shard 1/2", "stability --shard 3/2 --out /tmp/x",
                           "stability --shard 1/2", "agree --shard 1/2 --merge /tmp --out /tmp/x",
                           "stability --shard 1/2 --merge /tmp --out /tmp/x"}) {
    auto r = run_mfv(args);
    INFO(args << "\n" << r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: ", 0) == 0);
  }
  for (const char* command : {"agree", "stability"}) {
    auto r = run_mfv(std::string(command) + " --out /tmp/x", "SLURM_ARRAY_TASK_ID=4 SLURM_ARRAY_TASK_COUNT=3");
    INFO(r.out);
    CHECK(r.code == 2);
    CHECK(r.out.find("SLURM_ARRAY_TASK_ID") != std::string::npos);
  }
}
