// Integrator's per-sample values for the reference comparison
// (sample_values, program_sample_values) and its NaN-filled buffers.
#include "runtime/integrator.hpp"
#include "runtime/work_group.hpp"

#include <vector>

namespace mfv {

template <class T>
std::vector<T> program_sample_values(Runtime& rt, const cl::Program& program, const std::vector<IntegralSpec>& specs,
                                     uint32_t n, uint64_t seed) {
  std::vector<T> out(specs.size() * n);
  if (out.empty()) return out;
  cl::Kernel k(program, "sample_values");
  cl::Buffer spec_buf(rt.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, specs.size() * sizeof(IntegralSpec),
                      const_cast<IntegralSpec*>(specs.data()));
  cl::Buffer vals = nan_filled_buffer(rt, CL_MEM_WRITE_ONLY, out.size() * sizeof(T));
  k.setArg(0, spec_buf);
  k.setArg(1, static_cast<cl_uint>(n));
  k.setArg(2, static_cast<cl_ulong>(seed));
  k.setArg(3, vals);
  k.setArg(5, static_cast<cl_ulong>(out.size()));
  // one work-group size and grid width for every launch: one compile (runtime/work_group.hpp)
  for (size_t first = 0; first < out.size(); first += kMaxCountedGrid) {
    k.setArg(4, static_cast<cl_ulong>(first));
    enqueue_counted(rt.queue(), k, rt.device().device, std::min(kMaxCountedGrid, out.size() - first));
  }
  rt.queue().enqueueReadBuffer(vals, CL_TRUE, 0, out.size() * sizeof(T), out.data());
  return out;
}
template std::vector<float> program_sample_values<float>(Runtime&, const cl::Program&, const std::vector<IntegralSpec>&,
                                                         uint32_t, uint64_t);
template std::vector<double> program_sample_values<double>(Runtime&, const cl::Program&,
                                                           const std::vector<IntegralSpec>&, uint32_t, uint64_t);

std::vector<float> Integrator::sample_values(const std::vector<IntegralSpec>& specs, uint32_t n, uint64_t seed) {
  return program_sample_values<float>(rt_, program_, specs, n, seed);
}

cl::Buffer Integrator::nan_buffer(cl_mem_flags flags, size_t bytes) { return nan_filled_buffer(rt_, flags, bytes); }

namespace {
// 0x7fffffff is a float NaN, and twice a double NaN: exponent bits all ones, mantissa non-zero
// (0x7fc00000 twice would not be: its double exponent is 0x7fc)
constexpr cl_uint kNanPattern = 0x7fffffffu;

void fill_nan(Runtime& rt, const cl::Buffer& b, size_t bytes) {
  rt.queue().enqueueFillBuffer(b, kNanPattern, 0, bytes / sizeof(kNanPattern) * sizeof(kNanPattern));
}
}  // namespace

cl::Buffer Integrator::kept_nan_buffer(KeptBuffer& kept, cl_mem_flags flags, size_t bytes) {
  if (bytes <= kNanCopyBytes) return nan_buffer(flags, bytes);
  if (kept.bytes < bytes) {
    kept.buffer = cl::Buffer(rt_.context(), flags, bytes);
    kept.bytes = bytes;
  }
  fill_nan(rt_, kept.buffer, bytes);
  return kept.buffer;
}

// Buffers up to this size are NaN from the start (CL_MEM_COPY_HOST_PTR, a copy on the host), larger
// ones by a fill command: on PoCL each command costs a hand-over to its worker threads, and a short
// launch (mfv bench --case, 640 points x 32: an 80 KiB values buffer and a sums buffer) paid two
// fills; with copies its fastest of 99 calls took 116-138 us against 135-148 us at alpha 0.01, mu 0.9
// (docs/performance.md, issue 32). A larger buffer's fill stays with the device (a copy of 16 MiB
// would cost the host).
// (kNanCopyBytes: runtime/integrator.hpp)
cl::Buffer nan_filled_buffer(Runtime& rt, cl_mem_flags flags, size_t bytes) {
  if (bytes > 0 && bytes <= kNanCopyBytes) {
    thread_local const std::vector<cl_uint> nan(kNanCopyBytes / sizeof(cl_uint), kNanPattern);
    return cl::Buffer(rt.context(), flags | CL_MEM_COPY_HOST_PTR, bytes, const_cast<cl_uint*>(nan.data()));
  }
  cl::Buffer b(rt.context(), flags, bytes);
  if (bytes > 0) fill_nan(rt, b, bytes);
  return b;
}

}  // namespace mfv
