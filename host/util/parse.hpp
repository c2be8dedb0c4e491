// Small text parsing shared by the command line and mfv check's file
// declarations; errors are mfv::Error naming what was being read.
#pragma once

#include "runtime/error.hpp"

#include <fmt/format.h>

#include <sstream>
#include <stdexcept>
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

// The whole of `text` as a number (inf and nan are read, callers range-check).
inline double parse_number(const std::string& what, const std::string& text) {
  try {
    size_t used = 0;
    double v = std::stod(text, &used);
    if (used != text.size()) throw std::invalid_argument(text);
    return v;
  } catch (const std::exception&) {
    throw Error(fmt::format("{}: '{}' is not a number", what, text));
  }
}

}  // namespace mfv
