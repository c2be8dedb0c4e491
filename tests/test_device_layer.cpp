// The device layer (host/runtime/integrator.*) and the table of checks
// (host/checks/check_table.*): buffers start as NaN, so a result no kernel
// wrote fails instead of passing; the table's rows are what the plan builder
// integrates.
#include "checks/suite.hpp"
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "runtime/integrator.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <sched.h>
#include <unistd.h>
#include <cstdlib>
#include <iterator>
#include <random>
#include <filesystem>
#include <fstream>
#include <string>

using namespace mfv;

namespace {

TermSelection ggx_selection() {
  TermSelection sel;
  sel.d = {&find_term("ggx")};
  sel.g = {&find_term("smith_ggx")};
  sel.f = {&find_term("schlick")};
  return sel;
}

IntegralSpec ggx_albedo(uint32_t stream) {
  MicrofacetIntegral m;
  m.d = &find_term("ggx"), m.g = &find_term("smith_ggx"), m.f = &find_term("schlick");
  m.pd = m.pg = m.width = 0.3;
  m.f0 = 0.04, m.cos_o = 0.5;
  IntegralSpec s = spec_of(m);
  s.stream = stream;
  return s;
}

}  // namespace

TEST_CASE("A reciprocity pair no kernel wrote counts as the worst asymmetry", "[device][device_layer]") {
  if (!test::device_runtime()) return;
  // the microfacet kernel leaves the asymmetry of pair 0 unwritten
  const test::PlantedKernelDir dir("reciprocity.cl", "  asym[j * 4 * n + k] = reciprocity_microfacet_asym(",
                                   "  if (k > 0) asym[j * 4 * n + k] = reciprocity_microfacet_asym(");
  Runtime planted = dir.runtime();
  Integrator bad(planted, ggx_selection());
  bad.set_microfacet_reciprocity_from(0);  // the planted kernel, however few the pairs
  const WorstPairs w = bad.reciprocity({ggx_albedo(0)}, 64, 7);
  CHECK(std::isinf(w.worst[0]));
  CHECK(w.at[0] == 0);
  Integrator good(*test::device_runtime(), ggx_selection());
  CHECK(good.reciprocity({ggx_albedo(0)}, 64, 7).worst[0] < 1e-4);
}

TEST_CASE("A reciprocity pair no kernel wrote counts as the worst in a launch over the kept buffer",
          "[device][device_layer]") {
  if (!test::device_runtime()) return;
  // a launch above kNanCopyBytes reuses worst_of's buffer: it is NaN again before each launch, so
  // pair 0, left unwritten at seed 8 only, is not read as seed 7's value from the call before
  const test::PlantedKernelDir dir("reciprocity.cl", "  asym[j * 4 * n + k] = reciprocity_microfacet_asym(",
                                   "  if (k > 0 || seed != 8) asym[j * 4 * n + k] = reciprocity_microfacet_asym(");
  Runtime planted = dir.runtime();
  Integrator bad(planted, ggx_selection());
  bad.set_microfacet_reciprocity_from(0);
  std::vector<IntegralSpec> specs;
  for (uint32_t i = 0; i < 40; ++i) specs.push_back(ggx_albedo(i));
  const uint32_t pairs = 8192;  // 40 x 8192 floats: 1.25 MiB, above kNanCopyBytes
  REQUIRE(specs.size() * pairs * sizeof(float) > kNanCopyBytes);
  const WorstPairs before = bad.reciprocity(specs, pairs, 7), after = bad.reciprocity(specs, pairs, 8);
  for (size_t i = 0; i < specs.size(); ++i) {
    CHECK(before.worst[i] < 1e-4);
    CHECK(std::isinf(after.worst[i]));
    CHECK(after.at[i] == 0);
  }
}

