// Compile-ahead (issue 30, docs/ci.md "Cold start"): PoCL compiles each
// kernel at its first launch, for that launch's work-group size and grid
// class, and keeps it in its kernel cache ($POCL_CACHE_DIR); one process
// compiles one kernel at a time (a process-wide lock). So while `mfv run`
// works through its plans from the first, a child process (forked before
// the run touches OpenCL) builds the same programs and launches each kernel
// once as the run's first launch of it would: first the integration program
// and the float sample_values, each reported to the run on a pipe when built
// (the hand-over: the run builds the double twin meanwhile and then waits,
// bounded, to read them from the cache rather than build them beside the
// child; Runtime::await), then from the run's end backwards: reciprocity,
// the pointwise kinds, then the plans in reverse
// (Integrator::set_compile_ahead). The run then finds those kernels
// compiled in the cache. PoCL writes each entry to a temporary file and
// renames it, so neither process sees half an entry.
//
// The child shares nothing with the run but the cache: its output goes to
// /dev/null (or MFV_COMPILE_AHEAD_LOG), its exit status is ignored, and the
// run ends it (SIGKILL) once the run has launched all its kernels; it dies
// with the run (PR_SET_PDEATHSIG). The run's results are its own, whatever
// the child does. Where the cache is warm (the child's first launches, the
// reciprocity kernels, compile nothing), the child stops there.
//
// On by default where it pays (MFV_COMPILE_AHEAD unset or auto): the machine
// has two or more cores and one is free when the run starts (the tasks
// running besides mfv, read from /proc/loadavg, leave one); on this
// project's shared 2-core machine at load 7-8 the child made the cold run
// longer, on the idle one 1.2-1.5x shorter (docs/ci.md, "Cold start").
// MFV_COMPILE_AHEAD=1 turns it on and 0 off, on a device that is PoCL with
// its kernel cache on (POCL_KERNEL_CACHE not 0); MFV_COMPILE_AHEAD=only
// runs the child alone (the run waits for it and then runs nothing: a cache
// filled as the child fills it, for tests and CI).
#pragma once

#include "checks/suite.hpp"
#include "runtime/opencl.hpp"

#include <string>

#include <sys/types.h>

namespace mfv {

class CompileAhead {
 public:
  // Forks the child for run_suite over `sp` on the device `device_selector`
  // (as Runtime takes it) where MFV_COMPILE_AHEAD is 1 or only, or unset or
  // auto and compile_ahead_pays, and POCL_KERNEL_CACHE is not 0;
  // the child ends at once where the device is not PoCL. Call it before this
  // process's first OpenCL call. Throws mfv::Error for a bad
  // MFV_COMPILE_AHEAD; a child that cannot start is no error.
  CompileAhead(const SuitePlans& sp, const SuiteOptions& opt, const std::string& device_selector,
               const std::string& kernel_dir);
  ~CompileAhead() { end(); }
  CompileAhead(const CompileAhead&) = delete;
  CompileAhead& operator=(const CompileAhead&) = delete;
  bool started() const { return pid_ > 0; }
  bool only() const { return only_; }  // MFV_COMPILE_AHEAD=only
  int wait();  // waits for the child; its exit status (1 where it did not start or was killed)
  void end();  // ends the child (SIGKILL) if it still runs
  // The hand-over (Runtime::set_hand_over): true once the child has reported
  // `what` built; false where it did not start, ended without reporting it,
  // or is late: it waits at most as long again as the run has run since the
  // fork, 2 s at least (the child then builds what the run would build in
  // that time, or is stuck), and after one late report waits no more.
  bool await(HandOver what);

 private:
  pid_t pid_ = -1;
  bool only_ = false;
  int reports_ = -1;   // the read end of the child's reports (a pipe); -1: none, or no more waiting
  std::string seen_;   // the reports read
  double forked_ = 0;  // steady-clock seconds at the fork
};

// auto's rule: at least two cores, and the other tasks running (their mean
// count over a few readings) leave one of them free.
bool compile_ahead_pays(unsigned cores, double others_running);

// The child's work, on its own Runtime: returns its exit status. It writes
// each HandOver it has built to `reports` (a file descriptor; -1: none).
// MFV_COMPILE_AHEAD_TEST=abort or =hang makes it fail at once or never end
// (the tests of a failing child).
int compile_ahead(Runtime& rt, SuitePlans sp, const SuiteOptions& opt, int reports = -1);

}  // namespace mfv
