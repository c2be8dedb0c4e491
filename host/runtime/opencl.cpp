#include "runtime/opencl.hpp"

#include "runtime/build_options.hpp"
#include "runtime/embedded_kernels.hpp"
#include "runtime/kernel_includes.hpp"
#include "runtime/program_cache.hpp"
#include "runtime/provenance.hpp"
#include "runtime/work_group.hpp"
#include "util/error.hpp"
#include "util/parse.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include <sched.h>
#include <unistd.h>

namespace mfv {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string type_name(cl_device_type t) {
  if (t & CL_DEVICE_TYPE_GPU) return "GPU";
  if (t & CL_DEVICE_TYPE_CPU) return "CPU";
  if (t & CL_DEVICE_TYPE_ACCELERATOR) return "ACCELERATOR";
  return "OTHER";
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back())))) s.pop_back();
  return s;
}

// PoCL's compiler writes its diagnostics ("1 error generated.") straight to
// file descriptor 2 during clBuildProgram; they are held back while a build
// runs so mfv's one `mfv: error:` line comes first, and then passed on
// (warnings of a good build) or folded into the error's build log.
// Others (Oclgrind, which also ignores -Werror; Intel) put a good build's
// warnings only in the build log: its warning lines are passed on too, so
// that a warning shows on every implementation (the portability tests look
// for none). Left out: Intel's vectorizer saying a kernel "can't be
// vectorized due to unsupported vec type hint", which is what
// MFV_NO_IMPLICIT_VECTORIZE asks for (kernels/common.cl).
void pass_on_warnings(const std::string& log) {
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);)
    if (line.find("warning") != std::string::npos && line.find("unsupported vec type hint") == std::string::npos)
      std::fprintf(stderr, "%s\n", trim(line).c_str());
}

class StderrCapture {
 public:
  StderrCapture() : file_(std::tmpfile()) {
    std::fflush(stderr);
    if (file_) saved_ = ::dup(2);
    if (saved_ >= 0 && ::dup2(::fileno(file_), 2) < 0) ::close(saved_), saved_ = -1;
  }
  ~StderrCapture() { restore(); }
  // Puts fd 2 back and returns what was written to it meanwhile.
  std::string restore() {
    std::string text;
    if (saved_ >= 0) {
      std::fflush(stderr);
      ::dup2(saved_, 2);
      ::close(saved_);
      saved_ = -1;
      std::rewind(file_);
      char buf[4096];
      while (size_t n = std::fread(buf, 1, sizeof buf, file_)) text.append(buf, n);
    }
    if (file_) std::fclose(file_), file_ = nullptr;
    return text;
  }

 private:
  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

}  // namespace

std::string pin_pocl_workers() {
  // PoCL pins worker i to CPU i, and some of its versions abort where that CPU is not the
  // process's to use (a cpuset, taskset): pinned only where the process may run on every
  // online CPU
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  const long online = ::sysconf(_SC_NPROCESSORS_ONLN);
  bool every = online > 0 && online <= CPU_SETSIZE && ::sched_getaffinity(0, sizeof allowed, &allowed) == 0;
  for (long c = 0; every && c < online; ++c) every = CPU_ISSET(c, &allowed);
  if (every) ::setenv("POCL_AFFINITY", "1", 0);  // 0: an explicit value is kept
  const char* v = std::getenv("POCL_AFFINITY");
  return v ? v : "";
}

std::vector<DeviceInfo> list_devices() {
  pin_pocl_workers();  // before PoCL starts (the first platform query)
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    platforms.clear();  // the ICD loader reports "no platform" as an error
  }
  if (platforms.empty())
    throw Error("no OpenCL platform found; install an OpenCL driver (e.g. apt-get install pocl-opencl-icd)");
  std::vector<DeviceInfo> out;
  for (auto& p : platforms) {
    std::vector<cl::Device> devs;
    try {
      p.getDevices(CL_DEVICE_TYPE_ALL, &devs);
    } catch (const cl::Error&) {
      continue;  // a platform with no devices is not an error while others have some
    }
    for (auto& d : devs) {
      DeviceInfo i;
      i.index = static_cast<int>(out.size());
      i.platform = trim(p.getInfo<CL_PLATFORM_NAME>());
      i.name = trim(d.getInfo<CL_DEVICE_NAME>());
      i.type = type_name(d.getInfo<CL_DEVICE_TYPE>());
      i.driver = trim(d.getInfo<CL_DRIVER_VERSION>());
      i.version = trim(d.getInfo<CL_DEVICE_VERSION>());
      i.compute_units = d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
      i.fp64 = d.getInfo<CL_DEVICE_EXTENSIONS>().find("cl_khr_fp64") != std::string::npos;
      i.fp32_denorms = (d.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_DENORM) != 0;
      i.device = d;
      out.push_back(i);
    }
  }
  if (out.empty()) throw Error("OpenCL platforms exist but none has a device");
  return out;
}

