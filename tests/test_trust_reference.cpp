// Issue 16, the reference half: the same-sample comparison with the double
// twin and its derived bound fails the model x check of every formula bug a
// renderer makes that the statistics cannot see (planted in the kernel, or in
// the reference through plant_reference_term), at default samples and seed;
// near-mirror materials pass on several seeds; a failed gate names every
// reason (the stability half: test_trust_stability.cpp).
#include "catalog/catalog.hpp"
#include "checks/integrate.hpp"
#include "checks/suite.hpp"
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "plants.hpp"
#include "reference/reference.hpp"
#include "scene/scene.hpp"
#include "scene/scene_checks.hpp"
#include "suite_verdicts.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

using namespace mfv;

namespace {

// The default options of mfv run (seed 1, scale 1, 256 reference samples),
// with only the models a test needs.
SuiteOptions default_for(std::vector<std::string> models) {
  SuiteOptions o;
  o.models = std::move(models);
  return o;
}

bool any_line_has(const std::vector<std::string>& lines, const std::string& what) {
  for (auto& l : lines)
    if (l.find(what) != std::string::npos) return true;
  return false;
}

// A kernel plant that fails the default gate through the reference comparison
// of `check` x `model`, with the reason on its own line.
void expect_reference_failure(const std::string& file, const std::string& from, const std::string& to,
                              const std::string& filter, const std::string& check, const std::string& model) {
  if (!test::fp64_runtime("the comparison with the double twin")) return;
  const test::PlantedKernelDir dir(file, from, to);
  Runtime planted = dir.runtime();
  SuiteReport rep = run_suite(planted, default_for({filter}));
  CHECK(test::verdict_of(rep, check, model) == Verdict::Fail);
  CHECK_FALSE(rep.gate_ok());
  const auto reasons = rep.gate_failures();
  CAPTURE(reasons.size(), reasons.empty() ? "" : reasons.front());
  CHECK(any_line_has(reasons, "FAIL " + check + " " + model + ": same-sample reference"));
  CHECK(any_line_has(reasons, "derived bound"));
}

}  // namespace

TEST_CASE("The double twin agrees with the reference within its derived bound on correct models and bounds rounding",
          "[device][suite][reference]") {
  Runtime* rt = test::device_runtime();
  if (!rt || !rt->device().fp64) return;
  SuiteOptions opt = default_for({"ggx/smith_ggx_correlated/conductor", "gltf[chrome", "ward_004["});
  opt.reference_every = 1;  // every integral of these models
  SuiteReport rep = run_suite(*rt, opt);
  CAPTURE(rep.reference_worst, rep.reference_worst_at);
  CHECK(rep.reference_twin);
  CHECK(rep.reference_ok());
  CHECK(rep.gate_ok());
  size_t compared = 0, with_rounding = 0;
  for (auto& p : rep.points) {
    compared += p.reference_compared;
    with_rounding += p.reference_compared && p.rounding_bound > 0;
    CHECK_FALSE(p.reference_failed);
  }
  CHECK(compared == rep.reference_compared);
  CHECK(with_rounding > compared / 2);  // float rounding shows on most integrals and is bounded
}

TEST_CASE("Planted: a height-correlated G built as the separable one fails the default gate",
          "[device][suite][planted]") {
  expect_reference_failure("terms_g.cl", "real g = R(1.0) / (R(1.0) + Lambda_ggx(NoL, alpha) + Lambda_ggx(NoV, alpha));",
                           "real g = R(1.0) / ((R(1.0) + Lambda_ggx(NoL, alpha)) * (R(1.0) + Lambda_ggx(NoV, alpha)));",
                           "ggx/smith_ggx_correlated/schlick", "energy", "ggx/smith_ggx_correlated/schlick");
}

TEST_CASE("Planted: Schlick with (1-c)^4 fails the default gate", "[device][suite][planted]") {
  expect_reference_failure("terms_f.cl", "return f0 + (R(1.0) - f0) * (m2 * m2 * m);",
                           "return f0 + (R(1.0) - f0) * (m2 * m2);", "ggx/smith_ggx/schlick", "energy",
                           "ggx/smith_ggx/schlick");
}

TEST_CASE("Planted: a conductor with the sign of k^2 flipped fails the default gate", "[device][suite][planted]") {
  expect_reference_failure("terms_f.cl", "real e = (n - R(1.0)) * (n + R(1.0)) - k * k;",
                           "real e = (n - R(1.0)) * (n + R(1.0)) + k * k;", "ggx/smith_ggx/conductor", "energy",
                           "ggx/smith_ggx/conductor");
}

TEST_CASE("Planted: the glTF metal's Fresnel on the dielectric f0 fails the default gate", "[device][suite][planted]") {
  expect_reference_failure("model_gltf.cl", "real metal = (base + (R(1.0) - base) * fw) * spec;",
                           "real metal = (f0 + (R(1.0) - f0) * fw) * spec;", "gltf[chrome,r=0.2]", "energy",
                           "gltf[chrome,r=0.2]");
}

