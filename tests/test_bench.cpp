// mfv bench: one small run on the default device writes a complete JSON
// record; bad options exit 2 with one line.
#include "run_mfv.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

using mfv::test::run_mfv;

TEST_CASE("mfv bench measures devices and the reference in one run", "[bench][cli]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("mfv_bench_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  auto r = run_mfv("bench --integrals 8 --samples 4096 --ref-samples 128 --repeats 3 --threads 2 --out " +
                   dir.string());
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
      CHECK(row["vs_reference_x1"].get<double>() > 0);
    }
    // d_norm: the mean of the normalization integrals is 1 on every engine
    if (row["integrand"] == "d_norm") CHECK(std::fabs(row["checksum"].get<double>() - 1.0) < 0.02);
  }
  CHECK(integrands == std::set<std::string>{"d_norm", "albedo", "reciprocity"});
  CHECK(engines.count("reference x1") == 1);
  CHECK(engines.count("reference x2") == 1);
  CHECK(engines.size() >= 3);  // at least one device
  fs::remove_all(dir);
}

TEST_CASE("mfv bench rejects bad options with one line", "[bench][cli]") {
  for (const char* args : {"bench --repeats 0", "bench --integrand furnace", "bench --samples 1"}) {
    auto r = run_mfv(args);
    INFO(args << ": " << r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error:", 0) == 0);
  }
}
