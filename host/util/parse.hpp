// Small text parsing shared by the command line and mfv check's file
// declarations; errors are mfv::Error naming what was being read.
#pragma once

#include "util/error.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace mfv {

inline std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string part;
  while (std::getline(ss, part, sep)) out.push_back(part);
  return out;
}

// The whole of `text` as a number (inf and nan are read, and a value beyond
// the double range reads as +-inf, below it as 0 or a subnormal: callers
// range-check, parse_finite rejects the non-finite).
inline double parse_number(const std::string& what, const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0])))
    throw Error(fmt::format("{}: '{}' is not a number", what, text));
  char* end = nullptr;
  double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) throw Error(fmt::format("{}: '{}' is not a number", what, text));
  return v;
}

// Strict whole numbers for counts and seeds: decimal digits, or a decimal or
// exponent form whose value is an exact integer ("1e6"); never wrapped,
// saturated or truncated. Throws mfv::Error naming `what` when `text` is not
// such a number in [0, hi] (parse_unsigned) or [lo, hi] (parse_signed).
uint64_t parse_unsigned(const std::string& what, const std::string& text, uint64_t hi = UINT64_MAX);
int64_t parse_signed(const std::string& what, const std::string& text, int64_t lo = INT64_MIN, int64_t hi = INT64_MAX);

// parse_number, and the value must be finite (no nan, inf or overflow to inf).
double parse_finite(const std::string& what, const std::string& text);

}  // namespace mfv
