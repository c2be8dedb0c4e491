#pragma once

#include <string>

namespace mfv {

// Extra OpenCL C build options from the environment variable MFV_CL_OPTIONS,
// appended to every kernel build (and so recorded with the pinned options in
// results files). For checking the kernels themselves, e.g. `-Werror` (the
// portability tests: every kernel compiles warning-free on every
// implementation) or `-cl-denorms-are-zero` (a flush-to-zero build on a
// device that keeps denormals). Empty when unset. Throws mfv::Error unless it
// is whitespace-separated options, each `-` followed by letters, digits and
// `_ = . , + -` (no quoting, no file names with other characters).
std::string cl_options_from_env();

}  // namespace mfv
