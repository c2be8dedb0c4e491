#include "checks/agree_gltf.hpp"

#include "reference/model_gltf.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace mfv {
namespace {

constexpr int kRecord = 16;  // floats per record, kernels/agree_gltf.cl
// Inputs bumped for the conditioning allowance: wi.xyz, wo.xyz, six
// parameters, then (as mfv agree does for D x G x F BRDFs) the four cosines
// formed from the directions, which carry the float rounding of the
// kernel's half vector (l + v cancels as l -> -v).
constexpr int kInputs = 16;

// The reference at the record's inputs, input `bump` (or none, -1) scaled by 1 + by.
double reference_at(const float* r, int bump, double by) {
  double in[12];
  for (int k = 0; k < 12; ++k) in[k] = r[k];
  if (bump >= 0 && bump < 12) in[bump] *= 1.0 + by;
  const ref::GltfChannel p{in[6], in[7], in[8], in[9], in[10], in[11]};
  const glm::dvec3 wi(in[0], in[1], in[2]), wo(in[3], in[4], in[5]);
  if (wi.z <= 0.0 || wo.z <= 0.0) return 0.0;
  ref::Shading sh = ref::shading_from(wi, wo);
  double* cs[4] = {&sh.NoL, &sh.NoV, &sh.NoH, &sh.VoH};
  if (bump >= 12) *cs[bump - 12] *= 1.0 + by;
  return ref::gltf_pbr(p, sh);
}

}  // namespace

AgreeResult agree_gltf(Runtime& rt, cl::Program& prog, const AgreeOptions& opt, uint32_t stream,
                       double& kernel_seconds, double& reference_seconds) {
  AgreeResult res;
  res.name = "MODEL gltf";
  res.samples = opt.samples;
  res.ulp_budget = kGltfUlpBudget;
  const double eps = opt.fp64 ? 0x1p-52 : 0x1p-23;
  const size_t chunk = static_cast<size_t>(std::min<uint64_t>(opt.samples, 1u << 18));
  cl::Buffer buf(rt.context(), CL_MEM_WRITE_ONLY, chunk * kRecord * sizeof(float));
  std::vector<float> rec(chunk * kRecord);
  cl::Kernel k(prog, "agree_gltf");
  std::vector<double> rel;
  rel.reserve(opt.samples);
  double worst_score = -1;
  for (uint64_t first = 0; first < opt.samples; first += chunk) {
    const size_t n = static_cast<size_t>(std::min<uint64_t>(chunk, opt.samples - first));
    rt.queue().enqueueFillBuffer(buf, std::numeric_limits<float>::quiet_NaN(), 0, n * kRecord * sizeof(float));
    k.setArg(0, static_cast<cl_ulong>(opt.seed));
    k.setArg(1, static_cast<cl_uint>(stream));
    k.setArg(2, static_cast<cl_ulong>(first));
    k.setArg(3, buf);
    auto t0 = std::chrono::steady_clock::now();
    rt.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n));
    rt.queue().enqueueReadBuffer(buf, CL_TRUE, 0, n * kRecord * sizeof(float), rec.data());
    auto t1 = std::chrono::steady_clock::now();
    for (size_t i = 0; i < n; ++i) {
      const float* r = rec.data() + i * kRecord;
      double kv = r[12];
      if (std::isfinite(kv)) kv += r[13];
      const double rv = reference_at(r, -1, 0.0);
      const double diff = std::fabs(kv - rv);
      double ulps = diff / ulp_of(rv, opt.fp64);
      double rl = diff / std::max(std::fabs(rv), std::numeric_limits<double>::min());
      if (std::isnan(kv) || std::isnan(rv)) ulps = rl = std::numeric_limits<double>::infinity();
      rel.push_back(rl);
      res.max_rel = std::max(res.max_rel, rl);
      res.max_ulps = std::max(res.max_ulps, ulps);
      const double allowed = std::max((opt.fp64 ? 2.0 : 1.0) * kGltfUlpBudget * ulp_of(rv, opt.fp64), 1e-30);
      bool fail = !(diff <= allowed);
      if (fail && std::isfinite(kv) && std::isfinite(rv)) {
        // as mfv agree: within twice what the exact function moves when one
        // input moves by two units of rounding, the kernel is as good as its format allows
        double dev = 0;
        for (int j = 0; j < kInputs; ++j)
          for (double b : {2 * eps, -2 * eps}) dev = std::max(dev, std::fabs(reference_at(r, j, b) - rv));
        fail = diff > std::max(allowed, 2.0 * dev);
      }
      if (fail) res.failures++;
      const double score = fail ? 1e300 + ulps : ulps;
      if (score > worst_score) {
        worst_score = score;
        res.worst = fmt::format("wi=({:a}, {:a}, {:a}) wo=({:a}, {:a}, {:a}) alpha={:a} metallic={:a} base={:a} "
                                "f0={:a} f0_max={:a} weight={:a} kernel={:a} reference={:a}",
                                r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8], r[9], r[10], r[11], kv, rv);
      }
    }
    auto t2 = std::chrono::steady_clock::now();
    kernel_seconds += std::chrono::duration<double>(t1 - t0).count();
    reference_seconds += std::chrono::duration<double>(t2 - t1).count();
  }
  auto mid = rel.begin() + rel.size() / 2;
  std::nth_element(rel.begin(), mid, rel.end());
  res.median_rel = rel.empty() ? 0 : *mid;
  return res;
}

}  // namespace mfv