TEST_CASE("worst_of_values finds the worst and its pair as the one-pass scan does", "[device_layer]") {
  // the scan it replaces (Integrator::worst_of until issue 31): NaN is infinity at the last NaN,
  // else the first greatest value above 0
  auto scan = [](const std::vector<float>& v, float& worst, uint32_t& where) {
    worst = 0, where = 0;
    for (uint32_t p = 0; p < v.size(); ++p)
      if (!(v[p] <= worst)) worst = std::isnan(v[p]) ? INFINITY : v[p], where = p;
  };
  std::mt19937 rng(31);
  const float specials[] = {0.0f, -0.0f, -1.0f, INFINITY, -INFINITY, NAN, -NAN, 1e-30f, 0.5f, 0.25f};
  int compared = 0;
  for (uint32_t n : {0u, 1u, 7u, 255u, 256u, 257u, 1000u, 4096u}) {
    for (int trial = 0; trial < 200; ++trial) {
      std::vector<float> v(n);
      // few distinct values, so ties are common; a few specials planted
      for (float& x : v) x = float(rng() % 5) * 0.125f;
      const int plant = trial % 4 == 0 ? 0 : int(rng() % 4);
      for (int i = 0; i < plant && n > 0; ++i) v[rng() % n] = specials[rng() % std::size(specials)];
      if (trial % 3 == 0)
        for (float& x : v) x = -x;  // none above 0 (but a planted positive special)
      float w0, w1;
      uint32_t a0, a1;
      scan(v, w0, a0);
      worst_of_values(v.data(), n, w1, a1);
      const bool same =
          (std::isinf(w0) ? std::isinf(w1) : w0 == w1) && std::signbit(w0) == std::signbit(w1) && a0 == a1;
      if (!same)
        FAIL_CHECK("n " << n << " trial " << trial << ": " << w0 << " at " << a0 << " against " << w1 << " at " << a1);
      ++compared;
    }
  }
  CHECK(compared == 8 * 200);
}

TEST_CASE("The microfacet reciprocity kernel of four pairs per work-item gives every pair the generic kernel's bits",
          "[device][device_layer][reciprocity]") {
  // kernels/reciprocity.cl: reciprocity_values_microfacet writes pairs k + m n (m = 0..3) of a launch n wide,
  // reciprocity_values (spec_brdf) pair k of a launch as wide as the pairs; every pair of three widths
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  const cl::Program program = build_integrate_program(*rt, ggx_selection());
  std::vector<IntegralSpec> specs;
  for (float alpha : {0.3f, 0.02f, 1.0f}) {
    specs.push_back(ggx_albedo(uint32_t(specs.size())));
    specs.back().pd = specs.back().pg = alpha;
  }
  const uint32_t pairs = 4096;
  const size_t bytes = specs.size() * pairs * sizeof(float);
  auto asymmetries = [&](const char* kernel, size_t items) {
    cl::Kernel k(program, kernel);
    cl::Buffer sb(rt->context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, specs.size() * sizeof(IntegralSpec),
                  specs.data());
    cl::Buffer ab(rt->context(), CL_MEM_WRITE_ONLY, bytes);
    rt->queue().enqueueFillBuffer(ab, cl_uint(0x7fffffffu), 0, bytes);  // NaN: an unwritten pair differs
    k.setArg(0, sb);
    k.setArg(1, cl_ulong(7));
    k.setArg(2, ab);
    rt->queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(items, specs.size()));
    std::vector<uint32_t> bits(bytes / sizeof(float));
    rt->queue().enqueueReadBuffer(ab, CL_TRUE, 0, bytes, bits.data());
    return bits;
  };
  const auto generic = asymmetries("reciprocity_values", pairs);
  const auto fast = asymmetries("reciprocity_values_microfacet", pairs / 4);
  size_t differ = 0, nonzero = 0;
  for (size_t i = 0; i < generic.size(); ++i) {
    differ += generic[i] != fast[i];
    nonzero += generic[i] != 0 && generic[i] != 0x7fffffffu;
  }
  CHECK(differ == 0);
  // not vacuous: about a third are float rounding's asymmetries (4326 of 12288 here), not 0 or NaN
  CHECK(nonzero > generic.size() / 10);
}

