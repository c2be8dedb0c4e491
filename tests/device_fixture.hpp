// Device tests share one Runtime; where no OpenCL platform exists they are
// skipped with a message instead of failing.
#pragma once

#include "runtime/opencl.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>

#include <memory>

namespace mfv::test {

inline Runtime* device_runtime() {
  static std::unique_ptr<Runtime> rt;
  static bool tried = false;
  if (!tried) {
    tried = true;
    try {
      rt = std::make_unique<Runtime>("");
    } catch (const Error& e) {
      WARN("no OpenCL device, device test skipped: " << e.what());
    }
  }
  return rt.get();
}

}  // namespace mfv::test
