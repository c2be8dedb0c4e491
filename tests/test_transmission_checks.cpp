// The transmission kinds of mfv run (issue 29, through the registry of
// issue 27): every correct rough dielectric BSDF passes bsdf_furnace and
// transmission_masking and each known-bad entry they must catch fails
// (xfail) on seeds 1, 2 and 3; a named plant fails each kind on its physics
// alone (no same-sample reference comparison).
#include "checks/suite.hpp"
#include "device_fixture.hpp"
#include "plants.hpp"
#include "suite_verdicts.hpp"

#include <catch2/catch.hpp>

using namespace mfv;

namespace {

// The GGX entries (two correct, the five known-bad ones) at mfv run's defaults.
SuiteOptions ggx_bsdfs(const char* check, uint64_t seed) {
  SuiteOptions opt;
  opt.models = {"walter_ggx"};
  opt.checks = {check};
  opt.seed = seed;
  return opt;
}

// The plant makes `check` FAIL on walter_ggx_correlated and the gate fail,
// without the same-sample reference comparison (the physics alone).
void check_plant_fails(const test::Plant& plant, const char* check) {
  CAPTURE(plant.name);
  SuiteOptions opt = ggx_bsdfs(check, 1);
  opt.models = {"walter_ggx_correlated"};
  opt.reference_samples = 0;
  test::check_planted_fails(plant.file, plant.from, plant.to, opt, check, "walter_ggx_correlated");
}

}  // namespace

TEST_CASE("bsdf_furnace passes the correct GGX BSDFs and fails each known-bad entry on seeds 1, 2 and 3",
          "[device][suite][transmission]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  for (uint64_t seed : {1, 2, 3}) {
    CAPTURE(seed);
    const SuiteReport rep = run_suite(*rt, ggx_bsdfs("bsdf_furnace", seed));
    for (const char* ok : {"walter_ggx_separable", "walter_ggx_correlated"})
      CHECK(test::verdict_of(rep, "bsdf_furnace", ok) == Verdict::Pass);
    for (const char* bad : {"walter_ggx_f_at_n", "walter_ggx_no_eta2", "walter_ggx_jacobian_sum",
                            "walter_ggx_same_side", "walter_ggx_beckmann_g1"})
      CHECK(test::verdict_of(rep, "bsdf_furnace", bad) == Verdict::XFail);
    CHECK(rep.gate_ok());
  }
}

TEST_CASE("A BTDF with eta_o in place of eta_o^2 fails bsdf_furnace on its physics", "[device][suite][transmission][plant]") {
  if (!test::device_runtime()) return;
  check_plant_fails(test::kBtdfEtaNotSquared, "bsdf_furnace");
}

TEST_CASE("transmission_masking passes the GGX BSDFs with GGX's G1 and fails the one with Beckmann's on seeds 1, 2 and 3",
          "[device][suite][transmission]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  for (uint64_t seed : {1, 2, 3}) {
    CAPTURE(seed);
    const SuiteReport rep = run_suite(*rt, ggx_bsdfs("transmission_masking", seed));
    for (const char* ok : {"walter_ggx_separable", "walter_ggx_correlated", "walter_ggx_f_at_n", "walter_ggx_no_eta2",
                           "walter_ggx_jacobian_sum", "walter_ggx_same_side"})
      CHECK(test::verdict_of(rep, "transmission_masking", ok) == Verdict::Pass);
    CHECK(test::verdict_of(rep, "transmission_masking", "walter_ggx_beckmann_g1") == Verdict::XFail);
    CHECK(rep.gate_ok());
  }
}

TEST_CASE("smith_ggx's G1 with half its Lambda fails transmission_masking", "[device][suite][transmission][plant]") {
  if (!test::device_runtime()) return;
  check_plant_fails(test::kGgxG1HalfLambda, "transmission_masking");
}

TEST_CASE("bsdf_reciprocity passes the GGX BSDFs symmetric in i and o and fails the three that are not on seeds 1, 2 and 3",
          "[device][suite][transmission]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  for (uint64_t seed : {1, 2, 3}) {
    CAPTURE(seed);
    const SuiteReport rep = run_suite(*rt, ggx_bsdfs("bsdf_reciprocity", seed));
    for (const char* ok :
         {"walter_ggx_separable", "walter_ggx_correlated", "walter_ggx_same_side", "walter_ggx_beckmann_g1"})
      CHECK(test::verdict_of(rep, "bsdf_reciprocity", ok) == Verdict::Pass);
    for (const char* bad : {"walter_ggx_f_at_n", "walter_ggx_no_eta2", "walter_ggx_jacobian_sum"})
      CHECK(test::verdict_of(rep, "bsdf_reciprocity", bad) == Verdict::XFail);
    CHECK(rep.gate_ok());
  }
}

TEST_CASE("A BTDF kernel with eta_o in place of eta_o^2 fails bsdf_reciprocity, its double twin does not",
          "[device][suite][transmission][plant]") {
  if (!test::device_runtime()) return;
  SuiteOptions opt = ggx_bsdfs("bsdf_reciprocity", 1);
  opt.models = {"walter_ggx_correlated"};
  const test::Plant& plant = test::kBtdfEtaNotSquared;
  const SuiteReport bad = test::planted_suite(plant.file, plant.from, plant.to, opt);
  CHECK(test::verdict_of(bad, "bsdf_reciprocity", "walter_ggx_correlated") == Verdict::Fail);
  CHECK_FALSE(bad.gate_ok());
  for (const PointResult& p : bad.points) {
    CAPTURE(p.detail);
    CHECK((p.params.at("twin") == 1.0) == (p.estimate == 0));  // the kernel's points fail, the twin's pass
  }
}
