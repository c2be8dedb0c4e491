// mfv energy --shard K/N and mfv energy --merge (docs/scale.md): three
// shards of a small layout, each a process (one with its index from Bazel's
// variables), merged, equal the single run value for value in every output
// (energy.json, CSV, C header, layout files, report); each bad merge input
// exits 2 with one line naming the shard.
#include "bad_shards.hpp"
#include "checks/shard.hpp"
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

// A Kulla-Conty layout of 4 x 4 cells for one D x G: E, A, B and E_avg
// cells, csv/, kulla_conty.h, layout/ and plots/ (about 5 s on 2 cores).
const std::string kBase = "--quiet energy --layout kulla-conty:4 --models ggx/smith_ggx_correlated";
const std::string kRun = kBase + " --target 5e-5 --seed 5";

// energy.json less what a run measures of itself (times, date, provenance).
json values_of(const std::string& path) {
  json j = json::parse(slurp(path));
  j.erase("date");
  j.erase("provenance");
  for (const char* k : {"seconds", "build_seconds", "samples_per_second"}) j["summary"].erase(k);
  return j;
}

// report.md less its date line and its speed line.
std::string report_of(const std::string& path) {
  std::string out, line;
  std::istringstream in(slurp(path));
  while (std::getline(in, line))
    if (line.rfind("mfv ", 0) != 0 && line.find("**Speed:**") == std::string::npos) out += line + "\n";
  return out;
}

// Every file of the single run's folder, and no other, in the merge's: equal.
void require_equal_outputs(const std::string& single, const std::string& merged) {
  size_t files = 0;
  for (auto& e : std::filesystem::recursive_directory_iterator(single)) {
    if (!e.is_regular_file()) continue;
    const std::string rel = std::filesystem::relative(e.path(), single).string();
    const std::string other = merged + "/" + rel;
    INFO(rel);
    REQUIRE(std::filesystem::exists(other));
    ++files;
    if (rel == "energy.json")
      CHECK(values_of(e.path().string()) == values_of(other));
    else if (rel == "report.md")
      CHECK(report_of(e.path().string()) == report_of(other));
    else
      CHECK(slurp(e.path().string()) == slurp(other));
  }
  size_t merged_files = 0;
  for (auto& e : std::filesystem::recursive_directory_iterator(merged)) merged_files += e.is_regular_file();
  CHECK(merged_files == files);
  CHECK(files >= 5);  // energy.json, report.md, kulla_conty.h, csv/, layout/
}

}  // namespace

TEST_CASE("energy shards are contiguous runs of units of equal estimated cost", "[shard][energy]") {
  const std::vector<uint64_t> cost{32, 32, 64, 32, 64, 64, 32, 32};  // 2R for a glass cell
  size_t next = 0;
  for (uint32_t k = 0; k < 3; ++k) {
    auto [lo, hi] = cut_by_cost(cost, {k, 3, ""});
    CHECK(lo == next);
    next = hi;
  }
  CHECK(next == cost.size());
  CHECK(cut_by_cost(cost, {0, 3, ""}) == std::pair<size_t, size_t>{0, 3});  // 128 of 352
  CHECK(cut_by_cost(cost, {1, 3, ""}) == std::pair<size_t, size_t>{3, 5});  // 96
  CHECK(cut_by_cost(cost, {2, 3, ""}) == std::pair<size_t, size_t>{5, 8});  // 128
  // more shards than units: empty ones
  CHECK(cut_by_cost({5}, {0, 3, ""}) == std::pair<size_t, size_t>{0, 0});
  CHECK(cut_by_cost({5}, {1, 3, ""}) == std::pair<size_t, size_t>{0, 1});
  CHECK(cut_by_cost({5}, {2, 3, ""}) == std::pair<size_t, size_t>{1, 1});
}

TEST_CASE("three mfv energy shards merged equal the single run value for value, one with its index from Bazel's "
          "variables, and each bad merge input exits 2 naming the shard",
          "[shard][energy][device]") {
  if (!device_runtime()) return;
  Scratch s("mfv_energy_shard");
  const Run single = run_mfv(kRun + " --out " + s / "single");
  INFO(single.out);
  REQUIRE(single.code == 0);
  const std::string s1 = s / "s1", s2 = s / "s2", s3 = s / "s3";
  auto shard = [&](const std::string& dir, const std::string& args, const std::string& env, const std::string& from) {
    auto r = run_mfv(kRun + args + " --out " + dir, env);
    INFO(r.out);
    REQUIRE(r.code == 0);
    CHECK(r.out.find(from) != std::string::npos);
    CHECK(std::filesystem::exists(dir + "/energy_shard.json"));
  };
  const std::string status = s / "bazel_status";
  shard(s1, " --shard 1/3", "", "shard 1/3 (from --shard)");
  shard(s2, "", "TEST_TOTAL_SHARDS=3 TEST_SHARD_INDEX=1 TEST_SHARD_STATUS_FILE=" + status,
        "shard 2/3 from TEST_SHARD_INDEX/TEST_TOTAL_SHARDS (Bazel)");
  CHECK(std::filesystem::exists(status));
  shard(s3, " --shard 3/3", "", "shard 3/3 (from --shard)");
  // the shards in any order on the command line
  auto m = run_mfv(kRun + " --merge " + s3 + " " + s1 + " " + s2 + " --out " + s / "merged");
  INFO(m.out);
  REQUIRE(m.code == single.code);
  require_equal_outputs(s / "single", s / "merged");
  const json shards = json::parse(slurp(s / "merged/energy.json")).at("provenance").at("shards");
  REQUIRE(shards.size() == 3);
  CHECK(shards[1].get<std::string>().find("TEST_SHARD_INDEX") != std::string::npos);

  // bad inputs: exit 2, one line naming the shard, nothing written
  const BadMerges bad{s, kRun, "energy_shard.json", "energy.json"};
  bad.common(s1, s2, s3);
  // foreign shards: another seed, another plan (than a shard, or the merge's options)
  bad.foreign(s1, s2, s3, kBase + " --target 5e-5 --seed 6", "ran seed 6", "ran seed 5");
  bad.foreign(s1, s2, s3, kBase + " --target 6e-5 --seed 5", "ran another plan", "ran another plan");
}

TEST_CASE("mfv energy --shard: a bad K/N, no --out, --merge with --shard, or a bad engine variable is a one-line "
          "error",
          "[shard][energy][cli]") {
  for (const char* args : {"energy --shard 0/2 --out /tmp/x", "energy --shard 3/2 --out /tmp/x", "energy --shard 1/2",
                           "energy --shard 1/2 --merge /tmp --out /tmp/x"}) {
    auto r = run_mfv(args);
    INFO(args << "\n" << r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: ", 0) == 0);
  }
  auto r = run_mfv("energy --out /tmp/x", "TEST_TOTAL_SHARDS=2 TEST_SHARD_INDEX=5");
  CHECK(r.code == 2);
  CHECK(r.out.find("TEST_SHARD_INDEX") != std::string::npos);
}
