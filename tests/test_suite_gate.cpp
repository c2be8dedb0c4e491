// One gate (issue 27): mfv run's pointwise kinds, agree and stability, give
// verdicts in the same report as the integrals, so that a defect only
// pointwise checks can see fails mfv run, not only mfv agree or stability.
#include "checks/suite.hpp"
#include "device_fixture.hpp"
#include "plants.hpp"
#include "suite_verdicts.hpp"

#include <catch2/catch.hpp>

using namespace mfv;

TEST_CASE("mfv run's agree and stability passes give one verdict per case in the report", "[device][suite][gate]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  SuiteOptions opt;  // mfv run's defaults, the cases of GGX
  opt.models = {"ggx"};
  opt.checks = {"agree", "stability"};
  const SuiteReport rep = run_suite(*rt, opt);
  CHECK(test::verdict_of(rep, "agree", "D ggx") == Verdict::Pass);
  CHECK(test::verdict_of(rep, "stability", "D ggx") == Verdict::Pass);
  CHECK(rep.gate_ok());
}

TEST_CASE("A GGX D without its horizon test fails mfv run at its default settings", "[device][suite][gate][plant]") {
  if (!test::device_runtime()) return;
  const test::Plant& plant = test::kGgxNoHorizon;
  CAPTURE(plant.name);
  const test::PlantedKernelDir dir = test::planted(plant);
  Runtime planted = dir.runtime();
  // mfv run's defaults (scale 1, the pointwise kinds' budgets) for the GGX
  // models, with d_norm as the integral beside them (every integral kind
  // misses the defect: they never sample n.h <= 0; the full default run's
  // exit code with this plant is measured in docs/adding-a-check.md)
  SuiteOptions opt;
  opt.models = {"ggx"};
  opt.checks = {"d_norm", "agree", "stability"};
  const SuiteReport rep = run_suite(planted, opt);
  // the integrals never sample n.h <= 0: d_norm of the planted D still holds
  CHECK(test::verdict_of(rep, "d_norm", "ggx") == Verdict::Pass);
  // the pointwise kinds see it, in the same report and gate
  CHECK(test::verdict_of(rep, "agree", "D ggx") == Verdict::Fail);
  CHECK(test::verdict_of(rep, "stability", "D ggx") == Verdict::Fail);
  CHECK_FALSE(rep.gate_ok());
}
