// mfv stability (issue 6): the seed 000 edge cases, every sweep region, the
// gate on a planted unstable kernel, the outputs and bad options.
#include "catalog/catalog.hpp"
#include "checks/stability.hpp"
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "reference/reference.hpp"

#include "run_mfv.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

using namespace mfv;

namespace {

using mfv::test::Run;
using mfv::test::run_mfv;

bool no_platform(const Run& r) { return r.code == 2 && r.out.find("no OpenCL platform") != std::string::npos; }

// One sweep per precision, shared by the tests that read it.
const StabilityReport* sweep(bool fp64) {
  static std::unique_ptr<StabilityReport> rep[2];
  Runtime* rt = fp64 ? test::fp64_runtime("float64 sweep") : test::device_runtime();
  if (!rt) return nullptr;
  if (!rep[fp64]) {
    StabilityOptions opt;
    opt.fp64 = fp64;
    rep[fp64] = std::make_unique<StabilityReport>(run_stability(*rt, opt));
  }
  return rep[fp64].get();
}

const RegionResult* region(const StabilityCase& c, const std::string& name) {
  for (auto& r : c.regions)
    if (r.region == name) return &r;
  return nullptr;
}

}  // namespace

TEST_CASE("Reference G1 terms follow seed 000: (v.n) above 1 and tan = 0 give exactly 1", "[reference][edge][g1]") {
  const double above = std::nextafter(1.0, 2.0);
  for (auto fn : {ref::G1_smith_ggx, ref::G1_smith_beckmann, ref::G1_smith_beckmann_approx}) {
    for (double alpha : {1e-7, 0.3, 10.0}) {
      CAPTURE(alpha);
      CHECK(fn(above, alpha) == 1.0);
      CHECK(fn(1.0 + 1e-6, alpha) == 1.0);
      CHECK(fn(1.0, alpha) == 1.0);  // tan = 0: never divided by
    }
  }
  CHECK(ref::G1_smith_phong(above, 1e6) == 1.0);
  CHECK(ref::G1_smith_phong(1.0, 0.0) == 1.0);
}

TEST_CASE("Kernel and reference G1 give 1 at tan = 0 and at (v.n) rounded above 1 in every sweep point",
          "[device][stability][edge][g1]") {
  for (bool fp64 : {false, true}) {
    const StabilityReport* rep = sweep(fp64);
    if (!rep) continue;
    int g1_cases = 0;
    for (auto& c : rep->cases) {
      bool g1 = c.family == "G1" || (c.group == "variant" && c.family == "G1_smith_ggx");
      if (!g1) continue;
      const Term* term = try_find_term(c.name.substr(c.name.find(' ') + 1), Kind::G);
      if (term && !term->g1_not_one_at_normal.empty()) {  // a fitted Lambda (the catalog says why): no 1 expected
        for (auto* name : {"tan_zero", "above_one"}) CHECK(region(c, name)->expect.empty());
        continue;
      }
      ++g1_cases;
      for (auto* name : {"tan_zero", "above_one"}) {
        CAPTURE(fp64, c.name, name);
        auto* r = region(c, name);
        REQUIRE(r);
        CHECK(r->expect == "1");
        CHECK(r->points > 0);
        CHECK(r->violations == 0);
        CHECK(r->ref_violations == 0);
      }
    }
    CHECK(g1_cases == 6 + 2);  // six catalog Smith G1s (two anisotropic, on their isotropic slice), two GGX G1 forms
  }
}

TEST_CASE("Every sweep region runs and stable terms and BRDFs stay finite in float32 and float64",
          "[device][stability]") {
  for (bool fp64 : {false, true}) {
    const StabilityReport* rep = sweep(fp64);
    if (!rep) continue;
    CAPTURE(fp64);
    CHECK(rep->gate_pass());
    std::set<std::string> seen;
    size_t brdfs = 0;
    for (auto& c : rep->cases) {
      brdfs += c.group == "brdf";
      for (auto& r : c.regions) {
        CAPTURE(c.name, r.region, r.first_break);
        seen.insert(r.region);
        CHECK(r.points > 0);
        CHECK(r.violations == 0);  // the value the seeds prescribe (0 below the horizon, G1 = 1 at tan = 0)
        if (c.stable && r.in_domain) {
          CHECK(r.nan == 0);
          CHECK(r.inf == 0);
        }
      }
    }
    CHECK(brdfs == 5 * 9 * 4);
    for (auto* name :
         {"grazing", "mid", "normal", "tan_zero", "above_one", "below_horizon", "sharp", "rough", "zero_width",
          "f0_ends", "eta_near_1", "tir", "nk_extreme", "mirror", "near_mirror", "opposite", "non_unit", "scan"}) {
      CAPTURE(name);
      CHECK(seen.count(name) == 1);
    }
    CHECK_FALSE(rep->scans.empty());
  }
}

