// Integrator's reciprocity launches (kernels/reciprocity.cl): one pair per
// work-item, the worst asymmetry of each integral read back.
#include "runtime/integrator.hpp"
#include "runtime/specialize.hpp"
#include "runtime/work_group.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

namespace mfv {

// One launch of a reciprocity_values kernel over specs[at[0..]] into the worst of each;
// `k` writes one asymmetry per pair, per_item pairs per work-item (kernels/reciprocity.cl:
// reciprocity_values_microfacet writes pairs i and i + pairs / 2; per_item divides pairs).
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
    cl::Buffer ab = nan_buffer(CL_MEM_WRITE_ONLY, count * pairs * sizeof(float));  // an unwritten pair is the worst
    k.setArg(0, sb);
    k.setArg(1, static_cast<cl_ulong>(seed));
    k.setArg(2, ab);
    rt_.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(items, count), cl::NDRange(local, 1));
    std::vector<float> a(count * pairs);
    rt_.queue().enqueueReadBuffer(ab, CL_TRUE, 0, a.size() * sizeof(float), a.data());
    for (size_t i = 0; i < count; ++i) {
      float worst = 0;
      uint32_t where = 0;
      for (uint32_t p = 0; p < pairs; ++p) {
        const float v = a[i * pairs + p];
        if (!(v <= worst)) worst = std::isnan(v) ? INFINITY : v, where = p;
      }
      out.worst[at[first + i]] = worst;
      out.at[at[first + i]] = where;
    }
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
    // the microfacet kernel takes two pairs per work-item: an even count (reciprocity_pairs'
    // are multiples of 64; an odd count goes to the generic kernel, the same floats)
    if (microfacet() && pairs % 2 == 0 && specs[i].model == MFV_MODEL_MICROFACET && !(specs[i].pd2 > 0) &&
        !(specs[i].width_y > 0)) {
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
    worst_of(microfacet, specs, fast, pairs, seed, out, 2);
  }
  for (const auto& [name, at] : by_model) {
    cl::Kernel k = launched(name);
    worst_of(k, specs, at, pairs, seed, out);
  }
  if (!slow.empty()) worst_of(generic, specs, slow, pairs, seed, out);
  return out;
}

}  // namespace mfv
