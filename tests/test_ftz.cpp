// Flush-to-zero (issue 19): many GPUs flush float subnormals. Built with
// -cl-denorms-are-zero (MFV_CL_OPTIONS), which PoCL and Intel's CPU runtime
// honour (measured: exp(-95) reads 0), the Beckmann lobes still agree with
// the reference; their old form exp(-x) / (π α² cos⁴θ), whose exp(-x) is
// subnormal before a division by a small number scales it back up to
// ~1e-28, gives 0 there and fails, while on a device that keeps denormals it
// passes: only a flush-to-zero build catches it.
#include "agree_options.hpp"
#include "checks/agree.hpp"
#include "device_fixture.hpp"
#include "kernel_dir.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>

using namespace mfv;

namespace {

// The Beckmann lobes' agreement on `dir`'s kernels, built flushing
// subnormals or not (agree then allows FLT_MIN absolute, as on a
// flush-to-zero device: Runtime marks such a build so).
AgreeReport beckmann_agree(const std::string& dir, bool ftz) {
  if (ftz) ::setenv("MFV_CL_OPTIONS", "-cl-denorms-are-zero", 1);
  Runtime rt("", dir);
  ::unsetenv("MFV_CL_OPTIONS");
  CHECK(rt.device().fp32_denorms == !ftz);
  // tan θ within ~10 α of the normal at α ~ 1e-7 .. 1e-5 is rare in agree's
  // draw: 1e5 samples reach it (measured: the planted form below fails 2 at
  // seed 1; 3e4 samples do not reach it)
  AgreeOptions opt = test::agree_options({"D aniso_beckmann"}, 100000);
  opt.seed = 1;
  return run_agree(rt, opt);
}

}  // namespace

TEST_CASE("The Beckmann lobes agree with the reference in a flush-to-zero build", "[device][agree][ftz]") {
  if (!test::device_runtime()) return;
  AgreeReport rep = beckmann_agree("", true);
  REQUIRE(rep.results.size() == 1);
  CAPTURE(rep.results[0].max_ulps, rep.results[0].worst);
  CHECK(rep.results[0].pass());
}

TEST_CASE("The old Beckmann form exp(-x)/s fails agreement in a flush-to-zero build and only there",
          "[device][agree][ftz][planted]") {
  if (!test::device_runtime()) return;
  const test::PlantedKernelDir dir(
      "terms_d.cl", "static inline real beckmann_exp_over(real x, real s) {\n",
      "static inline real beckmann_exp_over(real x, real s) {\n"
      "  { real e0 = exp(-x); if (e0 == R(0.0)) return R(0.0); return e0 / s; }  // planted\n");
  AgreeReport ftz = beckmann_agree(dir.path(), true);
  REQUIRE(ftz.results.size() == 1);
  CAPTURE(ftz.results[0].max_ulps, ftz.results[0].worst);
  CHECK_FALSE(ftz.results[0].pass());
  AgreeReport denorm = beckmann_agree(dir.path(), false);
  REQUIRE(denorm.results.size() == 1);
  CHECK(denorm.results[0].pass());
}
