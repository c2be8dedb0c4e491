// mfv check runs user code, which may never return, and an OpenCL kernel
// cannot be pre-empted: the work runs in a child process (fork) that the
// parent kills when the time limit passes (issue 17).
#pragma once

#include <functional>
#include <string>

namespace mfv {

// Runs `work` in a child process and returns its exit code. After `seconds`
// the child gets SIGTERM (its handlers remove temporary files), a second
// later SIGKILL, and this throws mfv::Error naming `what` and the limit. The
// child gets SIGTERM when the parent dies (PR_SET_PDEATHSIG), so none is orphaned.
// Call it before any OpenCL object exists: only the calling thread survives
// a fork.
int run_with_time_limit(double seconds, const std::string& what, const std::function<int()>& work);

}  // namespace mfv
