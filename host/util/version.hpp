// The version `mfv --version` prints and the outputs record: the project
// version (CMakeLists.txt) and the build's git description
// (cmake/GitCommit.cmake, taken at build time).
#pragma once

#include "mfv_git_commit.h"

#include <string>

namespace mfv {

inline std::string version_text() { return std::string(MFV_VERSION) + " (git " + MFV_GIT_DESCRIBE + ")"; }

}  // namespace mfv