TEST_CASE("The kernel defaults are the stable formulations and every alternative breaks somewhere in float32",
          "[device][stability][variants]") {
  const StabilityReport* rep = sweep(false);
  if (!rep) return;
  std::set<std::string> families_with_default;
  for (auto& c : rep->cases) {
    if (c.group != "variant") continue;
    CAPTURE(c.name);
    uint64_t breaks = c.count(&RegionResult::breaks, true);
    if (c.is_default) {
      families_with_default.insert(c.family);
      CHECK(breaks == 0);
    } else {
      CHECK(breaks > 0);
    }
  }
  CHECK(families_with_default == std::set<std::string>{"D_ggx", "Lambda_ggx", "G1_smith_ggx", "VoH", "sin2H"});
  // Where the textbook forms break (the report's claim, pinned):
  for (auto& c : rep->cases) {
    CAPTURE(c.name);
    if (c.name == "variant D_ggx via (n.h)^2(a^2-1)+1") CHECK(region(c, "normal")->inf > 0);  // a^2 - 1 -> -1
    if (c.name == "variant D_ggx via tan2") CHECK(region(c, "grazing")->nan > 0);             // 0 * inf
    if (c.name == "variant Lambda_ggx via tan2") CHECK(region(c, "mid")->breaks > 0);         // sqrt(1+x) - 1
  }
}

TEST_CASE("The stability gate fails on a planted GGX D without the sin2 form", "[device][stability][planted]") {
  if (!test::device_runtime()) return;
  // seed 000's second GGX form: at n.h = 1 and alpha^2 below half an ulp of 1
  // the bracket is 0 and D = inf.
  const test::PlantedKernelDir dir("terms_d.cl", "real d = R(1.0) / (MFV_PI * a2 * k * k);",
                                   "real d = a2 / (MFV_PI * sqr(c * c * (a2 - R(1.0)) + R(1.0)));");
  Runtime rt = dir.runtime();
  StabilityOptions opt;
  opt.combinations = false;
  opt.only = {"D ggx"};
  StabilityReport rep = run_stability(rt, opt);
  REQUIRE(rep.cases.size() == 1);
  CHECK_FALSE(rep.gate_pass());
  CHECK(rep.cases[0].count(&RegionResult::inf, true) > 0);

  Run r = run_mfv("--kernel-dir " + dir.path() + " stability --terms-only --only 'D ggx'");
  CAPTURE(r.out);
  CHECK(r.code == 1);
  CHECK(r.out.find("gate: FAIL D ggx") != std::string::npos);
  CHECK(r.out.find("kernel=inf") != std::string::npos);  // the first breaking input, in hex-float
}

TEST_CASE("mfv stability --out writes JSON and Markdown whole and says in one line when gnuplot is missing",
          "[device][stability][cli]") {
  namespace fs = std::filesystem;
  const test::Scratch scratch("mfv_stability");
  const fs::path dir = scratch.dir / "out";
  Run r = run_mfv("stability --terms-only --only 'D ggx' --only 'variant' --out " + dir.string(),
                  "MFV_GNUPLOT=/nonexistent/gnuplot");
  if (no_platform(r)) {
    WARN("no OpenCL platform: " << r.out);
    return;
  }
  CAPTURE(r.out);
  CHECK(r.code == 0);
  CHECK(r.out.find("gate: pass") != std::string::npos);
  CHECK(r.out.find("plots skipped: gnuplot not found") != std::string::npos);
  std::ifstream in(dir / "stability.json");
  REQUIRE(in);
  auto j = nlohmann::json::parse(in);
  CHECK(j["schema"] == "mfv-stability/1");
  CHECK(j["gate"]["pass"] == true);
  CHECK(j["cases"].size() == 13);  // D ggx and 12 variants
  CHECK(fs::exists(dir / "stability.md"));
  CHECK(fs::exists(dir / "error_theta_d.dat"));
  for (auto& e : fs::directory_iterator(dir)) {
    CAPTURE(e.path());
    CHECK(e.path().string().find(".tmp-mfv") == std::string::npos);
  }
}

TEST_CASE("mfv stability rejects bad options with a one-line error and exit code 2", "[cli][errors][stability]") {
  struct Case {
    const char* args;
    const char* expect;
  };
  auto c = GENERATE(Case{"stability --only nothing-matches", "matches no stability case"},
                    Case{"stability --out /dev/null/x", "cannot create that folder"},
                    Case{"stability --samples 10", "--samples"}, Case{"stability --fp64=maybe", "--fp64"});
  CAPTURE(c.args);
  Run r = run_mfv(c.args);
  if (no_platform(r)) return;
  CAPTURE(r.out);
  CHECK(r.code == 2);
  CHECK(r.out.find(c.expect) != std::string::npos);
  CHECK(r.out.rfind("mfv: error: ", 0) == 0);
  size_t lines = 0;
  for (char ch : r.out) lines += ch == '\n';
  CHECK(lines == 1);
}
