// Work-group sizes come from the device's and the kernel's limits
// (host/runtime/work_group.hpp); MFV_MAX_LOCAL_SIZE imposes a small limit on
// any device, as a GPU's register-heavy kernel or Oclgrind's
// OCLGRIND_MAX_WGSIZE=32 would.
#include "checks/integrate.hpp"
#include "checks/stability.hpp"
#include "device_fixture.hpp"
#include "run_mfv.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/work_group.hpp"
#include "scoped_env.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>

using namespace mfv;

namespace {
IntegralSpec ggx_spec(uint32_t stream) {
  IntegralSpec s{};
  const Term* d = &find_term("ggx");
  const Term* g = &find_term("smith_ggx");
  const Term* f = &find_term("schlick");
  s.d = term_index(*d), s.g = term_index(*g), s.f = term_index(*f);
  s.pd = s.pg = 0.3f, s.width = 0.3f, s.f0 = 0.04f, s.cos_o = 0.5f, s.stream = stream;
  return s;
}
}  // namespace

TEST_CASE("The local size is the largest power of two within the preference, device, kernel and cap",
          "[device][work_group]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  cl::Program prog = build_integrate_program(*rt, TermSelection::all());
  cl::Kernel k(prog, "reciprocity_values");
  const size_t kernel_max = k.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(rt->device().device);
  const size_t free = fit_local_size(k, rt->device().device, 64);
  CHECK(free <= 64);
  CHECK(free <= kernel_max);
  CHECK((free & (free - 1)) == 0);
  const test::ScopedEnv cap("MFV_MAX_LOCAL_SIZE", "24");
  CHECK(fit_local_size(k, rt->device().device, 64) == std::min<size_t>(16, free));
  CHECK(fit_local_size(k, rt->device().device, 1024) == std::min<size_t>(16, kernel_max));
}

TEST_CASE("Reciprocity takes the same pairs whatever the work-group size", "[device][work_group]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  Integrator in(*rt, TermSelection::all());
  std::vector<IntegralSpec> specs{ggx_spec(0), ggx_spec(1), ggx_spec(2)};
  const WorstPairs free = in.reciprocity(specs, 64 * 8, 7);
  for (const char* cap : {"32", "8", "1"}) {
    const test::ScopedEnv c("MFV_MAX_LOCAL_SIZE", cap);
    const WorstPairs capped = in.reciprocity(specs, 64 * 8, 7);
    CAPTURE(cap);
    CHECK(capped.worst == free.worst);
    CHECK(capped.at == free.at);
  }
}

TEST_CASE("Integrals and stability pass under a work-group limit of 32", "[device][work_group]") {
  if (!test::device_runtime()) return;
  auto r = test::run_mfv("run --check energy --check reciprocity --model ggx --scale 0.05", "MFV_MAX_LOCAL_SIZE=32");
  CAPTURE(r.out);
  CHECK(r.code == 0);
  auto s = test::run_mfv("stability --only ggx", "MFV_MAX_LOCAL_SIZE=32");
  CAPTURE(s.out);
  CHECK(s.code == 0);
}

TEST_CASE("A bad MFV_MAX_LOCAL_SIZE is one error line and exit 2", "[cli][work_group]") {
  for (const char* bad : {"0", "-4", "abc", "12x", "", "99999999999"}) {
    auto r = test::run_mfv("eval ggx --NoH 0.9", std::string("MFV_MAX_LOCAL_SIZE='") + bad + "'");
    CAPTURE(bad, r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: MFV_MAX_LOCAL_SIZE", 0) == 0);
  }
}
