// Work-group sizes, in one place: every launch with an explicit local size
// asks here, so the device's and the kernel's limits are always respected
// (a register-heavy kernel on a GPU may allow far fewer work-items than the
// device maximum; Oclgrind can be told to allow only 32).
#pragma once

#include <CL/opencl.hpp>

#include <cstddef>

namespace mfv {

// The largest power of two <= `preferred` that fits CL_DEVICE_MAX_WORK_GROUP_SIZE,
// CL_DEVICE_MAX_WORK_ITEM_SIZES[0], the kernel's CL_KERNEL_WORK_GROUP_SIZE on
// `device`, and the cap in the environment variable MFV_MAX_LOCAL_SIZE (for
// testing small limits on any device). Throws mfv::Error on a bad
// MFV_MAX_LOCAL_SIZE (not a positive integer).
size_t fit_local_size(const cl::Kernel& kernel, const cl::Device& device, size_t preferred);

// MFV_MAX_LOCAL_SIZE as a number, 0 when unset. Throws mfv::Error when it is
// set to anything but a positive integer.
size_t local_size_cap_from_env();

}  // namespace mfv
