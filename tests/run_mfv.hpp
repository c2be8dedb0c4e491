// Runs the built mfv binary with arguments and captures its exit code and
// output, for tests of the command line.
#pragma once

#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace mfv::test {

struct Run {
  int code;
  std::string out;  // stdout and stderr together
};

// A shell command line as it is (for tools beside mfv, e.g. pgrep).
inline Run run_mfv_shell(const std::string& cmd_line) {
  FILE* p = popen((cmd_line + " 2>&1").c_str(), "r");
  REQUIRE(p != nullptr);
  std::string out;
  std::array<char, 4096> buf{};
  while (size_t n = fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
  int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// `env` is prefixed to the command (e.g. "MFV_GNUPLOT=/nonexistent").
inline Run run_mfv(const std::string& args, const std::string& env = "") {
  return run_mfv_shell(env + (env.empty() ? "" : " ") + std::string(MFV_BINARY) + " " + args);
}

}  // namespace mfv::test
