// mfv run --profile deep (over 10^6 integrals, denser grids) and --dry-run
// (the plan's size and time from a calibration launch): docs/scale.md.
#include "checks/profile.hpp"
#include "checks/shard.hpp"
#include "device_fixture.hpp"
#include "run_mfv.hpp"

#include <catch2/catch.hpp>

#include <set>

using namespace mfv;
using namespace mfv::test;

TEST_CASE("densified grids keep every point and put density - 1 more between neighbours", "[profile]") {
  const std::vector<double> v = {0.01, 0.1, 1.0};
  CHECK(densify(v, 1) == v);
  const std::vector<double> d = densify(v, 2);
  REQUIRE(d.size() == 5);
  CHECK(d[0] == 0.01);
  CHECK(d[1] == Approx(std::sqrt(0.001)));  // geometric between positive widths
  CHECK(d[4] == 1.0);
  const std::vector<double> z = densify({0.0, 2.0}, 2);  // from 0: arithmetic
  CHECK(z == std::vector<double>{0.0, 1.0, 2.0});
  const Term& schlick = find_term("schlick");
  const auto pts = densify_points(schlick, 3);
  CHECK(pts.size() == 3 * (schlick.check_points.size() - 1) + 1);
  for (auto& p : pts) CHECK(!p.label.empty());
  CHECK_THROWS_AS(profile_density("huge"), Error);
}

TEST_CASE("mfv run --profile deep plans over a million integrals, and the default profile is the default plan", "[profile]") {
  SuiteOptions opt;
  const size_t def = plan_integrals(make_suite_plans(opt));
  opt.density = profile_density("default");
  CHECK(plan_integrals(make_suite_plans(opt)) == def);
  opt.density = profile_density("deep");
  const SuitePlans deep = make_suite_plans(opt);
  CHECK(plan_integrals(deep) >= 1000000);
  // every check of the default run, with more integrals each
  std::set<std::string> checks;
  for (auto& p : deep.plans) checks.insert(p.check);
  for (const char* c : {"d_norm", "masking", "furnace", "energy", "energy_diffuse", "closed_form"}) CHECK(checks.count(c));
}

TEST_CASE("mfv run --dry-run prints integrals, samples and the estimated time on this device, and runs nothing",
          "[profile][device]") {
  if (!device_runtime()) return;
  auto r = run_mfv("--quiet run --dry-run --check masking --model ggx/smith_ggx --out /nonexistent/never");
  INFO(r.out);
  CHECK(r.code == 0);
  CHECK(r.out.find("integrals, ") != std::string::npos);
  CHECK(r.out.find(" samples, estimated time on this device: ") != std::string::npos);
  auto bad = run_mfv("run --profile huge");
  CHECK(bad.code == 2);
  CHECK(bad.out.rfind("mfv: error: unknown --profile 'huge'", 0) == 0);
}
