// mfv bench: one small run on the default device writes a complete JSON
// record; bad options exit 2 with one line.
#include "run_mfv.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>

using mfv::test::run_mfv;

TEST_CASE("mfv bench measures devices and the reference in one run", "[bench][cli]") {
  namespace fs = std::filesystem;
  const mfv::test::Scratch scratch("mfv_bench");
  const fs::path dir = scratch.dir / "out";
  auto r =
      run_mfv("bench --integrals 8 --samples 4096 --ref-samples 128 --repeats 3 --threads 2 --out " + dir.string());
  INFO(r.out);
  REQUIRE(r.code == 0);
  std::ifstream in(dir / "bench.json");
  const auto j = nlohmann::json::parse(in);
  CHECK(j["schema"] == "mfv-bench/1");
  CHECK(!j["date"].get<std::string>().empty());
  std::set<std::string> engines, integrands;
  for (const auto& row : j["rows"]) {
    engines.insert(row["engine"].get<std::string>());
    integrands.insert(row["integrand"].get<std::string>());
    CHECK(row["seconds"].size() == 3);
    CHECK(row["samples_per_second"].get<double>() > 0);
    CHECK(std::isfinite(row["checksum"].get<double>()));
    if (row.contains("driver")) {
      CHECK(!row["driver"].get<std::string>().empty());
      // each device row's share of the same device's FMA-bound peak row
      CHECK(row["fraction_of_peak"].get<double>() > 0);
      if (row["integrand"] == "peak") {
        CHECK(row["fraction_of_peak"].get<double>() == 1.0);
        CHECK(row["gflops_per_cpu_second"].get<double>() > 0);
      } else {
        CHECK(row["vs_reference_x1"].get<double>() > 0);
        CHECK(row["fraction_of_peak"].get<double>() < 1.0);  // an integrand cannot beat the peak
      }
    }
    // d_norm: the mean of the normalization integrals is 1 on every engine
    if (row["integrand"] == "d_norm") CHECK(std::fabs(row["checksum"].get<double>() - 1.0) < 0.02);
  }
  CHECK(integrands == std::set<std::string>{"d_norm", "albedo", "reciprocity", "peak"});
  CHECK(engines.count("reference x1") == 1);
  CHECK(engines.count("reference x2") == 1);
  CHECK(engines.size() >= 3);  // at least one device
}

TEST_CASE("mfv bench rejects bad options with one line", "[bench][cli]") {
  for (const char* args :
       {"bench --repeats 0", "bench --integrand furnace", "bench --samples 1", "bench --case ggx",
        "bench --case ggx/smith_ggx_correlated/none:0.5", "bench --case nope/smith_ggx_correlated/none:0.5:0.5",
        "bench --case ggx/ggx/none:0.5:0.5", "bench --case ggx/smith_ggx_correlated/none:x:0.5",
        "bench --case ggx/smith_ggx_correlated/none:0.5:0", "bench --case ggx/smith_ggx_correlated/none:0.5:1.5",
        "bench --case ggx/smith_ggx_correlated/none:-1:0.5", "bench --case ggx/smith_ggx_correlated/none/x:0.5:0.5"}) {
    auto r = run_mfv(args);
    INFO(args << ": " << r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error:", 0) == 0);
  }
}

TEST_CASE("mfv bench --case gives one integral's time to standard errors of 1e-4 and 1e-5", "[bench][cli][mis]") {
  namespace fs = std::filesystem;
  const mfv::test::Scratch scratch("mfv_bench_case");
  const fs::path dir = scratch.dir / "out";
  auto r = run_mfv("bench --case ggx/smith_ggx_correlated/none:0.5:0.5 --repeats 3 --out " + dir.string());
  INFO(r.out);
  REQUIRE(r.code == 0);
  std::ifstream in(dir / "bench.json");
  const auto j = nlohmann::json::parse(in);
  CHECK(j["schema"] == "mfv-bench-case/1");
  CHECK(j["samples_per_s"].get<double>() > 0);
  CHECK(j["variance_per_sample"].get<double>() > 0);
  CHECK(j["seconds_to_se_1e-4"].get<double>() > 0);
  // each target's call is the fewest timed points whose rms SE reached it (the rule
  // scripts/bench-peers.sh applies to Mitsuba 3's sizes): every count below it missed it,
  // and the grid goes one count beyond the 1e-5 call; the estimate is the quadrature's
  // 0.6982507 within 6 of its standard errors
  const auto& grid = j["grid"];
  REQUIRE(grid.size() >= 2);
  for (const auto& t : j["targets"]) {
    const double target = t["target_se"].get<double>();
    CHECK(t["rms_stderr"].get<double>() <= target);
    for (const auto& g : grid) {
      INFO("target " << target << ", count " << g["points_per_replicate"]);
      if (g["points_per_replicate"].get<uint32_t>() < t["points_per_replicate"].get<uint32_t>())
        CHECK(g["rms_stderr"].get<double>() > target);
      if (g["points_per_replicate"] == t["points_per_replicate"])
        CHECK(g["median_seconds"].get<double>() == t["median_seconds"].get<double>());
    }
  }
  CHECK(grid.back()["points_per_replicate"].get<uint32_t>() ==
        2 * j["targets"][1]["points_per_replicate"].get<uint32_t>());
  CHECK(j["rms_stderr"].get<double>() <= 1e-4);
  CHECK(std::fabs(j["estimate"].get<double>() - 0.6982507) < 6 * j["stderr"].get<double>());
  // the second target: one call's wall time and SE at 1e-5, more points than at 1e-4
  REQUIRE(j["targets"].size() == 2);
  const auto& t = j["targets"][1];
  CHECK(t["target_se"].get<double>() == 1e-5);
  CHECK(t["points_per_replicate"].get<uint32_t>() >= j["targets"][0]["points_per_replicate"].get<uint32_t>());
  CHECK(t["median_seconds"].get<double>() > 0);
  CHECK(j["seconds_to_se_1e-5"].get<double>() == t["seconds_to_se"].get<double>());
  CHECK(std::fabs(t["estimate"].get<double>() - 0.6982507) < 6 * t["stderr"].get<double>());
}
