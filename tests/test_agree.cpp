#include "agree_options.hpp"
#include "catalog/bsdfs.hpp"
#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "checks/agree.hpp"
#include "device_fixture.hpp"
#include "kernel_dir.hpp"

#include <catch2/catch.hpp>

using namespace mfv;

TEST_CASE("Every kernel term and every D x G x F BRDF agrees with the double reference on identical inputs",
          "[device][agree]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  AgreeOptions opt = test::agree_options({}, 20000);
  opt.seed = 12345;
  AgreeReport rep = run_agree(*rt, opt);
  // From the catalog (checks/agree.cpp make_cases): every term; the G1 of
  // each one-width Smith G (smith_ggx_correlated shares smith_ggx's); the
  // D x G x F BRDFs of the shared-width grid; each anisotropic D with its
  // Smith G under every F; every whole model; every rough dielectric BTDF.
  size_t g1s = 0, aniso_brdfs = 0;
  for (auto& t : catalog()) g1s += !t.aniso && !t.g1_kernel_fn.empty() && t.id != "smith_ggx_correlated";
  for (auto* d : aniso_terms_of(Kind::D))
    for (auto* g : aniso_terms_of(Kind::G)) aniso_brdfs += g->fit_for(d->id) ? terms_of(Kind::F).size() : 0;
  const size_t grid = terms_of(Kind::D).size() * terms_of(Kind::G).size() * terms_of(Kind::F).size();
  CHECK(rep.results.size() == catalog().size() + g1s + grid + aniso_brdfs + models().size() + bsdfs().size());
  test::check_every_case_passes(rep);
  for (auto& r : rep.results) {
    CAPTURE(r.name);
    CHECK(r.samples == opt.samples);
  }
}

TEST_CASE("float64 kernels agree with the reference to double-precision budgets", "[device][agree][fp64]") {
  Runtime* rt = test::fp64_runtime("float64 agreement");
  if (!rt) return;
  AgreeOptions opt = test::agree_options({}, 20000);
  opt.fp64 = true;
  test::check_every_case_passes(run_agree(*rt, opt));
}

TEST_CASE("Agreement catches a kernel term that is off by one part in ten thousand", "[device][agree][planted]") {
  if (!test::device_runtime()) return;
  const test::PlantedKernelDir dir("terms_d.cl", "real d = R(1.0) / (MFV_PI * a2 * k * k);",
                                   "real d = R(1.0001) / (MFV_PI * a2 * k * k);");
  Runtime rt = dir.runtime();
  AgreeReport rep = run_agree(rt, test::agree_options({"D ggx", "BRDF ggx/smith_ggx/none"}, 5000));
  REQUIRE(rep.results.size() == 2);
  test::check_every_case_fails(rep);
}

TEST_CASE("An agree case draws the same inputs whichever other cases run beside it", "[device][agree][streams]") {
  // Its stream is a hash of its name, not its position in the list: alone it
  // is case 0, after "D ggx" case 1; with positional streams the two runs
  // would draw different inputs and report a different worst input.
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  const AgreeReport alone = run_agree(*rt, test::agree_options({"BRDF ggx/smith_ggx/none"}, 4000));
  const AgreeReport beside = run_agree(*rt, test::agree_options({"D ggx", "BRDF ggx/smith_ggx/none"}, 4000));
  REQUIRE(alone.results.size() == 1);
  REQUIRE(beside.results.size() == 2);
  const AgreeResult& a = alone.results[0];
  const AgreeResult& b = beside.results[1];
  REQUIRE(b.name == a.name);
  CHECK(b.worst == a.worst);
  CHECK(b.max_rel == a.max_rel);
  CHECK(b.median_rel == a.median_rel);
}

TEST_CASE("Kernel G1 terms follow seed 000: (v.n) at or above 1 gives 1, at or below the horizon 0, never NaN",
          "[device][edge][g1]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  auto id = GENERATE(as<std::string>{}, "smith_beckmann_approx", "smith_beckmann", "smith_phong", "smith_ggx");
  struct Case {
    float NoV;
    double expected;
  };
  auto c = GENERATE(Case{1.0f, 1.0}, Case{0x1.000002p+0f, 1.0}, Case{0x1.00001p+0f, 1.0}, Case{0.0f, 0.0},
                    Case{-0.25f, 0.0});
  CAPTURE(id, c.NoV);
  PointSpec p;
  p.mode = EvalMode::G1;
  p.g = &find_term(id);
  p.inputs[1] = c.NoV;
  p.params[1] = id == "smith_phong" ? 30.0f : 0.3f;
  PointValue r = eval_point(*rt, p, false);
  CHECK(r.kernel == c.expected);
  CHECK(r.reference == c.expected);
}

TEST_CASE("A kernel that does not compile reports its build log with the real file name", "[device][errors]") {
  if (!test::device_runtime()) return;
  const test::PlantedKernelDir dir("terms_d.cl", "static inline real D_ggx(",
                                   "static inline real D_ggx(this is not C ");
  Runtime rt = dir.runtime();
  try {
    run_agree(rt, test::agree_options({}, 10));
    FAIL("the build should have failed");
  } catch (const Error& e) {
    std::string msg = e.what();
    CHECK(msg.find("kernel build failed") != std::string::npos);
    CHECK(msg.find("build log") != std::string::npos);
    CHECK(msg.find("terms_d.cl") != std::string::npos);
  }
}

TEST_CASE("mfv agree covers the anisotropic terms: kernel and reference on identical inputs",
          "[device][aniso][agree]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  AgreeOptions opt = test::agree_options({"aniso_"}, 20000);
  opt.seed = 99;
  AgreeReport rep = run_agree(*rt, opt);
  CHECK(rep.results.size() == 4 + 2 * 4);  // 2 D, 2 G1, 2 matched pairs x 4 F
  test::check_every_case_passes(rep);
}
