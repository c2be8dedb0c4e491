#include "runtime/build_options.hpp"

#include "util/error.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cstdlib>
#include <sstream>

namespace mfv {

namespace {

bool option_like(const std::string& t) {
  if (t.size() < 2 || t[0] != '-') return false;
  for (unsigned char c : t)
    if (!std::isalnum(c) && c != '_' && c != '=' && c != '.' && c != ',' && c != '+' && c != '-') return false;
  return true;
}

}  // namespace

std::string cl_options_from_env() {
  const char* env = std::getenv("MFV_CL_OPTIONS");
  if (!env) return "";
  std::istringstream in(env);
  std::string options;
  for (std::string t; in >> t;) {
    if (!option_like(t))
      throw Error(fmt::format("MFV_CL_OPTIONS: '{}' is not an OpenCL build option (expected -NAME, e.g. -Werror)", t));
    options += " " + t;
  }
  return options;
}

}  // namespace mfv