TEST_CASE("An integral whose sums no kernel wrote is NaN, not zero", "[device][device_layer]") {
  if (!test::device_runtime()) return;
  // the first work-group of every launch (here: each integral's only slice) leaves its sums unwritten
  const test::PlantedKernelDir dir("integrate.cl", "  if (lid == 0) {", "  if (lid == 0 && group > 0) {");
  Runtime planted = dir.runtime();
  for (bool plant : {true, false}) {
    Integrator in(plant ? planted : *test::device_runtime(), ggx_selection());
    in.set_albedo_fast_path(false);  // every integral through `integrate`
    const auto est = in.run({ggx_albedo(0), ggx_albedo(1)}, 4096, 3);
    CAPTURE(plant, est[0].mean, est[1].mean);
    for (const auto& e : est) CHECK(std::isnan(e.mean) == plant);
  }
}

TEST_CASE("The table of checks gives each D x G x F check its kind, samples and grid", "[suite][check_table]") {
  CHECK(check_row("d_norm").kind == IntegralKind::DNorm);
  CHECK(check_row("masking").kind == IntegralKind::Masking);
  CHECK(!check_row("masking").upper_only);
  CHECK(check_row("furnace").upper_only);
  CHECK(check_row("energy").base_samples == kSuiteBaseSamples / 2);
  CHECK_THROWS_AS(check_row("no_such_check"), Error);
  // the plan builder takes the row's grid: widths x views per D x G
  SuiteOptions opt;
  opt.checks = {"masking"};
  const std::vector<Plan> plans = make_plans(opt);
  REQUIRE(!plans.empty());
  const CheckRow& row = check_row("masking");
  CHECK(plans[0].check == "masking");
  CHECK(plans[0].samples == scaled_samples(row.base_samples, 1.0));
  CHECK(plans[0].specs.size() ==
        terms_of(Kind::D).size() * terms_of(Kind::G).size() * size_t(row.n_alpha) * size_t(row.n_view));
  for (const auto& s : plans[0].specs) CHECK(s.check == MFV_CHECK_MASKING);
}

// PoCL's worker threads pinned one to a core (runtime/opencl.hpp
// pin_pocl_workers): unpinned, a short launch often ran on one core
// (docs/performance.md, issue 32). Each CTest entry is its own process, so
// list_devices() here comes before PoCL starts and its POCL_AFFINITY takes.
TEST_CASE("PoCL's CPU worker threads are pinned one to a core", "[device][device_layer]") {
  if (const char* before = std::getenv("POCL_AFFINITY"))
    return test::skip(std::string("POCL_AFFINITY is set in the environment: ") + before);
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  if (!test::is_pocl(*rt) || rt->device().type != "CPU" || rt->device().compute_units < 2)
    return test::skip("not PoCL's CPU device with two cores or more");
  // pinned only where this process may run on every online CPU (PoCL pins worker i to CPU i)
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  const long online = ::sysconf(_SC_NPROCESSORS_ONLN);
  REQUIRE(::sched_getaffinity(0, sizeof allowed, &allowed) == 0);
  if (CPU_COUNT(&allowed) != online)
    return test::skip("this process may not run on every online CPU: PoCL's workers stay unpinned");
  const char* set = std::getenv("POCL_AFFINITY");
  CHECK(std::string(set ? set : "(unset)") == "1");
  // a launch, so that every worker has started
  Integrator in(*rt, ggx_selection());
  in.run({ggx_albedo(0)}, 4096, 3);
  // threads of this process allowed one CPU only: PoCL's pinned workers
  size_t pinned = 0;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream status(task.path() / "status");
    for (std::string line; std::getline(status, line);)
      if (line.rfind("Cpus_allowed_list:", 0) == 0) {
        const std::string list = line.substr(line.find(':') + 1);
        if (list.find_first_of(",-") == std::string::npos) ++pinned;
      }
  }
  CHECK(pinned >= rt->device().compute_units);
}
