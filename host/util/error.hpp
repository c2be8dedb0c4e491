// The one error type the CLI turns into a one-line message and exit code 2.
#pragma once
#include <stdexcept>
#include <string>

namespace mfv {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace mfv
