// The cold first run (issue 30): PoCL compiles a kernel at its first launch
// with each work-group size (and grid class), so a run that launches one
// kernel over many sizes pays many compiles (docs/performance.md, "Cold
// start"). These tests run mfv with PoCL's kernel cache in an empty folder
// and read back what PoCL compiled: one work-group variant per kernel and
// one double-twin program for the run. They also check that the counted
// launches (runtime/work_group.hpp) give the values of whole launches.
#include "albedo_spec.hpp"
#include "checks/compile_ahead.hpp"
#include "device_fixture.hpp"
#include "run_mfv.hpp"
#include "runtime/integrator.hpp"
#include "runtime/work_group.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <set>

using namespace mfv;
namespace fs = std::filesystem;

namespace {

// PoCL's cache: PROGRAM_HASH (two levels) / KERNEL / VARIANT / KERNEL.so.
// Returns, per kernel name, how many work-group variants were compiled,
// summed over programs, and the number of programs.
struct Compiled {
  std::map<std::string, int> variants;
  std::map<std::string, int> programs_with;  // programs that compiled the kernel at least once
  int programs = 0;
};

Compiled read_pocl_cache(const fs::path& dir) {
  Compiled c;
  for (auto& a : fs::directory_iterator(dir)) {
    if (!a.is_directory()) continue;
    for (auto& prog : fs::directory_iterator(a.path())) {
      if (!prog.is_directory()) continue;
      bool any = false;
      for (auto& kernel : fs::directory_iterator(prog.path())) {
        if (!kernel.is_directory()) continue;
        const std::string name = kernel.path().filename().string();
        int n = 0;
        for (auto& variant : fs::directory_iterator(kernel.path()))
          if (fs::exists(variant.path() / (name + ".so"))) ++n;
        if (n == 0) continue;
        any = true;
        c.variants[name] += n;
        c.programs_with[name] += 1;
      }
      c.programs += any ? 1 : 0;
    }
  }
  return c;
}

}  // namespace

TEST_CASE("A cold mfv run compiles each kernel once: one work-group size per kernel and one double twin",
          "[device][cold]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  if (!test::is_pocl(*rt)) return test::skip("the compile count is read from PoCL's kernel cache");
  test::Scratch scratch("mfv_cold");
  const fs::path cache = scratch.dir / "pocl", out = scratch.dir / "out";
  fs::create_directories(cache);
  // d_norm and masking (sum_pairs, sum_values over many counts), furnace
  // (n = 80 points a replicate) and energy (n = 40) of the same pairs, and
  // the reference comparison (sample_values over each plan's subset, float
  // and double twin) in every plan
  const test::Run r = test::run_mfv(
      "--quiet run --check d_norm --check masking --check furnace --check energy --model ggx/smith_ggx_correlated "
      "--model beckmann/smith_beckmann --out " + out.string(),
      "POCL_CACHE_DIR=" + cache.string() + " POCL_KERNEL_CACHE=1");
  INFO(r.out);
  REQUIRE(r.code == 0);
  const Compiled c = read_pocl_cache(cache);
  REQUIRE(c.variants.count("sample_values") == 1);
  for (const auto& [name, n] : c.variants) {
    CAPTURE(name, c.programs_with.at(name));
    CHECK(n == c.programs_with.at(name));  // one work-group variant in each program that compiled it
  }
  // sample_values in two programs: the float integration program and the run's one double twin
  CHECK(c.programs_with.at("sample_values") == 2);
  CHECK(c.programs == 2);
}

