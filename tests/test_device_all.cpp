// mfv bench --device all: every device of every platform in one table;
// other commands take one device and reject "all" with one error line.
#include "device_fixture.hpp"
#include "run_mfv.hpp"
#include "runtime/opencl.hpp"

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
  CHECK(r.out.rfind("mfv: error: --device all is for 'mfv bench' only", 0) == 0);
}
