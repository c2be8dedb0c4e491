#include "user/time_limit.hpp"

#include "util/error.hpp"

#include <fmt/format.h>

#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <new>
#include <thread>

namespace mfv {
namespace {

// Shared between the parent and the child (an anonymous shared mapping made
// before fork): the step the child is in and when it must end, in seconds
// of the steady clock; 0 = no step limit.
struct Watchdog {
  double deadline = 0, limit = 0;
  char step[96] = {0};
};
Watchdog* g_watchdog = nullptr;

double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// Waits up to `seconds` for `pid`, and while `dog` is set, up to its step's
// deadline; true with its status when it ended.
bool wait_for(pid_t pid, double seconds, int& status, const Watchdog* dog = nullptr) {
  const double end = now_s() + seconds;
  for (;;) {
    pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) return true;
    if (r < 0 && errno != EINTR) throw Error(fmt::format("waitpid failed: {}", std::strerror(errno)));
    const double t = now_s();
    if (t >= end) return false;
    if (dog && dog->deadline > 0 && t >= dog->deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

void stop(pid_t pid, int& status) {
  ::kill(pid, SIGTERM);
  if (!wait_for(pid, 1.0, status)) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
}

}  // namespace

int run_with_time_limit(double seconds, const std::string& what, const std::function<int()>& work,
                        bool step_limits) {
  std::fflush(stdout);
  std::fflush(stderr);
  void* shared = ::mmap(nullptr, sizeof(Watchdog), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (shared == MAP_FAILED) throw Error(fmt::format("cannot map the watchdog: {}", std::strerror(errno)));
  Watchdog* dog = new (shared) Watchdog();
  const pid_t parent = ::getpid();
  pid_t pid = ::fork();
  if (pid < 0) throw Error(fmt::format("cannot start the check process: {}", std::strerror(errno)));
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);     // its handlers still remove temporary files
    if (::getppid() != parent) ::_exit(2);  // the parent died before prctl
    if (step_limits) g_watchdog = dog;
    int rc = work();
    std::fflush(stdout);
    std::fflush(stderr);
    ::_exit(rc);  // no static destructors or atexit handlers of the parent's state
  }
  int status = 0;
  const bool ended = wait_for(pid, seconds, status, dog);
  const Watchdog seen = *dog;
  ::munmap(shared, sizeof(Watchdog));
  if (!ended && seen.deadline > 0 && now_s() >= seen.deadline) {
    stop(pid, status);
    throw Error(
        fmt::format("{}: {} did not finish within {:.0f} s and was stopped (the BRDF code may not terminate; the "
                    "limit is 100x a calibration launch of the same code, at least 30 s; --timeout sets one for the "
                    "whole check)",
                    what, seen.step, seen.limit));
  }
  if (!ended) {
    stop(pid, status);
    throw Error(
        fmt::format("{} did not finish within --timeout {:g} s and was stopped (the BRDF code may not "
                    "terminate; an OpenCL kernel cannot be interrupted, so the check runs in a child process)",
                    what, seconds));
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  int sig = WTERMSIG(status);
  throw Error(fmt::format("{} died from signal {} ({})", what, sig, strsignal(sig)));
}

void watchdog_arm(double seconds, const std::string& step) {
  if (!g_watchdog) return;
  std::snprintf(g_watchdog->step, sizeof(g_watchdog->step), "%s", step.c_str());
  g_watchdog->limit = seconds;
  g_watchdog->deadline = now_s() + seconds;
}

void watchdog_pause() {
  if (g_watchdog) g_watchdog->deadline = 0;
}

}  // namespace mfv
