#include "runtime/work_group.hpp"

#include "util/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string>
#include <vector>

namespace mfv {

size_t local_size_cap_from_env() {
  const char* env = std::getenv("MFV_MAX_LOCAL_SIZE");
  if (!env) return 0;
  const std::string s(env);
  const bool digits =
      !s.empty() && s.size() <= 9 && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
  if (!digits || std::stoul(s) == 0)
    throw Error(fmt::format("MFV_MAX_LOCAL_SIZE={}: expected a positive integer (the most work-items a group)", s));
  return std::stoul(s);
}

size_t fit_local_size(const cl::Kernel& kernel, const cl::Device& device, size_t preferred) {
  size_t limit = device.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
  const std::vector<size_t> per_dim = device.getInfo<CL_DEVICE_MAX_WORK_ITEM_SIZES>();
  if (!per_dim.empty()) limit = std::min(limit, per_dim[0]);
  limit = std::min(limit, kernel.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device));
  if (size_t cap = local_size_cap_from_env()) limit = std::min(limit, cap);
  size_t local = 1;
  while (local * 2 <= std::min(preferred, limit)) local *= 2;
  return local;
}

size_t counted_local_size(const cl::Kernel& kernel, const cl::Device& device) {
  return fit_local_size(kernel, device, 64);
}

size_t counted_grid(const cl::Kernel& kernel, const cl::Device& device, size_t count) {
  const size_t local = counted_local_size(kernel, device);
  return (count + local - 1) / local * local;
}

void enqueue_counted(cl::CommandQueue& queue, const cl::Kernel& kernel, const cl::Device& device, size_t count) {
  if (count == 0) return;
  if (count > kMaxCountedGrid)
    throw Error(fmt::format("internal: {} work-items in one counted launch (at most {})", count, kMaxCountedGrid));
  queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(counted_grid(kernel, device, count)),
                             cl::NDRange(counted_local_size(kernel, device)));
}

size_t row_local_size(const cl::Kernel& k, const cl::Device& device, uint32_t n) {
  const size_t simd = k.getWorkGroupInfo<CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE>(device);
  size_t local = fit_local_size(k, device, 1024);
  while (n % local != 0) local /= 2;
  if (simd > 0 && n <= 16 * simd && n % simd == 0) local = std::min(local, fit_local_size(k, device, simd));
  return local;
}

size_t scalar_row_local_size(const cl::Kernel& k, const cl::Device& device, uint32_t n) {
  const size_t simd = k.getWorkGroupInfo<CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE>(device);
  const size_t local = row_local_size(k, device, n);  // a power of two that divides n
  return simd > 0 ? std::min(local, fit_local_size(k, device, simd)) : local;
}

}  // namespace mfv
