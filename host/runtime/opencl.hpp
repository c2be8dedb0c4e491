// One owner for OpenCL platform, device, context, queue and program builds.
#pragma once

#include <CL/opencl.hpp>

#include <functional>
#include <set>
#include <string>
#include <vector>

namespace mfv {

struct DeviceInfo {
  int index = -1;  // position in list_devices()
  std::string platform;
  std::string name;
  std::string type;  // "GPU", "CPU", "ACCELERATOR", "OTHER"
  std::string driver;
  std::string version;
  unsigned compute_units = 0;
  bool fp64 = false;
  // CL_FP_DENORM in CL_DEVICE_SINGLE_FP_CONFIG: float subnormals kept. Without
  // it (many GPUs, -cl-denorms-are-zero by default) a float below FLT_MIN may
  // read as 0. Double subnormals are required by cl_khr_fp64.
  bool fp32_denorms = true;
  cl::Device device;
};

// Every device of every platform. Throws mfv::Error when no platform exists.
// Calls pin_pocl_workers() first.
std::vector<DeviceInfo> list_devices();

// Sets POCL_AFFINITY=1 where the environment does not set it (an explicit
// POCL_AFFINITY, 0 included, is kept) and the process may run on every online
// CPU (PoCL pins worker i to CPU i), so that PoCL's CPU device pins its
// worker threads one to a core; returns the value in force. Read by PoCL once,
// when it starts at the first platform query (list_devices), so it takes effect
// only where called before that. Unpinned, the Linux scheduler often woke
// both workers on one core for a short launch, and a call of 640 points x 32
// replicates ran on one core: mfv bench --case ... 0.5:0.5, 0.19-0.29 ms
// unpinned against 0.155-0.165 ms pinned (docs/performance.md, issue 32).
std::string pin_pocl_workers();

// "" picks the first GPU, else the first device; a number picks by index;
// anything else is, case-insensitively, first an exact device name, platform
// name or "platform device", then a substring of "platform device". A name
// that matches several devices is an error listing them.
DeviceInfo pick_device(const std::vector<DeviceInfo>& devices, const std::string& selector);
DeviceInfo select_device(const std::string& selector);  // pick_device over list_devices()
// mfv run's --device: "all" (every device of every platform) or a comma list
// of selectors as pick_device takes them ("0,0" names one device twice: two
// contexts and queues on it). One device where the selector is neither.
bool is_device_set(const std::string& selector);
std::vector<DeviceInfo> select_devices(const std::string& selector);

// What a compile-ahead child (checks/compile_ahead.hpp) builds into PoCL's
// cache for this process, and tells it when done: this process's own build
// of it then only reads the cache.
enum class HandOver : char {
  IntegrationProgram = 'P',  // the suite's integration program (Integrator's)
  SampleValues = 'S',        // that program's sample_values kernel, as the reference comparison launches it
};

struct BuildStats {
  int builds = 0;
  double seconds = 0.0;  // wall time spent in clBuildProgram, kept apart from run time
  int cached = 0;        // builds from a binary of the on-disk cache (runtime/program_cache.hpp)
};

class Runtime {
 public:
  explicit Runtime(const std::string& device_selector = "", std::string kernel_dir = "");
  // On a device of list_devices() (mfv run --device all: one Runtime per device).
  Runtime(const DeviceInfo& device, std::string kernel_dir);

  const DeviceInfo& device() const { return info_; }
  cl::Context& context() { return context_; }
  cl::CommandQueue& queue() { return queue_; }

  // A source that is not a kernels/ file (a user's file for mfv check),
  // labelled `name` in build logs (#line 1 "name") and placed before the
  // kernels/ file `before` ("" = at the end).
  struct ExtraSource {
    std::string name, text, before;
  };

  // Concatenates the named kernels/ files (with `generated` inserted before
  // the file named `insert_before`, or at the end, and any `extra` sources
  // where they ask) and builds them with the given -D definitions. Throws
  // mfv::Error with the build log on failure. A binary of the same device,
  // options and source in the on-disk cache (runtime/program_cache.hpp) is
  // taken instead of the source, and every source build is stored there.
  cl::Program build(const std::vector<std::string>& files, const std::vector<std::string>& defines,
                    const std::string& generated = "", const std::string& insert_before = "",
                    const std::vector<ExtraSource>& extra = {});

  // Pinned options shared by every build, and MFV_CL_OPTIONS
  // (runtime/build_options.hpp) where set, recorded in results files.
  std::string base_options() const;
  const BuildStats& build_stats() const { return stats_; }

  // The compile-ahead child's hand-over (checks/compile_ahead.hpp): where one
  // is set, await(what) waits until the child reports `what` built, and
  // returns true; false at once where none is set, and false where the child
  // ended or is late (the wait is bounded): the caller then builds it itself,
  // as without a child. What is built, and so every result, is the same.
  void set_hand_over(std::function<bool(HandOver)> await) { await_ = std::move(await); }
  bool hand_over() const { return static_cast<bool>(await_); }
  bool await(HandOver what) const { return await_ ? await_(what) : false; }

 private:
  std::string kernel_text(const std::string& file) const;
  cl::Program build_source(const std::string& source, const std::string& options);

  DeviceInfo info_;
  std::string kernel_dir_;
  std::string extra_options_;  // MFV_CL_OPTIONS
  std::string cache_dir_;      // "" = no on-disk program cache
  cl::Context context_;
  cl::CommandQueue queue_;
  BuildStats stats_;
  std::function<bool(HandOver)> await_;
};

}  // namespace mfv
