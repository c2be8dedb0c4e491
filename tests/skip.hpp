// Visible skips: a test that cannot run (no OpenCL device, no cl_khr_fp64, a
// second OpenCL implementation not installed) calls test::skip(why) and
// returns. The message is shown (WARN) and, where CTest runs the test case
// alone, the runner exits with kSkipExitCode (tests/main.cpp), which CTest
// reports as skipped (SKIP_RETURN_CODE, CMakeLists.txt), never as passed.
#pragma once

#include <catch2/catch.hpp>

#include <string>

namespace mfv::test {

constexpr int kSkipExitCode = 77;  // the Automake convention for "skipped"

inline int& skip_count() {
  static int n = 0;
  return n;
}
inline int skips() { return skip_count(); }

inline void skip(const std::string& why) {
  WARN("skipped: " << why);
  ++skip_count();
}

}  // namespace mfv::test
