#include "cli/report_errors.hpp"

#include "util/error.hpp"

#include <CL/opencl.hpp>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <new>

namespace mfv::cli {

int run_reporting_errors(const std::function<int()>& work) {
  try {
    return work();
  } catch (const CLI::CallForHelp&) {
    throw;  // main prints the help
  } catch (const CLI::CallForAllHelp&) {
    throw;
  } catch (const CLI::CallForVersion&) {
    throw;  // main prints the version
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "mfv: error: %s (see 'mfv --help')\n", e.what());
  } catch (const mfv::Error& e) {
    std::fprintf(stderr, "mfv: error: %s\n", e.what());
  } catch (const cl::Error& e) {
    std::fprintf(stderr, "mfv: error: OpenCL call %s failed with code %d\n", e.what(), e.err());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "mfv: error: out of host memory; lower --samples\n");
  } catch (const std::exception& e) {
    // a safety net: a library's exception the input check missed is still one line and exit 2
    std::fprintf(stderr, "mfv: error: unexpected: %s\n", e.what());
  }
  return 2;
}

}  // namespace mfv::cli
