// Issue 16: the stability gate counts values outside their domain (a term
// marked stable that is non-zero below the horizon fails), and mfv agree
// sends half vectors below the horizon.
#include "agree_options.hpp"
#include "checks/agree.hpp"
#include "checks/stability.hpp"
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "stability_options.hpp"

#include <catch2/catch.hpp>

#include <string>

using namespace mfv;

namespace {
bool any_line_has(const std::vector<std::string>& lines, const std::string& what) {
  for (auto& l : lines)
    if (l.find(what) != std::string::npos) return true;
  return false;
}
}  // namespace

TEST_CASE("Planted: GGX D without its horizon test fails the stability gate and mfv agree",
          "[device][stability][agree][planted]") {
  if (!test::device_runtime()) return;
  const test::PlantedKernelDir dir("terms_d.cl",
                                   "(MFV_PI * a2 * k * k);\n  return NoH <= R(0.0) ? R(0.0) : d;",
                                   "(MFV_PI * a2 * k * k);\n  return d;");
  Runtime rt = dir.runtime();
  StabilityReport rep = run_stability(rt, test::one_term("D ggx"));
  CHECK_FALSE(rep.gate_pass());
  CHECK(any_line_has(rep.gate_failures, "outside the domain in region 'below_horizon'"));

  // 20000 samples: one record in eight below the horizon
  AgreeReport agree = run_agree(rt, test::agree_options({"D ggx"}, 20000));
  bool failed = false;
  for (auto& r : agree.results) failed = failed || (r.name == "D ggx" && !r.pass());
  CHECK(failed);
}

TEST_CASE("The stability gate passes the correct terms with the domain counted", "[device][stability]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  StabilityOptions sopt;
  sopt.combinations = false;
  sopt.models = false;
  StabilityReport rep = run_stability(*rt, sopt);
  for (auto& l : rep.gate_failures) {
    CAPTURE(l);
    CHECK(false);
  }
}
