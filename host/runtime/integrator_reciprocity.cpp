// Integrator's reciprocity launches (kernels/reciprocity.cl): one pair per
// work-item, the worst asymmetry of each integral read back.
#include "runtime/integrator.hpp"
#include "runtime/specialize.hpp"
#include "runtime/work_group.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>

namespace mfv {

namespace {
// Pairs per work-item of reciprocity_values_microfacet (kernels/reciprocity.cl: pairs k + m n of a
// launch n wide, m = 0..3): four measured fastest of 2, 4 and 8 (docs/performance.md, issue 31)
constexpr uint32_t kMicrofacetPairsPerItem = 4;

inline uint32_t bits_of(float x) {
  uint32_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}
}  // namespace

void worst_of_values(const float* v, uint32_t n, float& worst, uint32_t& where) {
  // A float's bits as a signed integer are ordered as the floats among
  // non-negative ones (+inf 0x7f800000 above every finite one) and below 0
  // for negative ones; without its sign bit, above 0x7f800000 for a NaN only.
  // Pass 1, by blocks of kBlock, two integer maxima per block (a loop the
  // compiler vectorizes: a select in it did not): the first block with the
  // greatest value and the last block with a NaN. Pass 2 looks for the
  // index in that one block.
  constexpr uint32_t kBlock = 256;
  constexpr int32_t kInf = 0x7f800000;
  int32_t top = 0;
  uint32_t top_block = 0, nan_block = 0;
  bool nan = false;
  for (uint32_t b = 0; b < n; b += kBlock) {
    const float* q = v + b;
    const uint32_t len = std::min(n - b, kBlock);
    int32_t m = 0, m_abs = 0;
    for (uint32_t i = 0; i < len; ++i) {
      const uint32_t x = bits_of(q[i]);
      m = std::max(m, int32_t(x));
      m_abs = std::max(m_abs, int32_t(x & 0x7fffffffu));
    }
    if (m_abs > kInf) nan = true, nan_block = b;
    else if (m > top) top = m, top_block = b;  // strictly greater: the first block with it
  }
  worst = 0;
  where = 0;
  if (nan) {  // the scan's last update is at the last NaN, to inf
    worst = INFINITY;
    for (uint32_t p = std::min(n, nan_block + kBlock); p-- > nan_block;)
      if (int32_t(bits_of(v[p]) & 0x7fffffffu) > kInf) return void(where = p);
  } else if (top > 0) {  // the scan's last update is at the first greatest value
    std::memcpy(&worst, &top, sizeof worst);
    for (uint32_t p = top_block; p < std::min(n, top_block + kBlock); ++p)
      if (int32_t(bits_of(v[p])) == top) return void(where = p);
  }
}

// One launch of a reciprocity_values kernel over specs[at[0..]] into the worst of each;
// `k` writes one asymmetry per pair, per_item pairs per work-item (kernels/reciprocity.cl:
// reciprocity_values_microfacet writes pairs i + m pairs / 4, m = 0..3; per_item divides pairs).
void Integrator::worst_of(cl::Kernel& k, const std::vector<IntegralSpec>& specs, const std::vector<size_t>& at,
                          uint32_t pairs, uint64_t seed, WorstPairs& out, uint32_t per_item) {
  const uint32_t items = pairs / per_item;  // work-items per integral
  const size_t kMaxValues = size_t(1) << 22;  // 16 MiB of asymmetries a launch
  const size_t per_launch = std::max<size_t>(1, kMaxValues / pairs);
  size_t local = fit_local_size(k, rt_.device().device, 256);  // the device's and kernel's limits
  while (items % local != 0) local /= 2;                       // a power of two that divides items
  for (size_t first = 0; first < at.size() && !(compile_ahead_ && first > 0); first += per_launch) {
    const size_t count = std::min(per_launch, at.size() - first);
    std::vector<IntegralSpec> batch;
    for (size_t i = 0; i < count; ++i) batch.push_back(specs[at[first + i]]);
    cl::Buffer sb(rt_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, count * sizeof(IntegralSpec), batch.data());
    const size_t values = count * pairs, bytes = values * sizeof(float);
    // an unwritten pair is the worst: NaN in every value first
    cl::Buffer ab = kept_nan_buffer(worst_values_, CL_MEM_WRITE_ONLY, bytes);
    k.setArg(0, sb);
    k.setArg(1, static_cast<cl_ulong>(seed));
    k.setArg(2, ab);
    rt_.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(items, count), cl::NDRange(local, 1));
    // read in place (a map: on PoCL's CPU device the buffer's own memory, no copy)
    const auto* a = static_cast<const float*>(rt_.queue().enqueueMapBuffer(ab, CL_TRUE, CL_MAP_READ, 0, bytes));
    for (size_t i = 0; i < count; ++i)
      worst_of_values(a + i * pairs, pairs, out.worst[at[first + i]], out.at[at[first + i]]);
    rt_.queue().enqueueUnmapMemObject(ab, const_cast<float*>(a));
  }
}

