#include "runtime/integrator.hpp"

#include "runtime/specialize.hpp"
#include "runtime/work_group.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <tuple>

namespace mfv {

std::vector<std::string> catalog_sources(const std::vector<std::string>& then) {
  std::vector<std::string> files = {"common.cl",  "rng.cl",    "terms_d.cl",    "terms_g.cl",
                                    "terms_f.cl", "models.cl", "model_gltf.cl", kDispatchBefore};
  files.insert(files.end(), then.begin(), then.end());
  return files;
}

const std::vector<std::string>& integration_files() {
  static const std::vector<std::string> files = {"estimators.cl",   "albedo.cl",    "convergence.cl",
                                                 "aniso_values.cl", "btdf.cl", "transmission.cl", "integrate.cl", "model_values.cl",
                                                 "reciprocity.cl"};
  return files;
}

const std::vector<std::string>& integrate_sources() {
  static const std::vector<std::string> files = catalog_sources(integration_files());
  return files;
}

cl::Program build_integrate_program(Runtime& rt, const TermSelection& terms) {
  return build_integrate_program(rt, terms,
                                 generate_specializations(terms.specialized) +
                                     generate_model_specializations(terms.models, terms.reciprocity_per_model) + generate_check_kernels());
}

cl::Program build_integrate_program(Runtime& rt, const TermSelection& terms, const std::string& specializations) {
  std::vector<std::string> defines;
  if (rt.device().fp64) defines.push_back("MFV_ACC_DOUBLE");
  // Every term forced inline, so that PoCL vectorizes the fast paths of a
  // program of many terms (docs/performance.md); PoCL only: Intel's CPU
  // runtime miscompiles programs built so (kernels/terms_d.cl).
  const bool pocl = rt.device().platform.find("Portable Computing Language") != std::string::npos;
  if (pocl) defines.push_back("MFV_INLINE_TERMS");
  // The fast paths specialized per term pair (runtime/specialize.hpp): only
  // where the terms are inlined, so that their ids fold to constants.
  std::vector<Runtime::ExtraSource> extra;
  if (pocl && !specializations.empty()) extra.push_back({"<specialized>", specializations, ""});
  return rt.build(integrate_sources(), defines, generate_dispatch(terms), kDispatchBefore, extra);
}

Integrator::Integrator(Runtime& rt, const TermSelection& terms)
    : Integrator(rt, build_integrate_program(rt, terms), true) {}

// The program must define MFV_ACC_DOUBLE exactly when the device has fp64.
Integrator::Integrator(Runtime& rt, cl::Program program, bool catalog)
    : rt_(rt), program_(std::move(program)), acc_double_(rt.device().fp64) {
  // the catalog's program defines albedo_values and the other fast paths (a user program does not)
  fast_albedo_ = fast_albedo_available_ = catalog;
  local_size_ = fit_local_size(cl::Kernel(program_, "integrate"), rt.device().device, 64);
  const std::string names = program_.getInfo<CL_PROGRAM_KERNEL_NAMES>();
  for (size_t at = 0; at < names.size();) {
    size_t end = std::min(names.find(';', at), names.size());
    kernel_names_.insert(names.substr(at, end - at));
    at = end + 1;
  }
  // the checks' own `integrate` kernels the program has, where they take `integrate`'s
  // work-group size (the same slices, so the same sums): asked once, not per integral
  for (const std::string& name : check_kernel_names())
    if (kernel_names_.count(name) &&
        fit_local_size(cl::Kernel(program_, name.c_str()), rt.device().device, 64) == local_size_)
      check_kernels_.insert(name);
}

std::string Integrator::kernel_for(const std::string& base, const IntegralSpec& s) const {
  std::string name = specialized_name(base, s);
  return kernel_names_.count(name) ? name : base;
}

void Integrator::layout(uint64_t samples, uint32_t& per_item, uint32_t& slices) const {
  if (samples == 0) throw Error("samples per integral must be at least 1");
  per_item = static_cast<uint32_t>(std::clamp<uint64_t>((samples + local_size_ - 1) / local_size_, 1, 64));
  per_item += per_item & 1u;  // even, so stratified pairs stay within a work-item
  uint64_t per_slice = local_size_ * per_item;
  uint64_t s = (samples + per_slice - 1) / per_slice;
  if (s > (1u << 24)) throw Error(fmt::format("{} samples per integral is too many", samples));
  slices = static_cast<uint32_t>(s);
}

uint64_t Integrator::samples_used(uint64_t requested) const {
  uint32_t per_item, slices;
  layout(requested, per_item, slices);
  return uint64_t(slices) * local_size_ * per_item;
}

uint32_t Integrator::mis_points(uint64_t requested) const {
  // 5·2^(m-2) points: 2^m visible normals and two defensive shares of 2^(m-3)
  // (kernels/albedo.cl albedo_mis_microfacet), each a whole Sobol net; the
  // largest such count within the budget, at least 20 (m = 4)
  const uint64_t n = (samples_used(requested) + mis_replicates_ - 1) / mis_replicates_;
  if (n > (uint64_t(1) << 26)) throw Error(fmt::format("{} samples per integral is too many", requested));
  uint64_t points = 20;
  while (2 * points <= n) points *= 2;
  return uint32_t(points);
}

namespace {
// How the integrator samples each kind: a closed switch (compiled with
// -Werror=switch, CMakeLists.txt), so that a new IntegralKind states its
// sampling here or does not build; an id outside the enum is an error.
enum class Sampling { Iid, Stratified, Replicates };
Sampling sampling_of(int32_t check) {
  switch (static_cast<IntegralKind>(check)) {
    case IntegralKind::DNorm:     // stratified radius (where the proposal has one width)
    case IntegralKind::EavgRqmc:  // stratified view cosine²
      return Sampling::Stratified;
    case IntegralKind::AlbedoMis:  // points per RQMC replicate
    case IntegralKind::BsdfFlux: return Sampling::Replicates;
    case IntegralKind::Masking:
    case IntegralKind::Albedo:
    case IntegralKind::AlbedoRqmc:
    case IntegralKind::AlbedoRqmcB:
    case IntegralKind::MaskingT:
    case IntegralKind::BsdfAvg: return Sampling::Iid;
  }
  throw Error(fmt::format("internal: check id {} has no integrand (runtime/integrator.cpp sampling_of)", check));
}
}  // namespace

void Integrator::stratify(std::vector<IntegralSpec>& specs, uint64_t samples) const {
  const uint64_t n = samples_used(samples);
  if (n > UINT32_MAX) throw Error(fmt::format("{} samples per stratified integral is too many", n));
  // d_norm: stratified radius; E_avg (RQMC): stratified view cosine² (the
  // point count fixes the spacing, see kernels/integrate.cl). A mixture of
  // widths (width <= 0) draws its component from u_pick, which
  // stratification fixes: those d_norm integrals stay iid.
  const uint32_t mis = mis_points(samples);
  for (auto& s : specs) {
    const Sampling how = sampling_of(s.check);
    s.points = how == Sampling::Replicates ? mis : 0u;
    // mfv convergence's estimators are iid or RQMC; a mixture of widths stays iid (above)
    const bool stratified = how == Sampling::Stratified && s.estimator == 0 &&
                            (s.check != static_cast<int32_t>(IntegralKind::DNorm) || s.width > 0);
    s.strata = stratified ? uint32_t(n) : 0u;
  }
}

// kernels/aniso_values.cl spec_is_aniso_microfacet: anisotropic d_norm
// (stratified), masking and furnace albedo of the catalog's microfacet BRDF.
static const char* aniso_values_kernel(const IntegralSpec& s) {
  if (s.check == static_cast<int32_t>(IntegralKind::DNorm) && s.strata > 0) return "d_norm_aniso_values";
  if (s.check == static_cast<int32_t>(IntegralKind::Masking) && s.strata == 0) return "masking_aniso_values";
  if (s.check == static_cast<int32_t>(IntegralKind::Albedo) && s.strata == 0) return "albedo_aniso_values";
  return nullptr;
}

// kernels/model_values.cl: iid albedo of a whole model of the catalog, isotropic
// proposal, light in the xz-plane (width > 0 is checked by the caller).
static const char* model_values_kernel(const IntegralSpec& s) {
  const bool albedo = s.check == static_cast<int32_t>(IntegralKind::Albedo) && s.strata == 0;
  if (!albedo || s.model >= MFV_MODEL_CATALOG_END || s.width_y > 0 || s.phi_o != 0) return nullptr;
  return "model_albedo_values";
}

// kernels/integrate.cl spec_is_microfacet: the integrals a *_values kernel
// takes (one sample per work-item, vectorized on PoCL): iid albedo and
// masking, stratified d_norm, mfv energy's RQMC albedo and E_avg; and their
// anisotropic counterparts. Returns the kernel, or nullptr.
static const char* values_kernel(const IntegralSpec& s) {
  if (s.estimator != 0 || !(s.width > 0)) return nullptr;
  if (s.model != 0) return model_values_kernel(s);
  if (s.pd2 > 0) return s.width_y > 0 ? aniso_values_kernel(s) : nullptr;
  if (s.phi_o != 0 || s.width_y > 0) return nullptr;
  if (s.check == static_cast<int32_t>(IntegralKind::Albedo) && s.strata == 0) return "albedo_values";
  if (s.check == static_cast<int32_t>(IntegralKind::Masking) && s.strata == 0) return "masking_values";
  if (s.check == static_cast<int32_t>(IntegralKind::DNorm) && s.strata > 0) return "d_norm_values";
  if (s.check == static_cast<int32_t>(IntegralKind::AlbedoRqmc) && s.strata == 0) return "albedo_rqmc_values";
  if (s.check == static_cast<int32_t>(IntegralKind::EavgRqmc) && s.strata > 0) return "albedo_rqmc_values";
  return nullptr;
}

std::string Integrator::integrate_kernel_for(const IntegralSpec& s) const {
  // the check's own `integrate` (runtime/specialize.hpp) where the program has one that takes
  // `integrate`'s work-group size (check_kernels_)
  const std::string name = fast_albedo_ ? check_kernel_name(s) : "";
  return !name.empty() && check_kernels_.count(name) ? name : "integrate";
}

std::vector<Integrator::Sums> Integrator::sums_integrate(const std::vector<IntegralSpec>& specs,
                                                         const std::string& kernel, uint32_t per_item,
                                                         uint32_t slices, uint64_t seed, uint64_t first_index) {
  std::vector<Sums> out(specs.size());
  if (specs.empty()) return out;
  cl::Kernel k = kernel == "integrate" ? cl::Kernel(program_, "integrate") : launched(kernel);
  const size_t acc = acc_double_ ? sizeof(double) : sizeof(float);
  // Batches of at most ~2^15 work-groups keep buffers small and launches
  // short, and at least 16 of them let progress (util/progress.hpp) advance
  // during a check; the samples and sums do not depend on the batching.
  const size_t per_batch = std::max<size_t>(1, std::min((size_t(1) << 15) / slices, (specs.size() + 15) / 16));
  for (size_t first = 0; first < specs.size() && !(compile_ahead_ && first > 0); first += per_batch) {
    size_t count = std::min(per_batch, specs.size() - first);
    size_t groups = count * slices;
    cl::Buffer spec_buf(rt_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, count * sizeof(IntegralSpec),
                        const_cast<IntegralSpec*>(specs.data() + first));
    cl::Buffer sums = nan_buffer(CL_MEM_WRITE_ONLY, groups * MFV_SUM_SLOTS * acc);
    k.setArg(0, spec_buf);
    k.setArg(1, static_cast<cl_uint>(slices));
    k.setArg(2, static_cast<cl_uint>(per_item));
    k.setArg(3, static_cast<cl_ulong>(seed));
    k.setArg(4, sums);
    k.setArg(5, cl::Local(MFV_SUM_SLOTS * local_size_ * acc));
    k.setArg(6, static_cast<cl_ulong>(first_index));
    rt_.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(groups * local_size_), cl::NDRange(local_size_));
    add_sums(sums, count, slices, out.data() + first);
  }
  return out;
}