DeviceInfo pick_device(const std::vector<DeviceInfo>& devs, const std::string& selector) {
  if (selector.empty()) {
    for (auto& d : devs)
      if (d.type == "GPU") return d;
    return devs.front();
  }
  if (selector == "all" || is_device_set(selector))
    throw Error(fmt::format("--device {} is for 'mfv bench' and 'mfv run' only; other commands run on one device",
                            selector));
  if (std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); })) {
    uint64_t i = parse_unsigned("--device", selector);
    if (i >= devs.size())
      throw Error(fmt::format("no OpenCL device with index {} ({} found; see 'mfv devices')", i, devs.size()));
    return devs[i];
  }
  // Exact names first (device, platform, or "platform device"), then substrings;
  // more than one device either way is ambiguous.
  const std::string want = lower(selector);
  auto exact = [&](const DeviceInfo& d) {
    return lower(d.name) == want || lower(d.platform) == want || lower(d.platform + " " + d.name) == want;
  };
  auto part = [&](const DeviceInfo& d) { return lower(d.platform + " " + d.name).find(want) != std::string::npos; };
  for (auto match : {std::function<bool(const DeviceInfo&)>(exact), std::function<bool(const DeviceInfo&)>(part)}) {
    std::vector<const DeviceInfo*> found;
    for (auto& d : devs)
      if (match(d)) found.push_back(&d);
    if (found.size() == 1) return *found[0];
    if (found.size() > 1) {
      std::string names;
      for (auto* d : found)
        names += fmt::format("{}#{} {} / {}", names.empty() ? "" : ", ", d->index, d->platform, d->name);
      throw Error(fmt::format("--device '{}' matches {} devices ({}); give an index or an exact name", selector,
                              found.size(), names));
    }
  }
  throw Error(fmt::format("no OpenCL device matches '{}' (see 'mfv devices')", selector));
}

DeviceInfo select_device(const std::string& selector) { return pick_device(list_devices(), selector); }

bool is_device_set(const std::string& selector) {
  return selector == "all" || selector.find(',') != std::string::npos;
}

std::vector<DeviceInfo> select_devices(const std::string& selector) {
  std::vector<DeviceInfo> devs = list_devices();
  if (selector == "all") return devs;
  if (!is_device_set(selector)) return {pick_device(devs, selector)};
  std::vector<DeviceInfo> out;
  for (size_t at = 0;;) {
    const size_t comma = selector.find(',', at);
    const std::string one = selector.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    if (one.empty() || one == "all") throw Error(fmt::format("--device {}: an empty or 'all' entry in the list", selector));
    out.push_back(pick_device(devs, one));
    if (comma == std::string::npos) return out;
    at = comma + 1;
  }
}

Runtime::Runtime(const std::string& device_selector, std::string kernel_dir)
    : Runtime(select_device(device_selector), std::move(kernel_dir)) {}

Runtime::Runtime(const DeviceInfo& device, std::string kernel_dir) : info_(device), kernel_dir_(std::move(kernel_dir)) {
  local_size_cap_from_env();               // a bad MFV_MAX_LOCAL_SIZE fails here, before any work
  extra_options_ = cl_options_from_env();  // and a bad MFV_CL_OPTIONS
  // a build that may flush float subnormals is checked as on a flush-to-zero device
  if ((extra_options_ + " ").find(" -cl-denorms-are-zero ") != std::string::npos) info_.fp32_denorms = false;
  cache_dir_ = ProgramCache::default_dir();  // as does a bad MFV_PROGRAM_CACHE
  context_ = cl::Context(info_.device);
  queue_ = cl::CommandQueue(context_, info_.device);
  record_runtime(info_, kernel_dir_);
}

