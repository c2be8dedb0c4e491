// The furnace truth computed beside the run (FurnaceTruthAhead,
// checks/furnace_truth.hpp, issue 30): the background thread stores the
// truths under the key attach_furnace_truth would use, attach_furnace_truth
// then sets the same bits as the truth computed alone, the thread's error
// comes out of attach_furnace_truth, and the destructor stops a thread that
// was never joined without storing half its values.
#include "catalog/catalog.hpp"
#include "checks/furnace_truth.hpp"
#include "checks/integrate.hpp"
#include "checks/suite.hpp"
#include "reference/brdf.hpp"
#include "runtime/program_cache.hpp"
#include "scoped_env.hpp"
#include "test_files.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <thread>
#include <vector>

using namespace mfv;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The default furnace plan of `model` (empty: every model's).
std::vector<Plan> furnace_plans(const std::string& model) {
  SuiteOptions o;
  if (!model.empty()) o.models = {model};
  o.checks = {"furnace"};
  std::vector<Plan> out;
  for (Plan& p : make_plans(o))
    if (p.check == "furnace") out.push_back(std::move(p));
  return out;
}

// The specs of the points that take a truth, in order (attach_furnace_truth's list).
std::vector<IntegralSpec> truth_specs(const Plan& p) {
  std::vector<IntegralSpec> out;
  for (size_t i = 0; i < p.specs.size(); ++i)
    if (p.points[i].expect == Expect::Hold && !(p.specs[i].pd2 > 0) && p.specs[i].phi_o == 0)
      out.push_back(p.specs[i]);
  return out;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

TEST_CASE("The furnace truth computed beside the run is stored under the same keys and gives the same bits",
          "[furnace][truth][ahead]") {
  const test::Scratch scratch("mfv_truth_ahead");
  const test::ScopedEnv where("MFV_CACHE_DIR", scratch.dir.c_str()), on("MFV_TRUTH_CACHE", "1");
  std::vector<Plan> plans = furnace_plans("ggx/smith_ggx_correlated");
  REQUIRE(!plans.empty());
  std::vector<std::vector<KnownValue>> alone;  // the synchronous path's values, plan by plan
  std::vector<std::string> entries;
  size_t n = 0;
  for (const Plan& p : plans) {
    const std::vector<IntegralSpec> specs = truth_specs(p);
    n += specs.size();
    alone.push_back(albedos_by_quadrature(specs, 2));
    if (!specs.empty()) entries.push_back(ProgramCache(truth_cache_dir()).path(truth_cache_key(specs)));
  }
  REQUIRE(n == 384);
  {
    const FurnaceTruthAhead ahead(plans);
    // the thread stores the entries by itself, before anything joins it
    const auto t0 = std::chrono::steady_clock::now();
    auto all_stored = [&] {
      for (const std::string& e : entries)
        if (!std::filesystem::exists(e)) return false;
      return true;
    };
    while (!all_stored() && seconds_since(t0) < 120) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    REQUIRE(all_stored());
    for (Plan& p : plans) attach_furnace_truth(p);
  }
  for (size_t q = 0; q < plans.size(); ++q) {
    size_t k = 0;
    for (size_t i = 0; i < plans[q].specs.size(); ++i) {
      const PointResult& p = plans[q].points[i];
      if (!(p.expect == Expect::Hold && !(plans[q].specs[i].pd2 > 0) && plans[q].specs[i].phi_o == 0)) continue;
      INFO("plan " << q << " point " << i << ": " << p.known_value << " +- " << p.known_error << ", alone "
                   << alone[q][k].value);
      CHECK(p.known);
      CHECK(same_bits(p.known_value, alone[q][k].value));
      CHECK(same_bits(p.known_error, alone[q][k].error));
      ++k;
    }
    CHECK(k == alone[q].size());
  }
}

namespace {
double d_throws(double, double) { throw Error("planted: the reference D throws"); }
double d_cs_throws(double, double, double) { throw Error("planted: the reference D throws"); }
}  // namespace

TEST_CASE("The furnace truth's background error comes out of attach_furnace_truth, and an unjoined thread stops",
          "[furnace][truth][ahead][planted]") {
  const test::Scratch scratch("mfv_truth_ahead_error");
  const test::ScopedEnv where("MFV_CACHE_DIR", scratch.dir.c_str()), on("MFV_TRUTH_CACHE", "1");
  SECTION("a throwing reference term") {
    // another model than the first test's: a process knows the truths it computed
    const Term& beckmann = find_term("beckmann");
    Term planted = beckmann;
    planted.ref_d = d_throws;
    planted.ref_d_cs = d_cs_throws;
    struct Plant {
      const Term* original;
      ~Plant() { plant_reference_term(original, nullptr); }
    } const plant{&beckmann};
    plant_reference_term(&beckmann, &planted);
    std::vector<Plan> plans = furnace_plans("beckmann/smith_beckmann");
    REQUIRE(!plans.empty());
    {
      const FurnaceTruthAhead ahead(plans);
      CHECK_THROWS_WITH(attach_furnace_truth(plans[0]), "planted: the reference D throws");
    }
    {
      const FurnaceTruthAhead never_joined(plans);  // its error dies with it
    }
  }
  SECTION("the default run's truths, never joined") {
    const std::vector<Plan> plans = furnace_plans("");
    size_t n = 0;
    for (const Plan& p : plans) n += truth_specs(p).size();
    REQUIRE(n > 15000);  // ~3.1 s of one core
    const auto t0 = std::chrono::steady_clock::now();
    {
      const FurnaceTruthAhead ahead(plans);
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    const double secs = seconds_since(t0);
    INFO("stopped after " << secs << " s");
    CHECK(secs < 3);  // a view takes ~0.1 s of one core
    // nothing stored: the values were incomplete
    const std::filesystem::path dir = scratch.dir / "furnace-truth";
    const bool stored = std::filesystem::exists(dir) && !std::filesystem::is_empty(dir);
    CHECK_FALSE(stored);
  }
}