// The same sums for albedo_fast_path integrals through albedo_values (one
// sample per work-item, stored) and sum_values (the per-slice sums of
// `integrate`): the samples of `integrate`, reduced in the same slices.
std::vector<Integrator::Sums> Integrator::sums_values(const std::vector<IntegralSpec>& specs, const std::string& base,
                                                      const std::string& kernel, const std::string& d_kernel,
                                                      uint32_t per_item, uint32_t slices,
                                                      uint64_t seed, uint64_t first_index) {
  std::vector<Sums> out(specs.size());
  if (specs.empty()) return out;
  const uint64_t per_slice = uint64_t(local_size_) * per_item;  // a multiple of 4 (run())
  // masking_values (generic or by G) reads the samples' geometry and D from masking_geometry and
  // masking_d (kernels/integrate.cl): four planes of reals and one of D (sized as doubles,
  // whatever the program's real)
  const bool three_kernels = !d_kernel.empty();
  constexpr uint64_t kPlanes = 5;
  // 16 MiB of samples a launch, or of planes where there are some (the sums do not depend on it)
  const uint64_t kMaxValues = three_kernels ? (uint64_t(1) << 21) / kPlanes : uint64_t(1) << 22;
  // A launch takes `count` integrals over slices [s0, s0 + nslices).
  // and at most kMaxCountedGrid work-groups, one work-item each in the reduction (runtime/work_group.hpp)
  const uint32_t nslices =
      uint32_t(std::clamp<uint64_t>(std::min<uint64_t>(kMaxValues / per_slice, kMaxCountedGrid), 1, slices));
  const size_t per_launch =
      nslices == slices ? std::max<size_t>(1, std::min(kMaxValues / (per_slice * slices), kMaxCountedGrid / slices))
                        : 1;
  // stratified d_norm: neighbouring strata's squared differences, as `integrate`
  const bool pairs = base == "d_norm_values" || base == "d_norm_aniso_values";
  // RQMC: an E and a B plane, reduced by sum_rqmc
  const bool rqmc = base == "albedo_rqmc_values";
  // two samples per work-item, k and k + m / 2 of a row of m (kernels/estimators.cl MFV_SAMPLE_VALUES_2)
  const uint64_t per_work_item = base == "albedo_values" || base == "d_norm_values" ? 2 : 1;
  cl::Kernel values_k = launched(kernel), sum_k(program_, rqmc ? "sum_rqmc" : pairs ? "sum_pairs" : "sum_values");
  const size_t capacity = std::min(per_launch, specs.size()) * nslices * per_slice * (rqmc ? 2 : 1);
  cl::Buffer values = nan_buffer(CL_MEM_READ_WRITE, capacity * sizeof(float));
  cl::Kernel geometry_k, d_k;
  cl::Buffer planes, dv;
  if (three_kernels) {
    geometry_k = launched("masking_geometry");
    d_k = launched(d_kernel);
    // no NaN fill: masking_geometry writes every plane value the next two read, on the same grid
    // (as AlbedoMis's planes, runtime/integrator_mis.cpp); `values` keeps its fill
    planes = cl::Buffer(rt_.context(), CL_MEM_READ_WRITE, (kPlanes - 1) * capacity * sizeof(double));
    dv = cl::Buffer(rt_.context(), CL_MEM_READ_WRITE, capacity * sizeof(double));
  }
  const size_t acc = acc_double_ ? sizeof(double) : sizeof(float);
  for (size_t first = 0; first < specs.size() && !(compile_ahead_ && first > 0); first += per_launch) {
    const size_t count = std::min(per_launch, specs.size() - first);
    cl::Buffer spec_buf(rt_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, count * sizeof(IntegralSpec),
                        const_cast<IntegralSpec*>(specs.data() + first));
    for (uint32_t s0 = 0; s0 < slices && !(compile_ahead_ && s0 > 0); s0 += nslices) {
      const uint32_t ns = std::min(nslices, slices - s0);
      const size_t m = size_t(ns) * per_slice, groups = count * ns, width = m / per_work_item;
      // the largest power of two up to 1024 that divides the launch's width and that the device and kernel allow
      size_t local = fit_local_size(values_k, rt_.device().device, 1024);
      if (three_kernels)
        local = std::min({local, fit_local_size(geometry_k, rt_.device().device, 1024),
                          fit_local_size(d_k, rt_.device().device, 1024)});
      while (width % local != 0) local /= 2;
      if (three_kernels) {
        set_args(geometry_k, spec_buf, static_cast<cl_ulong>(seed),
                 static_cast<cl_ulong>(first_index + uint64_t(s0) * per_slice), planes);
        rt_.queue().enqueueNDRangeKernel(geometry_k, cl::NullRange, cl::NDRange(m, count), cl::NDRange(local, 1));
        set_args(d_k, spec_buf, planes, dv);
        rt_.queue().enqueueNDRangeKernel(d_k, cl::NullRange, cl::NDRange(m, count), cl::NDRange(local, 1));
        set_args(values_k, spec_buf, planes, dv, values);
      } else {
        set_args(values_k, spec_buf, static_cast<cl_ulong>(seed),
                 static_cast<cl_ulong>(first_index + uint64_t(s0) * per_slice), values);
      }
      rt_.queue().enqueueNDRangeKernel(values_k, cl::NullRange, cl::NDRange(width, count), cl::NDRange(local, 1));
      const size_t padded = counted_grid(sum_k, rt_.device().device, groups);  // a sum per launched work-item
      cl::Buffer sums = nan_buffer(CL_MEM_WRITE_ONLY, padded * MFV_SUM_SLOTS * acc);
      sum_k.setArg(0, values);
      sum_k.setArg(1, static_cast<cl_uint>(per_slice));
      if (rqmc) {
        sum_k.setArg(2, static_cast<cl_ulong>(count * m));  // the B plane follows the E plane
        sum_k.setArg(3, spec_buf);                          // stratified (E_avg) or not, per integral
        sum_k.setArg(4, static_cast<cl_uint>(ns));
        sum_k.setArg(5, sums);
        sum_k.setArg(6, static_cast<cl_ulong>(groups));
      } else {
        sum_k.setArg(2, sums);
        sum_k.setArg(3, static_cast<cl_ulong>(groups));
      }
      enqueue_counted(rt_.queue(), sum_k, rt_.device().device, groups);
      add_sums(sums, count, ns, out.data() + first);
    }
  }
  return out;
}

