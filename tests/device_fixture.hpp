// Device tests share one Runtime; where no OpenCL platform exists (or, for
// float64 tests, no cl_khr_fp64) they are skipped with a message instead of
// failing, and CTest reports them skipped (tests/skip.hpp), not passed.
#pragma once

#include "runtime/opencl.hpp"
#include "skip.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>

#include <memory>
#include <string>

namespace mfv::test {

inline Runtime* device_runtime() {
  static std::unique_ptr<Runtime> rt;
  static bool tried = false;
  static std::string why;
  if (!tried) {
    tried = true;
    try {
      rt = std::make_unique<Runtime>("");
    } catch (const Error& e) {
      why = e.what();
    }
  }
  if (!rt) skip("no OpenCL device: " + why);
  return rt.get();
}

// The shared Runtime where its device has cl_khr_fp64; else null, and `what`
// (the float64 part of a test) is skipped with a message.
inline Runtime* fp64_runtime(const std::string& what) {
  Runtime* rt = device_runtime();
  if (rt && !rt->device().fp64) {
    skip("device has no cl_khr_fp64: " + what);
    return nullptr;
  }
  return rt;
}

// PoCL builds the kernels specialized per term pair or model
// (runtime/specialize.hpp); other drivers do not.
inline bool is_pocl(const Runtime& rt) {
  return rt.device().platform.find("Portable Computing Language") != std::string::npos;
}

}  // namespace mfv::test
