// mfv bench --device all: every device of every platform in one table;
// mfv run --device all (or a list) shares every plan among the devices and
// gives the one-device run's records; other commands take one device and
// reject "all" or a list with one error line.
#include "device_fixture.hpp"
#include "run_mfv.hpp"
#include "checks/device_share.hpp"
#include "runtime/opencl.hpp"
#include "test_files.hpp"

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

using mfv::test::run_mfv;

TEST_CASE("bench --device all puts every device in one table", "[device][bench]") {
  if (!mfv::test::device_runtime()) return;
  auto r = run_mfv(
      "--device all bench --integrals 4 --samples 1024 --ref-samples 64 --repeats 1 --threads 1 "
      "--integrand d_norm");
  CAPTURE(r.out);
  REQUIRE(r.code == 0);
  for (auto& d : mfv::list_devices()) {
    CAPTURE(d.name);
    CHECK(r.out.find(d.name) != std::string::npos);
  }
}

TEST_CASE("The device selector all is rejected by commands that run on one device", "[cli]") {
  if (!mfv::test::device_runtime()) return;
  auto r = run_mfv("--device all agree --samples 10");
  CAPTURE(r.out);
  CHECK(r.code == 2);
  CHECK(r.out.rfind("mfv: error: --device all is for 'mfv bench' and 'mfv run' only", 0) == 0);
  r = run_mfv("--device 0,0 agree --samples 10");
  CHECK(r.code == 2);
  CHECK(r.out.rfind("mfv: error: --device 0,0 is for 'mfv bench' and 'mfv run' only", 0) == 0);
  for (const char* args : {"--device 0,0 run --dry-run", "--device all run --shard 1/2 --out /tmp/x",
                           "--device 0, run --check d_norm"}) {
    r = run_mfv(args);
    INFO(args << "\n" << r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: ", 0) == 0);
  }
}

TEST_CASE("a plan shared among devices takes chunks of at least 16 integrals, about 8 per device", "[cli]") {
  CHECK(mfv::share_chunk(10, 2) == 10);
  CHECK(mfv::share_chunk(100, 2) == 16);
  CHECK(mfv::share_chunk(1600, 2) == 100);
  CHECK(mfv::share_chunk(1601, 2) == 101);
  CHECK(mfv::share_chunk(0, 3) == 1);
}

namespace {
nlohmann::json records_and_verdicts(const std::string& dir) {
  auto r = nlohmann::json::parse(mfv::test::slurp(dir + "/results.json"));
  return {r.at("results"), r.at("groups"), r.at("run").at("tests"), r.at("reference")};
}
}  // namespace

TEST_CASE("mfv run --device on two devices shares every plan and gives the one-device run record for record",
          "[device][cli]") {
  if (!mfv::test::device_runtime()) return;
  mfv::test::Scratch s("mfv_devices");
  // the same device twice (two contexts and queues: this machine has one
  // device), and all of this machine's devices
  const std::string base =
      "--quiet run --scale 0.05 --seed 3 --model ggx --model charlie --check d_norm --check masking --check furnace "
      "--check energy --check reciprocity --out ";
  const auto one = run_mfv("--device 0 " + base + s / "one");
  REQUIRE(one.code <= 1);
  const auto two = run_mfv("--device 0,0 " + base + s / "two");
  INFO(two.out);
  REQUIRE(two.code == one.code);
  const auto all = run_mfv("--device all " + base + s / "all");
  REQUIRE(all.code == one.code);
  const nlohmann::json a = records_and_verdicts(s / "one");
  for (const char* d : {"two", "all"}) {
    const nlohmann::json b = records_and_verdicts(s / d);
    REQUIRE(a[0].size() == b[0].size());
    for (size_t i = 0; i < a[0].size(); ++i) {
      INFO(d << " record " << i);
      REQUIRE(a[0][i] == b[0][i]);
    }
    CHECK(a == b);
  }
  // both devices took work, and together every integral of the plans
  const auto r = nlohmann::json::parse(mfv::test::slurp(s / "two/results.json"));
  const auto& shared = r.at("device").at("shared");
  REQUIRE(shared.size() == 2);
  uint64_t integrated = 0, planned = 0;
  for (auto& d : shared) {
    CHECK(d.at("integrals").get<uint64_t>() > 0);
    integrated += d.at("integrals").get<uint64_t>();
  }
  for (auto& t : r.at("timings"))
    if (t.at("check") != "reciprocity") planned += t.at("integrals").get<uint64_t>();
  CHECK(integrated == planned);
}