// sum_values over `rows` consecutive runs of per_row values (a multiple of 4).
void Integrator::sum_rows(const cl::Buffer& values, size_t rows, uint64_t per_row, Sums* out) {
  cl::Kernel sum_k(program_, "sum_values");
  const size_t acc = acc_double_ ? sizeof(double) : sizeof(float);
  cl::Buffer sums = nan_buffer(CL_MEM_WRITE_ONLY, counted_grid(sum_k, rt_.device().device, rows) * MFV_SUM_SLOTS * acc);
  sum_k.setArg(0, values);
  sum_k.setArg(1, static_cast<cl_uint>(per_row));
  sum_k.setArg(2, sums);
  sum_k.setArg(3, static_cast<cl_ulong>(rows));
  enqueue_counted(rt_.queue(), sum_k, rt_.device().device, rows);
  add_sums(sums, rows, 1, out);
}

cl::Kernel Integrator::launched(const std::string& kernel) {
  launched_.insert(kernel);
  return cl::Kernel(program_, kernel.c_str());
}

// Mean and standard error of an AlbedoMis integral from its replicates' sums
// of n points each: the replicate means are iid, so SE = sd / sqrt(R) with
// R - 1 degrees of freedom.
static Estimate replicate_estimate(const double* sums, uint32_t replicates, uint32_t n) {
  Estimate e;
  e.samples = uint64_t(replicates) * n;
  double mean = 0;
  for (uint32_t r = 0; r < replicates; ++r) mean += sums[r] / n;
  mean /= replicates;
  double ss = 0;
  for (uint32_t r = 0; r < replicates; ++r) ss += (sums[r] / n - mean) * (sums[r] / n - mean);
  e.mean = mean;
  e.stderr_ = std::sqrt(ss / double(replicates - 1) / double(replicates));
  e.dof = replicates - 1;
  if (!std::isfinite(mean)) e.mean = e.stderr_ = std::numeric_limits<double>::quiet_NaN();
  return e;
}