TEST_CASE("sample_values launched in chunks of one work-group size gives each integral's values as alone",
          "[device][cold]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  // more values than one counted launch takes, and a count that is no multiple of the work-group size
  const uint32_t n = 251;
  std::vector<IntegralSpec> specs;
  for (uint32_t i = 0; i < 150; ++i)
    specs.push_back(test::albedo_spec("ggx", "smith_ggx_correlated", "schlick", 0.05 + 0.005 * i, 0.3 + 0.004 * i,
                                      0.04, 0.0, i, IntegralKind::Masking));
  REQUIRE(specs.size() * n > kMaxCountedGrid);
  Integrator in(*rt, TermSelection::all());
  const std::vector<float> all = in.sample_values(specs, n, 5);
  REQUIRE(all.size() == specs.size() * n);
  for (size_t j : {size_t(0), size_t(130), specs.size() - 1}) {  // the last integrals lie in the second launch
    CAPTURE(j);
    const std::vector<float> one = in.sample_values({specs[j]}, n, 5);
    for (uint32_t k = 0; k < n; ++k) {
      CAPTURE(k);
      REQUIRE(std::isfinite(all[j * n + k]));
      REQUIRE(std::memcmp(&all[j * n + k], &one[k], sizeof(float)) == 0);
    }
  }
}

namespace {

// The .so files of PoCL's cache under `dir`, by path relative to it.
std::set<std::string> compiled_files(const fs::path& dir) {
  std::set<std::string> out;
  for (auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().extension() == ".so") out.insert(fs::relative(e.path(), dir).string());
  return out;
}

// The plan of the census test above.
const char* const kPlanArgs =
    "--check d_norm --check masking --check furnace --check energy --model ggx/smith_ggx_correlated "
    "--model beckmann/smith_beckmann";

// Runs the compile-ahead child alone (MFV_COMPILE_AHEAD=only) on an empty
// cache, then the run without a child on that cache: the files the run added.
std::set<std::string> left_to_the_run(const fs::path& dir, const std::string& child_env,
                                      const std::string& plan_args = kPlanArgs) {
  const fs::path cache = dir / "pocl";
  fs::create_directories(cache);
  const std::string pocl = "POCL_CACHE_DIR=" + cache.string() + " POCL_KERNEL_CACHE=1";
  const std::string run = "--quiet run " + plan_args + " --out " + (dir / "out").string();
  const test::Run child = test::run_mfv(run, pocl + " MFV_COMPILE_AHEAD=only " + child_env);
  INFO(child.out);
  REQUIRE(child.code == 0);
  REQUIRE(!fs::exists(dir / "out" / "results.json"));  // it ran nothing itself
  const std::set<std::string> by_child = compiled_files(cache);
  REQUIRE(!by_child.empty());
  const test::Run alone = test::run_mfv(run, pocl + " MFV_COMPILE_AHEAD=0");
  INFO(alone.out);
  REQUIRE(alone.code == 0);
  std::set<std::string> added;
  for (const std::string& f : compiled_files(cache))
    if (!by_child.count(f)) added.insert(f);
  return added;
}

}  // namespace

TEST_CASE("The compile-ahead child compiles the run's kernels as the run launches them", "[device][cold]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  if (!test::is_pocl(*rt)) return test::skip("compile-ahead fills PoCL's kernel cache");
  test::Scratch scratch("mfv_ahead");
  // Everything but the double twin's program and its sample_values, which
  // the run builds while the child builds the float program (the hand-over):
  // the child's variants are the ones the run launches.
  const std::set<std::string> added = left_to_the_run(scratch.dir / "same", "");
  CAPTURE(added);
  REQUIRE(added.size() == 1);
  CHECK(fs::path(*added.begin()).filename() == "sample_values.so");
  // Planted: a child that launches at other work-group sizes leaves the run
  // its kernels to compile again.
  const std::set<std::string> planted = left_to_the_run(scratch.dir / "planted", "MFV_MAX_LOCAL_SIZE=4");
  CHECK(planted.size() > 1);
  // The pointwise kinds, which the child runs with as little host work as it
  // can (agree's first case): it leaves the run none of their kernels either
  const std::set<std::string> pointwise =
      left_to_the_run(scratch.dir / "pointwise", "",
                      "--check agree --check stability --check bsdf_reciprocity --model ggx/smith_ggx_correlated");
  CHECK(pointwise.empty());
}

