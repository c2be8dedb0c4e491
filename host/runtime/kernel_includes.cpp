#include "runtime/kernel_includes.hpp"

#include "util/error.hpp"

#include <fmt/format.h>

#include <sstream>

namespace mfv {
namespace {

// The quoted name of `#include "NAME"` (spaces allowed around '#'), else "".
std::string included_name(const std::string& line) {
  size_t i = line.find_first_not_of(" \t");
  if (i == std::string::npos || line[i] != '#') return "";
  i = line.find_first_not_of(" \t", i + 1);
  if (i == std::string::npos || line.compare(i, 7, "include") != 0) return "";
  size_t open = line.find('"', i + 7), close = open == std::string::npos ? open : line.find('"', open + 1);
  if (close == std::string::npos) return "";
  return line.substr(open + 1, close - open - 1);
}

// The name in the text's first line, `#line 1 "NAME"`.
std::string display_name(const std::string& text) {
  size_t open = text.find('"'), close = open == std::string::npos ? open : text.find('"', open + 1);
  if (text.rfind("#line 1 \"", 0) != 0 || close == std::string::npos) return "";
  return text.substr(open + 1, close - open - 1);
}

std::string expand(const std::string& text, const std::function<std::string(const std::string&)>& load,
                   std::set<std::string>& seen, std::set<std::string>& open_files) {
  const std::string self = display_name(text);
  std::istringstream in(text);
  std::string out, line;
  for (int number = 0; std::getline(in, line);) {
    ++number;
    const std::string name = included_name(line);
    if (name.rfind("abi/", 0) != 0 || number == 1) {  // other includes are the compiler's
      out += line + "\n";
      continue;
    }
    if (open_files.count(name)) throw Error(fmt::format("kernel file {} includes itself (through {})", name, self));
    if (seen.insert(name).second) {
      open_files.insert(name);
      out += expand(load(name), load, seen, open_files);
      open_files.erase(name);
    }
    out += fmt::format("#line {} \"{}\"\n", number + 1, self);
  }
  return out;
}

}  // namespace

std::string expand_kernel_includes(const std::string& text, const std::function<std::string(const std::string&)>& load,
                                   std::set<std::string>& seen) {
  std::set<std::string> open_files;
  return expand(text, load, seen, open_files);
}

}  // namespace mfv
