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
//
// Besides the whole limit (`seconds`, infinite: none), the child may arm a
// watchdog for each step of its work (watchdog_arm): a step that runs past
// its own limit is stopped the same way, so a user BRDF that never returns
// is stopped within the limit of the step it hangs in, not the whole run's.
// `step_limits` false: the whole limit alone (a limit the user chose), the
// steps' watchdogs are not armed.
int run_with_time_limit(double seconds, const std::string& what, const std::function<int()>& work,
                        bool step_limits = true);

// In the child of run_with_time_limit: the next step must end within
// `seconds` (named `step` in the message); watchdog_pause() lifts the limit
// (a build, which runs no user code). Outside such a child: no effect.
void watchdog_arm(double seconds, const std::string& step);
void watchdog_pause();

}  // namespace mfv