WorstPairs Integrator::reciprocity(const std::vector<IntegralSpec>& specs, uint32_t pairs, uint64_t seed) {
  WorstPairs out{std::vector<float>(specs.size(), 0.0f), std::vector<uint32_t>(specs.size(), 0)};
  if (specs.empty() || pairs == 0) return out;
  cl::Kernel generic(program_, "reciprocity_values"), microfacet;
  // not in user programs (mfv check) nor in float64 ones: asked by name, since
  // a failed clCreateKernel is an API error to checkers such as Oclgrind
  if (kernel_names_.count("reciprocity_values_microfacet"))
    microfacet = cl::Kernel(program_, "reciprocity_values_microfacet");
  std::vector<size_t> fast, slow;
  // whole models: the kernel specialized to the model where the program has
  // one (kernels/reciprocity.cl MFV_MODEL_RECIPROCITY_VALUES, PoCL only)
  std::map<std::string, std::vector<size_t>> by_model;
  for (size_t i = 0; i < specs.size(); ++i) {
    // the microfacet kernel takes kMicrofacetPairsPerItem pairs per work-item: a count they divide
    // (reciprocity_pairs' are multiples of 64; another goes to the generic kernel, the same floats)
    if (microfacet() && pairs % kMicrofacetPairsPerItem == 0 && specs[i].model == MFV_MODEL_MICROFACET &&
        !(specs[i].pd2 > 0) && !(specs[i].width_y > 0)) {
      fast.push_back(i);
      continue;
    }
    const std::string name = specialized_name("model_reciprocity_values", specs[i]);
    if (specs[i].model != MFV_MODEL_MICROFACET && kernel_names_.count(name)) by_model[name].push_back(i);
    else slow.push_back(i);
  }
  // the microfacet kernel only where its compile pays (kMicrofacetReciprocityPairs);
  // otherwise the generic one takes those integrals too, the same floats
  if (uint64_t(fast.size()) * pairs < microfacet_reciprocity_from_) {
    slow.insert(slow.end(), fast.begin(), fast.end());
    fast.clear();
  }
  if (compile_ahead_) {  // one integral of each kernel's group
    for (auto* at : {&fast, &slow}) at->resize(std::min<size_t>(at->size(), 1));
    for (auto& [name, at] : by_model) at.resize(1);
  }
  if (!fast.empty()) {
    launched_.insert("reciprocity_values_microfacet");
    worst_of(microfacet, specs, fast, pairs, seed, out, kMicrofacetPairsPerItem);
  }
  for (const auto& [name, at] : by_model) {
    cl::Kernel k = launched(name);
    worst_of(k, specs, at, pairs, seed, out);
  }
  if (!slow.empty()) worst_of(generic, specs, slow, pairs, seed, out);
  return out;
}

}  // namespace mfv
