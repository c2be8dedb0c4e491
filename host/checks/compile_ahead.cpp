#include "checks/compile_ahead.hpp"

#include "runtime/integrator.hpp"
#include "util/error.hpp"
#include "util/progress.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <limits>
#include <thread>

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace mfv {

namespace {

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "";
}

bool is_pocl(const DeviceInfo& d) { return d.platform.find("Portable Computing Language") != std::string::npos; }

// The child's log line (stderr: /dev/null unless MFV_COMPILE_AHEAD_LOG).
void note(std::chrono::steady_clock::time_point t0, const std::string& what) {
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = double(std::clock()) / CLOCKS_PER_SEC;  // the process's, all threads
  std::fprintf(stderr, "mfv compile-ahead: %7.2f s wall %7.2f s CPU: %s\n", s, cpu, what.c_str());
  std::fflush(stderr);
}

double cpu_now() { return double(std::clock()) / CLOCKS_PER_SEC; }

// A launch that compiles nothing (a kernel already in PoCL's cache, dlopen'd
// and run on one integral) takes milliseconds; the smallest compile, tenths
// of a second of CPU.
constexpr double kWarmCpuSeconds = 0.05;

}  // namespace

bool compile_ahead_pays(unsigned cores, double others_running) {
  return cores >= 2 && others_running <= double(cores) - 1.0;
}

static double others_running_now() {
  // /proc/loadavg's fourth field, "running/total", counts the tasks runnable
  // at this instant, this one included; ten readings 5 ms apart
  double sum = 0;
  int readings = 0;
  for (int k = 0; k < 10; ++k) {
    if (k > 0) ::usleep(5000);
    std::ifstream in("/proc/loadavg");
    double l1, l5, l15;
    int running = 0;
    char slash;
    if (in >> l1 >> l5 >> l15 >> running >> slash && running > 0) sum += running - 1, ++readings;
  }
  return readings > 0 ? sum / readings : std::numeric_limits<double>::infinity();  // unknown: busy
}

CompileAhead::CompileAhead(const SuitePlans& sp, const SuiteOptions& opt, const std::string& device_selector,
                           const std::string& kernel_dir) {
  const std::string on = env("MFV_COMPILE_AHEAD");
  if (!on.empty() && on != "auto" && on != "0" && on != "1" && on != "only")
    throw Error(fmt::format(
        "MFV_COMPILE_AHEAD={}: expected auto (the default: on where a core is free), 0 (off), 1 (on) or only", on));
  if (on == "0" || env("POCL_KERNEL_CACHE") == "0") return;
  // auto: the child takes the core the run's compiles leave (PoCL compiles one
  // kernel at a time a process); where no core is free it only competes with
  // the run (docs/ci.md, "Compiling ahead in a second process")
  if ((on.empty() || on == "auto") && !compile_ahead_pays(std::thread::hardware_concurrency(), others_running_now()))
    return;
  only_ = on == "only";
  const std::string log = env("MFV_COMPILE_AHEAD_LOG");
  const std::string sink = log.empty() ? "/dev/null" : log;
  const pid_t parent = ::getpid();
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid != 0) {
    pid_ = pid;  // -1: no child, and no error
    return;
  }
  // The child: a copy of this process before any OpenCL call. It never
  // returns into the caller: it ends with _exit (no atexit handlers, no
  // static destructors, no flush of buffers it shares with the run).
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(0);
  const int null_in = ::open("/dev/null", O_RDONLY);
  const int out = ::open(sink.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  if (null_in >= 0) ::dup2(null_in, 0);
  if (out >= 0) ::dup2(out, 1), ::dup2(out, 2);
  int rc = 1;
  try {
    Runtime rt(device_selector, kernel_dir);
    rc = is_pocl(rt.device()) ? compile_ahead(rt, sp, opt) : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mfv compile-ahead: %s\n", e.what());
  }
  std::fflush(nullptr);
  ::_exit(rc);
}

int CompileAhead::wait() {
  if (pid_ <= 0) return 1;
  int status = 0;
  const pid_t done = ::waitpid(pid_, &status, 0);
  pid_ = -1;
  return done > 0 && WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

void CompileAhead::end() {
  if (pid_ <= 0) return;
  int status = 0;
  if (::waitpid(pid_, &status, WNOHANG) == 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, &status, 0);
  }
  pid_ = -1;
}

int compile_ahead(Runtime& rt, SuitePlans sp, const SuiteOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  progress::set_quiet(true);
  note(t0, "started");
  const std::string test = env("MFV_COMPILE_AHEAD_TEST");
  if (test == "abort") std::abort();
  if (test == "hang")
    for (;;) ::pause();
  Integrator in(rt, suite_terms(sp));  // the run's program: the same source, so the same PoCL cache entry
  in.set_compile_ahead(true);
  note(t0, "integration program built");
  // The run's end first. Reciprocity: where its kernels were all in the
  // cache already, the cache is warm (an earlier run's), and the child stops.
  if (!sp.reciprocity.specs.empty()) {
    const double c0 = cpu_now();
    in.reciprocity(sp.reciprocity.specs, reciprocity_pairs(opt.scale), opt.seed);
    note(t0, "reciprocity");
    if (cpu_now() - c0 < kWarmCpuSeconds) {
      note(t0, "warm cache: done");
      return 0;
    }
  }
  SuiteReport scratch;  // the pointwise kinds (their own programs), whole
  run_pointwise_kinds(rt, opt, scratch);
  note(t0, "pointwise kinds");
  for (auto p = sp.plans.rbegin(); p != sp.plans.rend(); ++p) {
    if (p->specs.empty()) continue;
    in.run(p->specs, p->samples, opt.seed);
    note(t0, fmt::format("plan {} ({} integrals)", p->check, p->specs.size()));
  }
  note(t0, "done");
  return 0;
}

}  // namespace mfv
