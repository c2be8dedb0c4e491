// Integrator's AlbedoMis launches (kernels/integrate.cl albedo_mis_geometry,
// albedo_mis_df and albedo_mis_values; in a program of one pair
// albedo_mis_pair, the three in one; or one replicate kernel), one row per
// replicate, and sum_values over each row.
#include "runtime/integrator.hpp"
#include "runtime/specialize.hpp"
#include "runtime/work_group.hpp"
#include "util/error.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

namespace mfv {

// AlbedoMis in one kernel specialized to a pair (kernels/integrate.cl MFV_ALBEDO_MIS_PAIR), in a
// program of one pair only (runtime/specialize.cpp): its name without the pair's ids.
constexpr const char* kMisPair = "albedo_mis_pair";

// AlbedoMis integrals through albedo_mis_values (one point per work-item,
// one row per replicate) and sum_values (one sum per row).
std::vector<Integrator::Sums> Integrator::sums_mis(const std::vector<IntegralSpec>& specs, uint64_t seed) {
  std::vector<Sums> out(specs.size() * mis_replicates_);
  // by (values kernel, albedo_mis_df kernel): specialized per G and per D where the program has them
  std::map<std::pair<std::string, std::string>, std::vector<size_t>> by_kernel;
  for (size_t i = 0; i < specs.size(); ++i) {
    // isotropic catalog terms take the vectorized albedo_mis_microfacet (specialized where the
    // program has it); anisotropic terms, whole models and user code albedo_mis_general
    const IntegralSpec& s = specs[i];
    const bool iso = s.model == 0 && !(s.pd2 > 0) && !(s.width_y > 0) && s.phi_o == 0 && fast_albedo_available_;
    const bool flux = s.check == static_cast<int32_t>(IntegralKind::BsdfFlux);  // kernels/transmission.cl
    // one kernel for the pair where the program has it (a program of one pair), else three
    const std::string pair = iso ? kernel_for(kMisPair, s) : "";
    by_kernel[flux                   ? std::pair<std::string, std::string>("bsdf_flux_mis_values", "")
              : iso && pair != kMisPair ? std::pair<std::string, std::string>(pair, "")
              : iso ? std::pair(kernel_for("albedo_mis_values", s), kernel_for("albedo_mis_df", s))
                    : std::pair<std::string, std::string>("albedo_mis_general_values", "")]
        .push_back(i);
  }
  if (compile_ahead_) {  // one integral of each kernel's group, the last group first
    for (auto g = by_kernel.rbegin(); g != by_kernel.rend(); ++g)
      sums_mis({specs[g->second.front()]}, g->first.first, g->first.second, seed);
    return out;
  }
  for (const auto& [kernels, at] : by_kernel) {
    std::vector<IntegralSpec> group;
    for (size_t i : at) group.push_back(specs[i]);
    const std::vector<Sums> sums = sums_mis(group, kernels.first, kernels.second, seed);
    for (size_t j = 0; j < at.size(); ++j)
      std::copy_n(sums.begin() + j * mis_replicates_, mis_replicates_, out.begin() + at[j] * mis_replicates_);
  }
  return out;
}

// Rows a work-group of albedo_mis_geometry, albedo_mis_df and albedo_mis_values takes, at most.
constexpr size_t kMisRowsPerGroup = 8;

std::vector<Integrator::Sums> Integrator::sums_mis(const std::vector<IntegralSpec>& specs, const std::string& kernel,
                                                   const std::string& df_kernel, uint64_t seed) {
  const size_t rows = specs.size() * mis_replicates_;
  std::vector<Sums> out(rows);
  if (specs.empty()) return out;
  const uint32_t n = specs.front().points;  // points per replicate, the same for every spec of a run
  for (const auto& s : specs)
    if (s.points != n || n % 4 != 0) throw Error("internal: AlbedoMis integrals of one run take the same points");
  // albedo_mis_values (generic or by G) reads the points' geometry and D F from albedo_mis_geometry
  // and albedo_mis_df (kernels/integrate.cl): five planes of reals and one of D F (sized as
  // doubles, whatever the program's real)
  const bool three_kernels = !df_kernel.empty();
  constexpr uint64_t kPlanes = 6;
  // 16 MiB of samples a launch, or of planes where there are some
  const uint64_t kMaxValues = three_kernels ? (uint64_t(1) << 21) / kPlanes : uint64_t(1) << 22;
  // rows a launch: at most kMaxCountedGrid, sum_rows' one launch (runtime/work_group.hpp)
  size_t per_launch = size_t(std::clamp<uint64_t>(kMaxValues / n, 1, kMaxCountedGrid));
  // Three kernels, two of them cheap per point (albedo_mis_df is a D and a product), each paying
  // PoCL's cost per work-group: rows of 80 points take 8-point work-groups (row_local_size), so
  // their work-groups take up to 8 rows (kMisRowsPerGroup), a count fixed by the replicates (a
  // launch takes whole integrals), so that PoCL compiles one work-group size per kernel.
  // The one-pair kernel takes as many rows a work-group (bench --case, 640 points: 85 us a launch
  // against 160 us with one row, docs/performance.md "One kernel for one pair"). The one-kernel
  // replicate kernels (albedo_mis_general_values, bsdf_flux_mis_values: scalar,
  // MFV_NO_IMPLICIT_VECTORIZE) take one SIMD width of points and rows as these whatever n is
  // (scalar_row_local_size), so that the furnace's n = 80 and the anisotropic check's n = 160
  // share one compile (docs/performance.md, "Cold start").
  const bool vectorized = three_kernels || kernel.rfind(kMisPair, 0) == 0;
  if (per_launch >= mis_replicates_) per_launch -= per_launch % mis_replicates_;
  size_t rows_local = kMisRowsPerGroup;
  while (mis_replicates_ % rows_local != 0) rows_local /= 2;
  cl::Kernel k = launched(kernel);
  cl::Buffer spec_buf(rt_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, specs.size() * sizeof(IntegralSpec),
                      const_cast<IntegralSpec*>(specs.data()));
  cl::Buffer values = nan_buffer(CL_MEM_READ_WRITE, std::min(per_launch, rows) * n * sizeof(float));
  cl::Kernel geometry_k, df_k;
  cl::Buffer planes, df;
  if (three_kernels) {
    geometry_k = launched("albedo_mis_geometry");
    df_k = launched(df_kernel);
    // no NaN fill: albedo_mis_geometry writes every plane value the next two read, on the same
    // grid (the fill cost as much as the geometry kernel: docs/performance.md, "One kernel for one
    // pair"); `values`, which the sums read, keeps its fill
    planes = cl::Buffer(rt_.context(), CL_MEM_READ_WRITE, (kPlanes - 1) * std::min(per_launch, rows) * n * sizeof(double));
    df = cl::Buffer(rt_.context(), CL_MEM_READ_WRITE, std::min(per_launch, rows) * n * sizeof(double));
  }
  auto enqueue = [&](cl::Kernel& kk, size_t count) {
    const size_t local = vectorized ? row_local_size(kk, rt_.device().device, n)
                                    : scalar_row_local_size(kk, rt_.device().device, n);
    size_t ly = rows_local;
    while (count % ly != 0 || local * ly > fit_local_size(kk, rt_.device().device, 1024)) ly /= 2;
    rt_.queue().enqueueNDRangeKernel(kk, cl::NullRange, cl::NDRange(n, count), cl::NDRange(local, ly));
  };
  for (size_t row0 = 0; row0 < rows && !(compile_ahead_ && row0 > 0); row0 += per_launch) {
    const size_t count = std::min(per_launch, rows - row0);
    if (three_kernels) {
      const auto reps = static_cast<cl_uint>(mis_replicates_), first_row = static_cast<cl_uint>(row0);
      set_args(geometry_k, spec_buf, static_cast<cl_ulong>(seed), reps, first_row, planes, df);
      enqueue(geometry_k, count);
      set_args(df_k, spec_buf, reps, first_row, planes, df);
      enqueue(df_k, count);
      set_args(k, spec_buf, reps, first_row, planes, df, values);
    } else {
      set_args(k, spec_buf, static_cast<cl_ulong>(seed), static_cast<cl_uint>(mis_replicates_),
               static_cast<cl_uint>(row0), values);
    }
    enqueue(k, count);
    sum_rows(values, count, n, out.data() + row0);
  }
  return out;
}

}  // namespace mfv
