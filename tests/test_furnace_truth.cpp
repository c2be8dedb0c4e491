// The furnace's quadrature truth (checks/furnace_truth.cpp): the batched path
// that shares each view's nodes, shading and term values must give the bits
// of one integral at a time, on any number of threads; its error estimate
// covers its error; the copy kept on disk is read back, or recomputed where
// it does not check out.
#include "catalog/catalog.hpp"
#include "checks/furnace_truth.hpp"
#include "checks/integrate.hpp"
#include "checks/suite.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/program_cache.hpp"
#include "scoped_env.hpp"
#include "test_files.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <vector>

using namespace mfv;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every `every`-th integral of the default run's furnace plans (isotropic and
// anisotropic: the latter take the one-at-a-time path).
std::vector<IntegralSpec> furnace_specs(size_t every) {
  std::vector<IntegralSpec> out;
  size_t k = 0;
  for (const Plan& p : make_plans(SuiteOptions{}))
    if (p.check == "furnace")
      for (const IntegralSpec& s : p.specs)
        if (k++ % every == 0) out.push_back(s);
  return out;
}

// Integrals at one view that differ in one parameter each, of D, G, F or kd:
// a term-value cache keyed on less than (term, its parameters) would mix them.
std::vector<IntegralSpec> variants() {
  IntegralSpec s;
  s.check = int32_t(IntegralKind::Albedo);
  s.d = term_index(find_term("ggx"));
  s.g = term_index(find_term("smith_ggx_correlated"));
  s.f = term_index(find_term("schlick"));
  s.pd = s.pg = 0.3f;
  s.f0 = 0.04f;
  s.cos_o = 0.5f;
  std::vector<IntegralSpec> out(6, s);
  out[1].pd = 0.5f;
  out[2].pg = 0.5f;
  out[3].f0 = 0.9f;
  out[4].kd = 0.2f;
  out[5].g = term_index(find_term("smith_ggx"));
  return out;
}

void require_same(const std::vector<IntegralSpec>& specs, const std::vector<KnownValue>& got) {
  REQUIRE(got.size() == specs.size());
  for (size_t i = 0; i < specs.size(); ++i) {
    const KnownValue one = albedo_by_quadrature(specs[i]);
    INFO("integral " << i << ": batched " << got[i].value << " +- " << got[i].error << ", alone " << one.value);
    CHECK(same_bits(got[i].value, one.value));
    CHECK(same_bits(got[i].error, one.error));
  }
}

}  // namespace

TEST_CASE("The furnace truth's shared-node quadrature gives the bits of one integral at a time", "[furnace][truth]") {
  const std::vector<IntegralSpec> specs = furnace_specs(29);
  REQUIRE(specs.size() > 400);
  const std::vector<KnownValue> one = albedos_by_quadrature(specs, 1), three = albedos_by_quadrature(specs, 3);
  for (size_t i = 0; i < specs.size(); ++i) {
    CHECK(same_bits(one[i].value, three[i].value));
    CHECK(same_bits(one[i].error, three[i].error));
  }
  require_same(specs, one);
}

TEST_CASE("The furnace truth keeps integrals apart that differ in one term parameter", "[furnace][truth][planted]") {
  const std::vector<IntegralSpec> specs = variants();
  const std::vector<KnownValue> got = albedos_by_quadrature(specs, 2);
  require_same(specs, got);
  for (size_t i = 1; i < specs.size(); ++i) CHECK(got[i].value != got[0].value);  // each parameter moves it
}

namespace {

// The isotropic furnace integrals of one model at default settings.
std::vector<IntegralSpec> model_furnace_specs(const std::string& model) {
  SuiteOptions o;
  o.models = {model};
  o.checks = {"furnace"};
  std::vector<IntegralSpec> out;
  for (const Plan& p : make_plans(o))
    if (p.check == "furnace")
      for (size_t i = 0; i < p.specs.size(); ++i)
        if (p.points[i].expect == Expect::Hold && !(p.specs[i].pd2 > 0) && p.specs[i].phi_o == 0)
          out.push_back(p.specs[i]);
  return out;
}

// Mean error estimate and mean |value - much finer rule| over every `every`-th spec.
std::pair<double, double> mean_estimate_and_error(const std::vector<IntegralSpec>& specs, size_t every,
                                                  const RuleSet& rules) {
  const ProductRule much_finer{24, 4, 12, 1e-7};
  double est = 0, act = 0;
  size_t n = 0;
  for (size_t i = 0; i < specs.size(); i += every, ++n) {
    const KnownValue v = albedo_by_rules(specs[i], rules);
    est += v.error;
    act += std::fabs(v.value - albedo_by_rules(specs[i], {much_finer, much_finer, much_finer}).value);
  }
  return {est / n, act / n};
}

}  // namespace

// The pooled test (suite_judge.cpp) adds the mean of the points' error
// estimates to its bias bound against the mean deviation, to which the truth
// contributes mean(fine - exact), at most mean |fine - exact|: the mean
// estimate must cover that, measured against a much finer rule.
TEST_CASE("The furnace truth's error estimate covers its actual error in the pool's mean", "[furnace][truth][planted]") {
  const std::vector<IntegralSpec> specs = model_furnace_specs("ggx/smith_ggx_correlated");
  REQUIRE(specs.size() == 384);
  const auto [est, act] = mean_estimate_and_error(specs, 4, furnace_rules());
  INFO("mean estimate " << est << ", mean error " << act);
  CHECK(est >= act);
  CHECK(est < 1e-5);  // the tightened rules: 3.4e-6 over all 384 (the former pair 3.9e-5)
  // planted: a coarse rule equal to the fine one estimates nothing and is caught
  const RuleSet& r = furnace_rules();
  const auto [est0, act0] = mean_estimate_and_error(specs, 16, {r.coarser, r.coarser, r.coarser});
  CHECK(est0 == 0);
  CHECK(act0 > 0);
}

