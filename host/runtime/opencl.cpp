#include "runtime/opencl.hpp"

#include "runtime/embedded_kernels.hpp"
#include "runtime/error.hpp"
#include "runtime/work_group.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <fstream>
#include <sstream>

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

}  // namespace

std::vector<DeviceInfo> list_devices() {
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

DeviceInfo select_device(const std::string& selector) {
  auto devs = list_devices();
  if (selector.empty()) {
    for (auto& d : devs)
      if (d.type == "GPU") return d;
    return devs.front();
  }
  if (selector == "all") throw Error("--device all is for 'mfv bench' only; other commands run on one device");
  if (std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); })) {
    size_t i = std::stoul(selector);
    if (i >= devs.size())
      throw Error(fmt::format("no OpenCL device with index {} ({} found; see 'mfv devices')", i, devs.size()));
    return devs[i];
  }
  for (auto& d : devs)
    if (lower(d.platform + " " + d.name).find(lower(selector)) != std::string::npos) return d;
  throw Error(fmt::format("no OpenCL device matches '{}' (see 'mfv devices')", selector));
}

Runtime::Runtime(const std::string& device_selector, std::string kernel_dir)
    : info_(select_device(device_selector)), kernel_dir_(std::move(kernel_dir)) {
  local_size_cap_from_env();  // a bad MFV_MAX_LOCAL_SIZE fails here, before any work
  context_ = cl::Context(info_.device);
  queue_ = cl::CommandQueue(context_, info_.device);
}

std::string Runtime::base_options() const {
  // Pinned: no fast-math, denormals kept, so float results are comparable
  // with the reference (kernels/rng.cl writes Philox out: no include path).
  return "-cl-std=CL1.2";
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

cl::Program Runtime::build(const std::vector<std::string>& files, const std::vector<std::string>& defines,
                           const std::string& generated, const std::string& insert_before,
                           const std::vector<ExtraSource>& extra) {
  std::vector<ExtraSource> inserts = extra;
  if (!generated.empty()) inserts.insert(inserts.begin(), {"<generated>", generated, insert_before});
  std::vector<bool> done(inserts.size(), false);
  std::string source;
  auto insert = [&](const std::string& before) {
    for (size_t i = 0; i < inserts.size(); ++i)
      if (!done[i] && (inserts[i].before == before || before.empty())) {
        source += "#line 1 \"" + inserts[i].name + "\"\n" + inserts[i].text + "\n";
        done[i] = true;
      }
  };
  for (auto& f : files) {
    insert(f);
    source += kernel_text(f);
    source += "\n";
  }
  insert("");  // those whose file is not in the list, or that asked for the end

  std::string options = base_options();
  for (auto& d : defines) options += " -D" + d;

  cl::Program program(context_, source);
  auto t0 = std::chrono::steady_clock::now();
  try {
    program.build(std::vector<cl::Device>{info_.device}, options.c_str());
  } catch (const cl::BuildError& e) {
    std::string log;
    for (auto& [dev, text] : e.getBuildLog()) log += trim(text) + "\n";
    throw Error(fmt::format("kernel build failed on {} (options: {}); build log:\n{}", info_.name, options, log));
  } catch (const cl::Error& e) {
    throw Error(fmt::format("kernel build failed on {}: {} ({})", info_.name, e.what(), e.err()));
  }
  stats_.builds += 1;
  stats_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return program;
}

}  // namespace mfv
