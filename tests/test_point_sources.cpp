// The point sources crossed with the registry in one function
// (cross_sources, docs/adding-a-check.md step 6): every source builds points
// for every kind the registry names for it, from the kind's shape and
// fields; a source named for a kind it cannot take fails with a message
// naming both; the plans come in registry order, each under its kind's name.
#include "checks/registry.hpp"
#include "checks/suite.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

using namespace mfv;

namespace {

// The kinds mfv run crosses with its sources: integrals and reciprocity pairs.
bool crossed(const CheckKind& k) {
  return (k.runner == Runner::Integral || k.runner == Runner::Pairs) && k.in_run;
}

size_t registry_index(const std::string& check) {
  const auto& kinds = check_kinds();
  for (size_t i = 0; i < kinds.size(); ++i)
    if (check == kinds[i].check) return i;
  return kinds.size();
}

}  // namespace

TEST_CASE("Every source of mfv run builds points for each kind the registry names for it", "[suite][checks][sources]") {
  SuiteOptions opt;
  opt.models = {"ggx"};  // a few models of each source (the sheen lobes' quadrature left out: fast)
  for (const PointSource& src : suite_sources(opt))
    for (const CheckKind& k : check_kinds()) {
      if (!crossed(k) || !(k.sources & src.source)) continue;
      INFO(src.name << " x " << k.check);
      std::vector<Plan> plans;
      CHECK(src.add(k, plans));
      for (const Plan& p : plans) {
        CHECK(p.check == k.check);
        for (const PointResult& pt : p.points) CHECK(pt.check == k.check);
      }
    }
}

TEST_CASE("A source the registry names for a kind of a shape it has no points of fails naming both",
          "[suite][checks][sources]") {
  PointSource planted{kSourceGrid, "a planted source", [](const CheckKind&, std::vector<Plan>&) { return false; }};
  try {
    cross_sources({planted}, [](const CheckKind& k) { return std::string(k.check) == "masking"; });
    FAIL("no error");
  } catch (const Error& e) {
    CHECK_THAT(e.what(), Catch::Contains("the registry says a planted source takes check kind 'masking'"));
  }
  // a source the registry does not name for the kind is never asked
  PointSource other{kSourceUser, "unasked", [](const CheckKind&, std::vector<Plan>&) { return false; }};
  CHECK_NOTHROW(cross_sources({other}, [](const CheckKind& k) { return std::string(k.check) == "closed_form"; }));
}

TEST_CASE("mfv run's plans come kind by kind in registry order, each from the kind's sources",
          "[suite][checks][sources]") {
  SuiteOptions opt;
  opt.models = {"beckmann", "lambert"};
  const std::vector<Plan> plans = make_plans(opt);
  REQUIRE(!plans.empty());
  for (size_t i = 1; i < plans.size(); ++i) CHECK(registry_index(plans[i - 1].check) <= registry_index(plans[i].check));
  for (const Plan& p : plans) {
    const CheckKind& k = check_kind(p.check);
    CHECK(crossed(k));
    // every integral of a plan integrates its kind's integrand, but where a
    // source states otherwise (docs/adding-a-check.md, What remains: the
    // anisotropic furnace's defensive mixture; whole models' albedo)
    for (const IntegralSpec& s : p.specs)
      if (s.check != static_cast<int32_t>(k.kind))
        CHECK((s.check == static_cast<int32_t>(IntegralKind::Albedo) && shape_of(k) != Shape::DNorm &&
               shape_of(k) != Shape::Masking));
  }
  // the pairs kind: one plan of the grid's and the whole models' batches
  for (const CheckKind& k : check_kinds())
    if (shape_of(k) == Shape::Pairs) {
      const Plan r = reciprocity_plan(k, opt);
      CHECK(r.check == k.check);
      CHECK(std::any_of(r.points.begin(), r.points.end(), [](const PointResult& p) { return p.d != nullptr; }));
      CHECK(std::any_of(r.points.begin(), r.points.end(), [](const PointResult& p) { return !p.model.empty(); }));
    }
}
