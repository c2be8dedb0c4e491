// Streams keyed by identity (host/checks/streams.hpp): an integral's Philox
// stream depends on what it is, never on what else its plan holds, so adding
// a check, a term or a point leaves every other integral's samples as they
// were; a plan holding one integral twice is an error naming it.
#include "albedo_spec.hpp"
#include "checks/streams.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

using namespace mfv;

namespace {
IntegralSpec furnace_at(double alpha, double cos_o) {
  return test::albedo_spec("ggx", "smith_ggx_correlated", "none", alpha, cos_o, 0.0, 0.0, 0, IntegralKind::AlbedoMis);
}
}  // namespace

TEST_CASE("An integral's stream does not depend on the other integrals of its plan", "[streams]") {
  std::vector<IntegralSpec> a = {furnace_at(0.3, 0.5), furnace_at(0.1, 0.9)};
  // the same two with a new point before, between and after them
  std::vector<IntegralSpec> b = {furnace_at(0.7, 0.2), a[1], furnace_at(0.2, 0.2), a[0]};
  assign_streams("furnace", a);
  assign_streams("furnace", b);
  CHECK(a[0].stream == b[3].stream);
  CHECK(a[0].stream_hi == b[3].stream_hi);
  CHECK(a[1].stream == b[1].stream);
  CHECK(a[1].stream_hi == b[1].stream_hi);
  CHECK(a[0].stream != a[1].stream);
  CHECK(a[0].stream_hi < (1u << 24));  // 56 bits: 24 above the draw in counter word 3
}

TEST_CASE("The stream key names the check, the terms by id and each parameter that is not its default",
          "[streams]") {
  IntegralSpec s = furnace_at(0.3, 0.5);
  const std::string key = integral_key("furnace", s);
  CAPTURE(key);
  CHECK(key.find("check=furnace") != std::string::npos);
  CHECK(key.find("d=ggx g=smith_ggx_correlated f=none") != std::string::npos);
  CHECK(key.find("cos_o=") != std::string::npos);
  CHECK(key.find("eta=") == std::string::npos);  // at its default: a field added with a default moves no key
  CHECK(key.find("stream") == std::string::npos);
  // another check on the same integral, or another parameter, is another stream
  CHECK(stream_of_key(key) != stream_of_key(integral_key("energy", s)));
  s.eta = 1.5f;
  CHECK(stream_of_key(key) != stream_of_key(integral_key("furnace", s)));
  // the sample count is not part of the identity
  IntegralSpec t = furnace_at(0.3, 0.5);
  t.strata = 4096;
  t.points = 128;
  CHECK(integral_key("furnace", t) == key);
}

TEST_CASE("A plan that holds the same integral twice is an error naming it", "[streams]") {
  std::vector<IntegralSpec> twice = {furnace_at(0.3, 0.5), furnace_at(0.1, 0.9), furnace_at(0.3, 0.5)};
  try {
    assign_streams("furnace", twice);
    FAIL("the duplicate should have been refused");
  } catch (const Error& e) {
    const std::string msg = e.what();
    CHECK(msg.find("check furnace holds the same integral twice") != std::string::npos);
    CHECK(msg.find("d=ggx") != std::string::npos);
  }
}
