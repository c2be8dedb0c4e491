// Kernel files include the layouts they share with the host
// (`#include "abi/pointwise.h"`, kernels/abi/). A program is built from one
// string, so the loader pastes each included file under abi/ in place of its
// #include line (other includes are left to the OpenCL compiler), once per program (later includes of the same file are
// dropped), with #line directives so build logs still point at the right file and line. The same names resolve in the
// embedded sources and under --kernel-dir.
#pragma once

#include <functional>
#include <set>
#include <string>

namespace mfv {

// text: a kernel file as the loader returns it (first line `#line 1 "NAME"`);
// load(name): another file's text in the same form; seen: the files pasted
// so far into this program. Throws mfv::Error for an include of a file
// that does not exist or an include cycle.
std::string expand_kernel_includes(const std::string& text, const std::function<std::string(const std::string&)>& load,
                                   std::set<std::string>& seen);

}  // namespace mfv
