// Work-group sizes, in one place: every launch with an explicit local size
// asks here, so the device's and the kernel's limits are always respected
// (a register-heavy kernel on a GPU may allow far fewer work-items than the
// device maximum; Oclgrind can be told to allow only 32).
#pragma once

#include <CL/opencl.hpp>

#include <cstddef>
#include <cstdint>

namespace mfv {

// The largest power of two <= `preferred` that fits CL_DEVICE_MAX_WORK_GROUP_SIZE,
// CL_DEVICE_MAX_WORK_ITEM_SIZES[0], the kernel's CL_KERNEL_WORK_GROUP_SIZE on
// `device`, and the cap in the environment variable MFV_MAX_LOCAL_SIZE (for
// testing small limits on any device). Throws mfv::Error on a bad
// MFV_MAX_LOCAL_SIZE (not a positive integer).
size_t fit_local_size(const cl::Kernel& kernel, const cl::Device& device, size_t preferred);

// Launches of a one-dimensional kernel over `count` work-items whose count
// varies from launch to launch (the reductions sum_values, sum_pairs,
// sum_rqmc, and sample_values: kernels/integrate.cl). PoCL compiles a kernel
// at its first launch with each work-group size, and once more for a grid
// of 65535 work-items or more ("smallgrid" or not); a size left to the driver
// (cl::NullRange) follows the count, so a kernel launched over many counts
// was compiled many times: sample_values 12 times in one default run, each
// 2-8 s of CPU cold (docs/performance.md, "Cold start"). So these launches
// take work-groups of one size, fit_local_size(kernel, device, 64), the grid
// rounded up to whole groups (the kernel ignores work-items past `count`), and
// at most kMaxCountedGrid work-items a launch (callers cut larger counts).
constexpr size_t kMaxCountedGrid = 32768;
size_t counted_local_size(const cl::Kernel& kernel, const cl::Device& device);
// The work-items enqueue_counted launches for `count`: count rounded up to
// whole work-groups (buffers a kernel writes per work-item are this long).
size_t counted_grid(const cl::Kernel& kernel, const cl::Device& device, size_t count);
void enqueue_counted(cl::CommandQueue& queue, const cl::Kernel& kernel, const cl::Device& device, size_t count);
// Sets a kernel's arguments 0, 1, ... in order (one line a launch where
// several kernels take their arguments in turn).
template <class... Args>
void set_args(cl::Kernel& kernel, const Args&... args) {
  cl_uint i = 0;
  (kernel.setArg(i++, args), ...);
}

// The work-group size of a replicate kernel (albedo_mis_values and the
// other MFV_*_ROWS kernels) over rows of n points. Short
// rows (at most 16 SIMD widths, the default run's n = 40 and 80) take one
// SIMD width, CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE (8 on PoCL), where
// it divides n: PoCL compiles a kernel once per work-group size, so furnace
// (n = 80) and energy (n = 40) then share each pair's compile, 45 compiles
// fewer on a cold default run, and the furnace's integration took no longer
// (median of 5: 0.97 s against 1.03 s with 16; docs/performance.md, "Cold
// start"). Longer rows take the largest power of two that divides n within
// the device's and kernel's limits (up to 1024): there small work-groups cost
// more per point (mfv bench --case, n = 1280: 0.56 ms to SE 1e-4 with 8
// against 0.41 ms with 256; with 64 against up to 1024, 1.5-1.7 ms against
// 1.0-1.4 ms).
size_t row_local_size(const cl::Kernel& kernel, const cl::Device& device, uint32_t n);
// The work-group size of a scalar replicate kernel (MFV_MIS_ROWS, not
// vectorized) over rows of n points: one SIMD width where it divides n, for
// every n (row_local_size's larger sizes for long rows pay off where PoCL
// vectorizes across work-items), so that rows of 80 and 160 points share
// one compile.
size_t scalar_row_local_size(const cl::Kernel& kernel, const cl::Device& device, uint32_t n);

// MFV_MAX_LOCAL_SIZE as a number, 0 when unset. Throws mfv::Error when it is
// set to anything but a positive integer.
size_t local_size_cap_from_env();

}  // namespace mfv