TEST_CASE("A compile-ahead child that fails or never ends leaves the run's results as without it", "[device][cold]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  if (!test::is_pocl(*rt)) return test::skip("compile-ahead runs where the device is PoCL");
  test::Scratch scratch("mfv_ahead_fail");
  const std::string args = "--quiet run --check d_norm --check masking --model ggx/smith_ggx_correlated --out ";
  // each with PoCL's cache empty (a cold run: the run waits for the child's hand-over only there)
  auto results = [&](const std::string& name, const std::string& env) {
    fs::create_directories(scratch.dir / name / "pocl");
    const test::Run r = test::run_mfv(args + (scratch.dir / name / "out").string() + "/",
                                      "MFV_COMPILE_AHEAD_LOG=" + (scratch.dir / name / "child.log").string() +
                                          " POCL_CACHE_DIR=" + (scratch.dir / name / "pocl").string() + " " + env);
    INFO(r.out);
    REQUIRE(r.code == 0);
    const nlohmann::json j = nlohmann::json::parse(test::slurp(scratch.dir / name / "out" / "results.json"));
    return std::make_pair(j.at("results"), j.at("groups"));
  };
  const auto without = results("off", "MFV_COMPILE_AHEAD=0");
  CHECK(!fs::exists(scratch.dir / "off" / "child.log"));
  // auto (the default) starts a child or not by the load; the results are the same either way
  CHECK(results("auto", "MFV_COMPILE_AHEAD=auto") == without);
  // A child that works hands the run the integration program (it built it into PoCL's cache)
  // (POCL_AFFINITY unset: this test process's own list_devices set it, and an explicit value is kept)
  CHECK(results("on", "env -u POCL_AFFINITY MFV_COMPILE_AHEAD=1") == without);
  const std::string on_log = test::slurp(scratch.dir / "on" / "child.log");
  CAPTURE(on_log);
  CHECK(on_log.find("mfv run: integration program taken from the child") != std::string::npos);
  // beside the child, the run's and the child's PoCL workers are left unpinned (pin_pocl_workers pins
  // otherwise): two lines, one a process
  size_t unpinned = 0;
  for (size_t at = 0; (at = on_log.find("PoCL's workers left unpinned beside the child", at)) != std::string::npos; ++at)
    ++unpinned;
  CHECK(unpinned == 2);
  for (const char* failure : {"abort", "hang"}) {
    CAPTURE(failure);
    CHECK(results(failure, std::string("MFV_COMPILE_AHEAD=1 MFV_COMPILE_AHEAD_TEST=") + failure) == without);
    // the child started, and the run ended it
    const std::string log = test::slurp(scratch.dir / failure / "child.log");
    CAPTURE(log);
    CHECK(log.find("started") != std::string::npos);
    // the run waited for the child's hand-over no longer than the child lived, or than its bound, and built
    // the program itself
    const std::string outcome =
        failure == std::string("abort") ? "not built: the child ended; built here" : "late: built here";
    CHECK(log.find("mfv run: integration program " + outcome) != std::string::npos);
    CHECK(log.find("taken from the child") == std::string::npos);
    // a hung child is ended by the run: none is left with the run's --out in its command line
    const test::Run left = test::run_mfv_shell("pgrep -f '[-]-out " + (scratch.dir / failure).string() + "/'");
    CHECK(left.code == 1);
  }
  const test::Run bad = test::run_mfv(args + (scratch.dir / "bad").string(), "MFV_COMPILE_AHEAD=yes");
  CHECK(bad.code == 2);
  CHECK(bad.out.find("MFV_COMPILE_AHEAD=yes") != std::string::npos);
}

TEST_CASE("Compile-ahead's default takes a free core and never a busy machine", "[cold]") {
  CHECK(compile_ahead_pays(2, 0.0));
  CHECK(compile_ahead_pays(2, 1.0));   // one other task: the second core is free
  CHECK(!compile_ahead_pays(2, 1.3));  // more than one: the child would compete with the run
  CHECK(!compile_ahead_pays(1, 0.0));  // one core: the run's own compiles hold it
  CHECK(compile_ahead_pays(16, 14.5));
  CHECK(!compile_ahead_pays(16, std::numeric_limits<double>::infinity()));  // load unknown
}
