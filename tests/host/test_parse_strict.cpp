// Strict numbers (util/parse.hpp): counts and seeds never wrap, saturate or
// truncate; NaN and Inf are rejected (issue 17). Host-only: also run under
// AddressSanitizer and UBSan (cmake/Sanitize.cmake).
#include "util/error.hpp"
#include "util/parse.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>

namespace {

template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const mfv::Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("parse_unsigned takes whole numbers in range, in digits or exact exponent form", "[parse]") {
  CHECK(mfv::parse_unsigned("--seed", "0") == 0);
  CHECK(mfv::parse_unsigned("--seed", "18446744073709551615") == UINT64_MAX);
  CHECK(mfv::parse_unsigned("--samples", "1e6") == 1000000);
  CHECK(mfv::parse_unsigned("--samples", "4096.0") == 4096);
  CHECK(mfv::parse_unsigned("--samples", "+7") == 7);
  CHECK(mfv::parse_unsigned("--samples", "1e19") == 10000000000000000000ull);
  CHECK(mfv::parse_unsigned("--n", "100", 100) == 100);
}

TEST_CASE("parse_unsigned rejects what CLI11 wrapped, saturated or truncated", "[parse]") {
  struct Case {
    const char* text;
    const char* expect;
  };
  auto c = GENERATE(Case{"-1", "negative"}, Case{"18446744073709551616", "out of range"},  // 2^64
                    Case{"1e23", "out of range"}, Case{"2e19", "out of range"}, Case{"1.5", "not a whole number"},
                    Case{"nan", "not a finite number"}, Case{"inf", "not a finite number"},
                    Case{"1e400", "not a finite number"}, Case{"", "not a number"}, Case{" 5", "not a number"},
                    Case{"5 ", "not a number"}, Case{"12abc", "not a number"}, Case{"0x", "not a number"},
                    Case{"99999999999999999999999", "out of range"});
  CAPTURE(c.text);
  std::string e = error_of([&] { mfv::parse_unsigned("--seed", c.text); });
  CAPTURE(e);
  CHECK(e.rfind("--seed: ", 0) == 0);
  CHECK(e.find(c.expect) != std::string::npos);
  CHECK(error_of([&] { mfv::parse_unsigned("--n", "101", 100); }).find("out of range [0, 100]") != std::string::npos);
}

TEST_CASE("parse_signed covers the whole int64 range and nothing beyond", "[parse]") {
  CHECK(mfv::parse_signed("--k", "-9223372036854775808") == INT64_MIN);
  CHECK(mfv::parse_signed("--k", "9223372036854775807") == INT64_MAX);
  CHECK(mfv::parse_signed("--k", "-1e3") == -1000);
  CHECK(error_of([&] { mfv::parse_signed("--k", "9223372036854775808"); }).find("out of range") != std::string::npos);
  CHECK(error_of([&] { mfv::parse_signed("--k", "-9223372036854775809"); }).find("out of range") != std::string::npos);
  CHECK(error_of([&] { mfv::parse_signed("--k", "-1e19"); }).find("out of range") != std::string::npos);
  CHECK(error_of([&] { mfv::parse_signed("--k", "5", 6, 7); }).find("out of range [6, 7]") != std::string::npos);
}

TEST_CASE("parse_finite rejects NaN, infinities and overflow", "[parse]") {
  CHECK(mfv::parse_finite("--scale", "1e300") == 1e300);
  CHECK(mfv::parse_finite("--scale", "-0.5") == -0.5);
  for (const char* t : {"nan", "NaN", "inf", "-inf", "1e400", "-1e400", "infinity"}) {
    CAPTURE(t);
    CHECK(error_of([&] { mfv::parse_finite("--scale", t); }).find("not a finite number") != std::string::npos);
  }
}
