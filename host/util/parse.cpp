#include "util/parse.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace mfv {
namespace {

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

// Decimal digits without wrapping; false when the value exceeds `hi`.
bool digits_value(const std::string& s, uint64_t hi, uint64_t& v) {
  v = 0;
  for (char c : s) {
    uint64_t d = uint64_t(c - '0');
    if (v > (hi - d) / 10) return false;  // v * 10 + d > hi, tested without overflow
    v = v * 10 + d;
  }
  return true;
}

// |value| of `text` without its sign, at most `hi`; `range` names the range in errors.
uint64_t magnitude(const std::string& what, const std::string& text, const std::string& body, uint64_t hi,
                   const std::string& range) {
  uint64_t v = 0;
  if (all_digits(body)) {
    if (!digits_value(body, hi, v)) throw Error(fmt::format("{}: {} is out of range {}", what, text, range));
    return v;
  }
  if (std::any_of(body.begin(), body.end(), [](unsigned char c) { return std::isspace(c); }))
    throw Error(fmt::format("{}: '{}' is not a number", what, text));
  double x = parse_number(what, body);
  if (!std::isfinite(x)) throw Error(fmt::format("{}: '{}' is not a finite number", what, text));
  if (x != std::floor(x)) throw Error(fmt::format("{}: {} is not a whole number", what, text));
  // 2^64 is exact in double; every double below it with no fraction converts exactly.
  if (x < 0 || x >= 0x1p64 || uint64_t(x) > hi)
    throw Error(fmt::format("{}: {} is out of range {}", what, text, range));
  return uint64_t(x);
}

}  // namespace

uint64_t parse_unsigned(const std::string& what, const std::string& text, uint64_t hi) {
  const std::string range = fmt::format("[0, {}]", hi);
  if (!text.empty() && text[0] == '-' && text != "-0")
    throw Error(fmt::format("{}: {} is negative; give a whole number in {}", what, text, range));
  return magnitude(what, text, !text.empty() && (text[0] == '+' || text[0] == '-') ? text.substr(1) : text, hi, range);
}

int64_t parse_signed(const std::string& what, const std::string& text, int64_t lo, int64_t hi) {
  const std::string range = fmt::format("[{}, {}]", lo, hi);
  bool negative = !text.empty() && text[0] == '-';
  std::string body = !text.empty() && (text[0] == '+' || negative) ? text.substr(1) : text;
  // magnitudes up to 2^63 (INT64_MIN's), then the range proper
  uint64_t m = magnitude(what, text, body, uint64_t(INT64_MAX) + 1, range);
  if (!negative && m > uint64_t(INT64_MAX)) throw Error(fmt::format("{}: {} is out of range {}", what, text, range));
  int64_t v = negative ? (m == uint64_t(INT64_MAX) + 1 ? INT64_MIN : -int64_t(m)) : int64_t(m);
  if (v < lo || v > hi) throw Error(fmt::format("{}: {} is out of range {}", what, text, range));
  return v;
}

double parse_finite(const std::string& what, const std::string& text) {
  double v = parse_number(what, text);
  if (!std::isfinite(v)) throw Error(fmt::format("{}: '{}' is not a finite number", what, text));
  return v;
}

}  // namespace mfv
