#include "user/time_limit.hpp"

#include "util/error.hpp"

#include <fmt/format.h>

#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>

namespace mfv {
namespace {

// Waits up to `seconds` for `pid`; true with its status when it ended.
bool wait_for(pid_t pid, double seconds, int& status) {
  auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  for (;;) {
    pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) return true;
    if (r < 0 && errno != EINTR) throw Error(fmt::format("waitpid failed: {}", std::strerror(errno)));
    if (std::chrono::steady_clock::now() >= end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

int run_with_time_limit(double seconds, const std::string& what, const std::function<int()>& work) {
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t parent = ::getpid();
  pid_t pid = ::fork();
  if (pid < 0) throw Error(fmt::format("cannot start the check process: {}", std::strerror(errno)));
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);     // its handlers still remove temporary files
    if (::getppid() != parent) ::_exit(2);  // the parent died before prctl
    int rc = work();
    std::fflush(stdout);
    std::fflush(stderr);
    ::_exit(rc);  // no static destructors or atexit handlers of the parent's state
  }
  int status = 0;
  if (!wait_for(pid, seconds, status)) {
    ::kill(pid, SIGTERM);
    if (!wait_for(pid, 1.0, status)) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
    }
    throw Error(
        fmt::format("{} did not finish within --timeout {:g} s and was stopped (the BRDF code may not "
                    "terminate; an OpenCL kernel cannot be interrupted, so the check runs in a child process)",
                    what, seconds));
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  int sig = WTERMSIG(status);
  throw Error(fmt::format("{} died from signal {} ({})", what, sig, strsignal(sig)));
}

}  // namespace mfv