std::string Runtime::base_options() const {
  // Pinned: no fast-math, denormals kept, so float results are comparable
  // with the reference (kernels/rng.cl writes Philox out: no include path).
  return "-cl-std=CL1.2" + extra_options_;
}

std::string Runtime::kernel_text(const std::string& file) const {
  if (!kernel_dir_.empty()) {
    std::string path = kernel_dir_ + "/" + file;
    std::ifstream in(path);
    if (!in) throw Error(fmt::format("cannot read kernel file {} (from --kernel-dir)", path));
    std::stringstream ss;
    ss << "#line 1 \"" << path << "\"\n" << in.rdbuf();
    return ss.str();
  }
  for (auto& k : embedded_kernels())
    if (file == k.name) return k.text;
  throw Error(fmt::format("internal: no embedded kernel named {}", file));
}

cl::Program Runtime::build_source(const std::string& source, const std::string& options) {
  cl::Program program(context_, source);
  StderrCapture capture;
  try {
    program.build(std::vector<cl::Device>{info_.device}, options.c_str());
  } catch (const cl::BuildError& e) {
    std::string log, printed = trim(capture.restore());
    for (auto& [dev, text] : e.getBuildLog()) log += trim(text) + "\n";
    if (!printed.empty() && log.find(printed) == std::string::npos) log += printed + "\n";
    throw Error(fmt::format("kernel build failed on {} (options: {}); build log:\n{}", info_.name, options, log));
  } catch (const cl::Error& e) {
    capture.restore();
    throw Error(fmt::format("kernel build failed on {}: {} ({})", info_.name, e.what(), e.err()));
  }
  std::string printed = capture.restore();
  if (!printed.empty()) std::fputs(printed.c_str(), stderr);
  if (printed.find("warning") == std::string::npos)
    pass_on_warnings(program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(info_.device));
  return program;
}

cl::Program Runtime::build(const std::vector<std::string>& files, const std::vector<std::string>& defines,
                           const std::string& generated, const std::string& insert_before,
                           const std::vector<ExtraSource>& extra) {
  std::vector<ExtraSource> inserts = extra;
  if (!generated.empty()) inserts.insert(inserts.begin(), {"<generated>", generated, insert_before});
  std::vector<bool> done(inserts.size(), false);
  std::string source;
  // Each file, and each file it includes (kernels/abi/), recorded once with
  // its hash, without the #line mfv puts first.
  std::set<std::string> seen;
  auto load = [&](const std::string& f) {
    std::string text = kernel_text(f);
    record_kernel_source(f, text.substr(text.find('\n') + 1));
    return text;
  };
  auto insert = [&](const std::string& before) {
    for (size_t i = 0; i < inserts.size(); ++i)
      if (!done[i] && (inserts[i].before == before || before.empty())) {
        source += expand_kernel_includes("#line 1 \"" + inserts[i].name + "\"\n" + inserts[i].text, load, seen) + "\n";
        if (inserts[i].name != "<generated>") record_kernel_source(inserts[i].name, inserts[i].text);
        done[i] = true;
      }
  };
  for (auto& f : files) {
    insert(f);
    source += expand_kernel_includes(load(f), load, seen);
    source += "\n";
  }
  insert("");  // those whose file is not in the list, or that asked for the end

  std::string options = base_options();
  for (auto& d : defines) options += " -D" + d;

  auto t0 = std::chrono::steady_clock::now();
  const ProgramCache cache(cache_dir_);
  const std::string key = cache.enabled() ? ProgramCache::key(info_, options, source) : "";
  cl::Program program;
  if (auto binary = cache.load(key)) {
    try {
      program = cl::Program(context_, {info_.device}, cl::Program::Binaries{*binary});
      program.build(std::vector<cl::Device>{info_.device}, options.c_str());
      stats_.cached += 1;
    } catch (const cl::Error&) {
      program = cl::Program();  // a binary the driver refuses (another driver build): from source
    }
  }
  if (!program()) {
    program = build_source(source, options);
    if (cache.enabled()) {
      const auto binaries = program.getInfo<CL_PROGRAM_BINARIES>();
      if (binaries.size() == 1) cache.store(key, binaries[0]);
    }
  }
  stats_.builds += 1;
  stats_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return program;
}

}  // namespace mfv
