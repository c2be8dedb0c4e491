#include "checks/compile_ahead.hpp"

#include "runtime/integrator.hpp"
#include "util/error.hpp"
#include "util/progress.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <limits>
#include <thread>

#include <fcntl.h>
#include <poll.h>
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

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The child's report that it has built `what` (CompileAhead::await reads it).
void report(int fd, HandOver what) {
  const char c = static_cast<char>(what);
  if (fd >= 0 && ::write(fd, &c, 1) != 1) {
  }  // a run that stopped waiting has closed its end: nothing to tell
}

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

// A line in the compile-ahead log (MFV_COMPILE_AHEAD_LOG), where one is set:
// the run's own notes beside the child's (the child's stderr is that file).
static void append_to_log(const std::string& line) {
  const std::string log = env("MFV_COMPILE_AHEAD_LOG");
  if (log.empty()) return;
  if (std::FILE* f = std::fopen(log.c_str(), "a")) {
    std::fprintf(f, "%s\n", line.c_str());
    std::fclose(f);
  }
}

// Beside a child, the run and the child share the cores: PoCL's workers are
// left unpinned (runtime/opencl.cpp pin_pocl_workers keeps this explicit 0;
// a user's own POCL_AFFINITY is kept), so that a worker can move off the core
// the other process compiles on. Pinned, the idle cold default run took 22.6 s
// against 21.6 s unpinned (2 alternated rounds, Zen 4, 2 cores).
static void leave_workers_unpinned() {
  if (std::getenv("POCL_AFFINITY")) return;
  ::setenv("POCL_AFFINITY", "0", 1);
  append_to_log(fmt::format("mfv run (pid {}): PoCL's workers left unpinned beside the child", ::getpid()));
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
  int reports[2] = {-1, -1};  // the child's hand-over reports (await)
  if (::pipe2(reports, O_CLOEXEC) != 0) reports[0] = reports[1] = -1;
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid > 0) leave_workers_unpinned();
  if (pid != 0) {
    pid_ = pid;  // -1: no child, and no error
    forked_ = steady_seconds();
    if (reports[1] >= 0) ::close(reports[1]);
    if (pid > 0)
      reports_ = reports[0];
    else if (reports[0] >= 0)
      ::close(reports[0]);
    return;
  }
  if (reports[0] >= 0) ::close(reports[0]);
  leave_workers_unpinned();
  ::signal(SIGPIPE, SIG_IGN);  // a report the run no longer reads fails, and the child goes on
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
    rc = is_pocl(rt.device()) ? compile_ahead(rt, sp, opt, reports[1]) : 0;
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

// The run's line in the child's log (MFV_COMPILE_AHEAD_LOG, where set) on a hand-over.
static void note_hand_over(HandOver what, const char* outcome, double waited) {
  static std::string noted;  // each hand-over's outcome once (the comparison awaits sample_values per plan)
  if (noted.find(static_cast<char>(what)) != std::string::npos) return;
  noted += static_cast<char>(what);
  append_to_log(fmt::format("mfv run: {} {} (waited {:.2f} s)",
                            what == HandOver::IntegrationProgram ? "integration program" : "sample_values", outcome,
                            waited));
}

bool CompileAhead::await(HandOver what) {
  const char c = static_cast<char>(what);
  const double start = steady_seconds();
  const double deadline = start + std::max(2.0, start - forked_);
  while (seen_.find(c) == std::string::npos) {
    if (reports_ < 0) {
      note_hand_over(what, "not waited for: built here", steady_seconds() - start);
      return false;
    }
    const double left = deadline - steady_seconds();
    pollfd p{reports_, POLLIN, 0};
    const int ready = left > 0 ? ::poll(&p, 1, int(std::ceil(left * 1000))) : 0;
    if (ready < 0 && errno == EINTR) continue;
    char got[16];
    const ssize_t n = ready > 0 ? ::read(reports_, got, sizeof got) : -1;
    if (n < 0 && ready > 0 && errno == EINTR) continue;
    if (n <= 0) {  // late (the deadline), ended (end of file) or an error: no more waiting
      ::close(reports_);
      reports_ = -1;
      note_hand_over(what, ready > 0 ? "not built: the child ended; built here" : "late: built here",
                     steady_seconds() - start);
      return false;
    }
    seen_.append(got, size_t(n));
  }
  note_hand_over(what, "taken from the child", steady_seconds() - start);
  return true;
}

void CompileAhead::end() {
  if (reports_ >= 0) ::close(reports_);
  reports_ = -1;
  if (pid_ <= 0) return;
  int status = 0;
  if (::waitpid(pid_, &status, WNOHANG) == 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, &status, 0);
  }
  pid_ = -1;
}

int compile_ahead(Runtime& rt, SuitePlans sp, const SuiteOptions& opt, int reports) {
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
  // the run, building the double twin meanwhile, takes it from the cache
  report(reports, HandOver::IntegrationProgram);
  // The reference comparison's float sample_values, which the run reaches
  // after its first plan (its costliest compile there, ~2 s): the run waits
  // for it rather than compiling it beside the child
  if (opt.reference_samples > 0)
    if (const IntegralSpec* first = first_spec(sp.plans)) {
      in.sample_values({*first}, 1, opt.seed);
      note(t0, "sample_values");
    }
  report(reports, HandOver::SampleValues);
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
  compile_pointwise_kinds(rt, opt);  // the pointwise kinds (their own programs)
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