namespace {

std::vector<unsigned char> bytes_of(const std::vector<KnownValue>& v) {
  const auto* p = reinterpret_cast<const unsigned char*>(v.data());
  return {p, p + v.size() * sizeof(KnownValue)};
}

void require_bits(const std::vector<KnownValue>& got, const std::vector<KnownValue>& want) {
  REQUIRE(got.size() == want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    INFO("integral " << i << ": " << got[i].value << " +- " << got[i].error << ", computed " << want[i].value);
    CHECK(same_bits(got[i].value, want[i].value));
    CHECK(same_bits(got[i].error, want[i].error));
  }
}

}  // namespace

// The truths kept on disk across runs (stored_albedos_by_quadrature): a
// second run reads them (shown by an entry planted with other values, which
// comes back), and a truncated or corrupt entry is recomputed and replaced.
TEST_CASE("The furnace truth comes from disk on a second run, and a truncated or corrupt entry is recomputed",
          "[furnace][truth][planted]") {
  namespace fs = std::filesystem;
  const test::Scratch scratch("mfv_truth_cache");
  const std::string dir = scratch / "furnace-truth";
  std::vector<IntegralSpec> specs;
  for (const IntegralSpec& s : model_furnace_specs("ggx/smith_ggx_correlated"))
    if (specs.size() < 48) specs.push_back(s);
  REQUIRE(specs.size() == 48);
  const std::vector<KnownValue> fresh = albedos_by_quadrature(specs, 2);
  require_bits(stored_albedos_by_quadrature(specs, 2, dir), fresh);  // computed, and stored
  const std::string key = truth_cache_key(specs);
  REQUIRE(key.size() == 64);
  const std::string entry = ProgramCache(dir).path(key);
  REQUIRE(fs::exists(entry));
  CHECK(ProgramCache(dir).load(key) == bytes_of(fresh));

  // planted: an entry that checks out but holds other values is what a second run reads
  std::vector<KnownValue> other = fresh;
  for (KnownValue& v : other) v.value += 1;
  ProgramCache(dir).store(key, bytes_of(other));
  require_bits(stored_albedos_by_quadrature(specs, 2, dir), other);

  ProgramCache(dir).store(key, bytes_of(fresh));
  const uintmax_t size = fs::file_size(entry);
  SECTION("one flipped bit in the values") {
    std::fstream f(entry, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(std::streamoff(size - 5));
    const char c = char(f.get() ^ 0x10);
    f.seekp(std::streamoff(size - 5));
    f.put(c);
  }
  SECTION("truncated") { fs::resize_file(entry, size - sizeof(KnownValue)); }
  SECTION("empty") { fs::resize_file(entry, 0); }
  CHECK(!ProgramCache(dir).load(key));
  require_bits(stored_albedos_by_quadrature(specs, 2, dir), fresh);  // recomputed
  CHECK(ProgramCache(dir).load(key) == bytes_of(fresh));             // and replaced
}

TEST_CASE("The furnace truth's disk key holds every parameter, but not the stream", "[furnace][truth]") {
  const std::vector<IntegralSpec> specs = variants();
  std::set<std::string> keys;
  for (const IntegralSpec& s : specs) keys.insert(truth_cache_key({s}));
  CHECK(keys.size() == specs.size());
  IntegralSpec streamed = specs[0];
  streamed.stream = 7;
  streamed.stream_hi = 3;
  CHECK(truth_cache_key({streamed}) == truth_cache_key({specs[0]}));
  CHECK(truth_cache_key({specs[0], specs[1]}) != truth_cache_key({specs[1], specs[0]}));
  // a test's planted reference term must not read nor write the disk
  const Term& ggx = find_term("ggx");
  plant_reference_term(&ggx, &ggx);
  CHECK(truth_cache_key({specs[0]}).empty());
  plant_reference_term(&ggx, nullptr);
  CHECK(!truth_cache_key({specs[0]}).empty());
}

TEST_CASE("MFV_TRUTH_CACHE turns the furnace truth's disk cache off and on", "[furnace][truth]") {
  const test::ScopedEnv where("MFV_CACHE_DIR", "/tmp/mfv-x");
  {
    const test::ScopedEnv on("MFV_TRUTH_CACHE", nullptr);
    CHECK(truth_cache_dir() == "/tmp/mfv-x/furnace-truth");
  }
  {
    const test::ScopedEnv on("MFV_TRUTH_CACHE", "1");
    CHECK(truth_cache_dir() == "/tmp/mfv-x/furnace-truth");
  }
  {
    const test::ScopedEnv off("MFV_TRUTH_CACHE", "0");
    CHECK(truth_cache_dir().empty());
  }
  {
    const test::ScopedEnv bad("MFV_TRUTH_CACHE", "yes");
    CHECK_THROWS_AS(truth_cache_dir(), Error);
  }
}
