// Kernel sources compiled into the binary by cmake/EmbedKernels.cmake.
#pragma once
#include <string>
#include <vector>

namespace mfv {

struct EmbeddedKernel {
  const char* name;  // file name under kernels/
  const char* text;  // starts with #line 1 "name"
};

const std::vector<EmbeddedKernel>& embedded_kernels();

}  // namespace mfv