// Adds the (sum, sum of squares) pairs of `count` integrals x `slices`
// work-groups (integral-major, in acc_t) to out[0 .. count).
void Integrator::add_sums(const cl::Buffer& sums, size_t count, uint32_t slices, Sums* out) {
  const size_t groups = count * slices;
  std::vector<double> host(groups * MFV_SUM_SLOTS);
  if (acc_double_) {
    rt_.queue().enqueueReadBuffer(sums, CL_TRUE, 0, groups * MFV_SUM_SLOTS * sizeof(double), host.data());
  } else {
    std::vector<float> f(groups * MFV_SUM_SLOTS);
    rt_.queue().enqueueReadBuffer(sums, CL_TRUE, 0, groups * MFV_SUM_SLOTS * sizeof(float), f.data());
    std::copy(f.begin(), f.end(), host.begin());
  }
  for (size_t i = 0; i < count; ++i)
    for (uint32_t j = 0; j < slices; ++j) {
      out[i].sum += host[MFV_SUM_SLOTS * (i * slices + j) + MFV_SLOT_SUM];
      out[i].sumsq += host[MFV_SUM_SLOTS * (i * slices + j) + MFV_SLOT_SECOND];
    }
  if (task_) task_->advance(groups * group_samples_);
}

std::vector<Estimate> Integrator::run(const std::vector<IntegralSpec>& specs_in, uint64_t samples, uint64_t seed,
                                      uint64_t first_index) {
  uint32_t per_item, slices;
  layout(samples, per_item, slices);
  const uint64_t n = uint64_t(slices) * local_size_ * per_item;
  std::vector<IntegralSpec> specs = specs_in;
  stratify(specs, samples);
  if (first_index > 0)
    for (auto& s : specs)
      if (s.strata > 0) throw Error("internal: a stratified integral cannot be extended (first_index > 0)");
  // isotropic microfacet integrals take the vectorizable fast paths
  std::vector<IntegralSpec> mis;
  std::vector<size_t> mis_at;
  // the integrals `integrate` takes, by kernel (the generic one or a check's own)
  std::map<std::string, std::vector<size_t>> general_at;
  // by (base, values kernel, masking_d kernel), specialized where the program has them
  std::map<std::tuple<std::string, std::string, std::string>, std::vector<size_t>> fast_at;
  for (size_t j = 0; j < specs.size(); ++j) {
    if (sampling_of(specs[j].check) == Sampling::Replicates) {
      if (!(specs[j].width > 0) || specs[j].estimator != 0)
        throw Error("internal: AlbedoMis takes integrals with a proposal width > 0 (kernels/albedo.cl albedo_mis_general)");
      mis.push_back(specs[j]);
      mis_at.push_back(j);
      continue;
    }
    // sum_values takes runs of a multiple of 4 (per_item is even)
    const char* fast = fast_albedo_ && local_size_ % 2 == 0 ? values_kernel(specs[j]) : nullptr;
    const std::string kernel = fast ? kernel_for(fast, specs[j]) : "";
    // a path the program lacks goes to `integrate` (whole models have only
    // their specialized kernels: kernels/model_values.cl)
    if (fast && !kernel_names_.count(kernel)) fast = nullptr;
    if (fast) {
      const bool masking = std::string(fast) == "masking_values";  // and masking_d (kernels/integrate.cl)
      fast_at[{fast, kernel, masking ? kernel_for("masking_d", specs[j]) : ""}].push_back(j);
    } else {
      general_at[integrate_kernel_for(specs[j])].push_back(j);
    }
  }
  std::vector<Sums> sums(specs.size());
  progress::Task task("samples", specs.size() * n);
  task_ = &task;
  group_samples_ = uint64_t(local_size_) * per_item;
  if (compile_ahead_) {  // each kernel's first launch, on one integral of each specialized group, the last first
    sums_mis(mis, seed);
    for (const auto& [kernel, at] : general_at)
      sums_integrate({specs[at.front()]}, kernel, per_item, slices, seed, first_index);
    for (auto g = fast_at.rbegin(); g != fast_at.rend(); ++g)
      sums_values({specs[g->second.front()]}, std::get<0>(g->first), std::get<1>(g->first), std::get<2>(g->first),
                  per_item, slices, seed, first_index);
    task_ = nullptr;
    return std::vector<Estimate>(specs.size());
  }
  for (const auto& [kernel, at] : fast_at) {
    std::vector<IntegralSpec> fast;
    for (size_t j : at) fast.push_back(specs[j]);
    const auto fs = sums_values(fast, std::get<0>(kernel), std::get<1>(kernel), std::get<2>(kernel), per_item, slices,
                                seed, first_index);
    for (size_t j = 0; j < at.size(); ++j) sums[at[j]] = fs[j];
  }
  for (const auto& [kernel, at] : general_at) {
    std::vector<IntegralSpec> general;
    for (size_t j : at) general.push_back(specs[j]);
    const auto gs = sums_integrate(general, kernel, per_item, slices, seed, first_index);
    for (size_t j = 0; j < at.size(); ++j) sums[at[j]] = gs[j];
  }
  task_ = nullptr;
  std::vector<Estimate> out(specs.size());
  const auto ms = sums_mis(mis, seed);
  for (size_t j = 0; j < mis.size(); ++j) {
    std::vector<double> rep(mis_replicates_);
    for (uint32_t r = 0; r < mis_replicates_; ++r) rep[r] = ms[j * mis_replicates_ + r].sum;
    out[mis_at[j]] = replicate_estimate(rep.data(), mis_replicates_, mis[j].points);
  }
  for (size_t i = 0; i < specs.size(); ++i) {
    if (sampling_of(specs[i].check) == Sampling::Replicates) continue;
    const double s = sums[i].sum, ss = sums[i].sumsq;
    Estimate& e = out[i];
    e.samples = n;
    e.mean = s / double(n);
    if (specs[i].check == static_cast<int32_t>(IntegralKind::AlbedoRqmc)) {
      e.b_mean = ss / double(n);  // the kernel's second accumulator holds B here
      e.stderr_ = std::numeric_limits<double>::quiet_NaN();
    } else if (specs[i].strata > 0) {
      // pairs of neighbouring strata as strata of two: Var = sum (y_a - y_b)^2 / n^2
      e.stderr_ = std::sqrt(ss) / double(n);
    } else {
      double var = std::max(0.0, ss / double(n) - e.mean * e.mean) * double(n) / double(n - (n > 1 ? 1 : 0));
      e.stderr_ = std::sqrt(var / double(n));
    }
    if (!std::isfinite(s) || !std::isfinite(ss))
      e.mean = e.stderr_ = e.b_mean = std::numeric_limits<double>::quiet_NaN();
  }
  return out;
}

}  // namespace mfv