TEST_CASE("Planted: Ward with alpha_t and alpha_b swapped fails the default gate", "[device][suite][planted]") {
  expect_reference_failure(
      "models.cl",
      "real f = p[0] * ward_exp(h, p[1], p[2]) * (R(0.25) * MFV_INV_PI) / p[1] / p[2] / (sqrt(l.z) * sqrt(v.z));",
      "real f = p[0] * ward_exp(h, p[2], p[1]) * (R(0.25) * MFV_INV_PI) / p[1] / p[2] / (sqrt(l.z) * sqrt(v.z));",
      "ward_004[", "energy", "ward_004[at=0.3,ab=0.1]");
}

namespace {
double d_ggx_times_1002(double NoH, double alpha) { return 1.002 * ref::D_ggx(NoH, alpha); }
double d_ggx_cs_times_1002(double cos2, double sin2, double alpha) { return 1.002 * ref::D_ggx_cs(cos2, sin2, alpha); }
}  // namespace

TEST_CASE("Planted: the double reference's GGX D scaled by 1.002 fails the default gate", "[device][suite][planted]") {
  Runtime* rt = test::device_runtime();
  if (!rt || !rt->device().fp64) return;
  const Term& ggx = find_term("ggx");
  Term planted = ggx;
  planted.ref_d = d_ggx_times_1002;
  planted.ref_d_cs = d_ggx_cs_times_1002;
  plant_reference_term(&ggx, &planted);
  SuiteReport rep = run_suite(*rt, default_for({"ggx/smith_ggx/schlick"}));
  plant_reference_term(&ggx, nullptr);
  CHECK(test::verdict_of(rep, "energy", "ggx/smith_ggx/schlick") == Verdict::Fail);
  CHECK_FALSE(rep.gate_ok());
  CHECK(any_line_has(rep.gate_failures(), "same-sample reference"));
}

TEST_CASE("Near-mirror and grazing materials pass the gate on several seeds", "[device][suite][scene][nearmirror]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  const test::Scratch s("mfv_near_mirror");
  const std::string path = s.file("near_mirror.json", R"({"materials": [
    {"name": "metal r0", "model": "gltf", "baseColor": [0.9, 0.6, 0.3], "metallic": 1.0, "roughness": 0.0},
    {"name": "metal r0.01", "model": "gltf", "baseColor": 1.0, "metallic": 1.0, "roughness": 0.01},
    {"name": "metal r0.02", "model": "gltf", "baseColor": 0.8, "metallic": 1.0, "roughness": 0.02},
    {"name": "plastic r0", "model": "gltf", "baseColor": 0.5, "metallic": 0.0, "roughness": 0.0},
    {"name": "plastic r0.01", "model": "gltf", "baseColor": 0.5, "metallic": 0.0, "roughness": 0.01},
    {"name": "plastic r0.02", "model": "gltf", "baseColor": 0.5, "metallic": 0.0, "roughness": 0.02},
    {"name": "ggx 1e-4", "d": "ggx", "g": "smith_ggx_correlated", "f": "conductor", "alpha": 1e-4, "params": {"n": 0.43, "k": 2.45}},
    {"name": "beckmann 1e-4", "d": "beckmann", "g": "smith_beckmann", "f": "dielectric", "alpha": 1e-4, "params": {"eta": 1.5}}
  ]})");
  Scene scene = load_scene(path);
  for (uint64_t seed : {1, 2, 3}) {
    SuiteOptions opt;
    opt.seed = seed;
    opt.reference_every = 1;  // as mfv run --scene
    SceneRun run = run_scene(*rt, scene, opt);
    CAPTURE(seed, run.rep.reference_worst, run.rep.reference_worst_at);
    for (auto& line : run.rep.gate_failures()) {
      CAPTURE(line);
      CHECK(false);
    }
    CHECK(run.rep.gate_ok());
  }
}

// The bound's lobe term (checks/reference_compare.cpp: 2^-46 of the scale /
// (mu w), derived for the reference's second rounding of the half vector)
// is largest at the near-mirror material's grazing views: a formula error of
// 2.3e-6 still fails there.
TEST_CASE("Planted: GGX's D with pi rounded to 3.1416 fails a near-mirror material at its most grazing views",
          "[device][suite][scene][nearmirror][planted]") {
  if (!test::fp64_runtime("the comparison with the double twin")) return;
  const test::Scratch s("mfv_near_mirror_planted");
  const std::string path = s.file("ggx_1e-4.json", R"({"materials": [
    {"name": "ggx 1e-4", "d": "ggx", "g": "smith_ggx_correlated", "f": "conductor", "alpha": 1e-4, "params": {"n": 0.43, "k": 2.45}}
  ]})");
  Scene scene = load_scene(path);
  const test::PlantedKernelDir dir = test::planted(test::kGgxPiRounded);
  Runtime planted = dir.runtime();
  SuiteOptions opt;
  opt.reference_every = 1;  // as mfv run --scene
  SceneRun run = run_scene(planted, scene, opt);
  CHECK_FALSE(run.rep.gate_ok());
  const auto reasons = run.rep.gate_failures();
  for (auto& line : reasons) UNSCOPED_INFO(line);
  const std::string at = "FAIL furnace ggx/smith_ggx_correlated/none pD=0.0001 pG=0.0001: same-sample reference at ";
  for (const char* view : {"alpha=0.0001 cos_o=0.0001:", "alpha=0.0001 cos_o=0.000134596:"}) {
    CAPTURE(view);
    CHECK(any_line_has(reasons, at + view));
  }
}
