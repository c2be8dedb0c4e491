// results.json's records are dumped on the host's threads and joined
// (report/suite_report.cpp): the text must be the bytes of dumping the whole
// object at once.
#include "catalog/catalog.hpp"
#include "report/suite_report.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace mfv;

namespace {

// Records of every shape point_record writes: NaN and infinite values, a
// known value, a reference failure with quotes, backslashes and non-ASCII
// text, a measured maximum, an expectation.
std::vector<PointResult> varied_points(size_t n) {
  std::vector<PointResult> out(n);
  for (size_t i = 0; i < n; ++i) {
    PointResult& p = out[i];
    p.check = i % 2 ? "furnace" : "d_norm";
    p.d = &find_term("ggx");
    p.g = i % 3 ? &find_term("smith_ggx") : nullptr;
    p.params = {{"alpha", 0.01 * double(i + 1)}, {"cos_o", 1.0 / double(i + 1)}};
    p.estimate = i % 7 == 3 ? std::numeric_limits<double>::quiet_NaN() : 1.0 + 1e-3 * double(i);
    p.z = i % 11 == 5 ? std::numeric_limits<double>::infinity() : -0.5 * double(i);
    p.stderr_ = i % 29 == 6 ? 1e-320 : 1e-4 / double(i + 1);  // a subnormal (a glass cell's SE) reads back
    p.samples = 4096 * i;
    p.known = i % 5 == 1;
    p.known_value = 0.9 - 1e-5 * double(i);
    p.known_error = 2e-9;
    p.reference_failed = i % 13 == 7;
    p.reference_detail = "twin \"0.5\" vs reference \\ 0.4 \xce\x9b \xc2\xb1 1e-3\n";
    p.expect = i % 17 == 2 ? Expect::Fail : Expect::Hold;
    p.bounded = i % 19 == 4;
    p.measure = "max asymmetry";
    p.detail = i % 19 == 4 ? "at l=(0.1, 0.2, 0.97)" : "";
    p.failed = i % 23 == 9;
  }
  return out;
}

std::string dump_at_once(const std::vector<PointResult>& points) {
  nlohmann::json j = {{"schema", "mfv-run/1"}, {"groups", nlohmann::json::array()}, {"tool", {{"name", "mfv"}}}};
  j["results"] = nlohmann::json::array();
  for (auto& p : points) j["results"].push_back(point_record(p));
  return j.dump();
}

std::string dump_joined(const std::vector<PointResult>& points) {
  nlohmann::json j = {{"schema", "mfv-run/1"}, {"groups", nlohmann::json::array()}, {"tool", {{"name", "mfv"}}}};
  j["results"] = nlohmann::json::array();
  return dump_with_results(j, results_array_json(points));
}

}  // namespace

TEST_CASE("results.json's records dumped apart and joined are the bytes of one dump", "[report][json]") {
  for (size_t n : {0, 1, 2, 1000}) {
    INFO(n << " records");
    const std::vector<PointResult> points = varied_points(n);
    CHECK(dump_joined(points) == dump_at_once(points));
  }
}

TEST_CASE("The joined results.json differs where one record differs", "[report][json][planted]") {
  std::vector<PointResult> points = varied_points(50);
  const std::string before = dump_joined(points);
  points[30].estimate += 1e-6;  // one record's value moves: the joined text must show it
  CHECK(dump_joined(points) != before);
  CHECK(dump_joined(points) == dump_at_once(points));
}
