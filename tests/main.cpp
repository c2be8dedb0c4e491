// The test runner: Catch2's, and visible skips (tests/skip.hpp). A test case
// run alone (as CTest runs each: catch_discover_tests) that skipped what it
// could not run (no OpenCL device, no cl_khr_fp64, an implementation not
// installed) and failed nothing exits with test::kSkipExitCode, which CTest's
// SKIP_RETURN_CODE reports as skipped, never as passed. The mfv runs it
// starts fork no compile-ahead child unless a test sets MFV_COMPILE_AHEAD:
// the default, on where a core is free, would make them depend on the load.
#define CATCH_CONFIG_RUNNER
#include "skip.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>

int main(int argc, char* argv[]) {
  ::setenv("MFV_COMPILE_AHEAD", "0", /*overwrite=*/0);
  Catch::Session session;
  if (int rc = session.applyCommandLine(argc, argv); rc != 0) return rc;
  const int failed = session.run();
  const bool one_case = session.configData().testsOrTags.size() == 1;
  if (failed == 0 && one_case && mfv::test::skips() > 0) return mfv::test::kSkipExitCode;
  return failed;
}
