// Every kernel program mfv builds compiles warning-free with -Werror on every
// OpenCL implementation present (PoCL; Intel's CPU runtime, Oclgrind and
// rusticl where scripts/install-ocl-extras.sh installed them), through
// MFV_CL_OPTIONS (host/runtime/build_options.hpp). What each can check:
// - PoCL and rusticl honour -Werror; PoCL refuses other -W options
//   ("Invalid build option"), so it checks clang's default warnings.
// - rusticl (llvmpipe) has no fp64: there a double constant in a float
//   build is clang's warning "double precision constant requires
//   cl_khr_fp64", an error under -Werror: no implicit double.
// - Intel's compiler takes clang's -Werror=double-promotion: any float
//   promoted to double (x * 0.5 instead of x * 0.5f) is an error there, on
//   a device that has fp64 and would otherwise compute it in double (float
//   builds only: a MFV_DOUBLE build promotes float records by design). Not
//   -Werror: its vectorizer warns that the kernels' vec_type_hint
//   (MFV_NO_IMPLICIT_VECTORIZE, the workaround for its miscompilation)
//   stops it, which -Werror would make fatal; other warnings are in the
//   build log, which mfv passes on, and the test finds none.
// - Oclgrind ignores -Werror (a warning leaves the build good): mfv passes a
//   good build log's warning lines on to stderr, and the test finds none.
// Nothing here relies on -cl-fp32-correctly-rounded-divide-sqrt, -cl-denorms-are-zero
// or -cl-mad-enable: mfv passes none of them (Runtime::base_options).
#include "ocl_vendors.hpp"
#include "run_mfv.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace mfv::test;

namespace {

// One command per program variant mfv builds, each with the smallest
// workload (the builds are the point; verdicts are the conformance tests').
struct Program {
  std::string args;
  bool fp64;            // needs cl_khr_fp64: builds with MFV_DOUBLE, where float promoted to double is meant
  bool doubles = fp64;  // builds a MFV_DOUBLE program (run: the reference twin on fp64 devices)
};
const std::vector<Program>& programs() {
  static const std::vector<Program> p = {
      // integrate.cl (MFV_ACC_DOUBLE on fp64 devices), and on fp64 devices
      // its MFV_DOUBLE twin for the same-sample reference comparison
      {"run --check closed_form --scale 0.01 --model 'lambert['", false, true},
      {"agree --samples 64 --only 'D ggx'", false},            // agree.cl, float
      {"agree --fp64 --samples 64 --only 'D ggx'", true},      // agree.cl, MFV_DOUBLE
      {"samplers --samples 4096 --device-only", false},        // samplers.cl
      {"stability --terms-only --only 'D ggx'", false},        // stability.cl, float
      {"stability --fp64 --terms-only --only 'D ggx'", true},  // stability.cl, MFV_DOUBLE
      // --timeout: the watchdog's 30 s floor is for users' code; on a loaded
      // 2-core machine Oclgrind's calibration launch alone came close to it
      // user_brdf.cl, and on fp64 devices the user file's double twin
      // (user/user_twin.*), where double is meant
      {"check --brdf " + kBrdfExamples +
           "ggx.cl --as ggx/smith_ggx_correlated/schlick --samples 64 --check reciprocity --timeout 600",
       false, true},  // with MFV_USER_HAS_D, MFV_USER_HAS_G1
      {"check --brdf " + kBrdfExamples + "lambert.cl --samples 64 --check reciprocity --timeout 600", false,
       true},  // neither
  };
  return p;
}

// The compiler's warnings in mfv's output ("file:line:col: warning: ..."),
// not a driver's own notes (rusticl: "MESA: warning: Treating
// load_kernel_arg in control flow as uniform").
std::string warnings_in(const std::string& out) {
  std::istringstream in(out);
  std::string found;
  for (std::string line; std::getline(in, line);)
    if (line.find("warning") != std::string::npos && line.rfind("MESA: warning:", 0) != 0) found += line + "\n";
  return found;
}

// Builds every program on the implementation `env` selects with `options`
// (and `float_options` too where it builds no MFV_DOUBLE program); each
// build must succeed and print no warning.
void builds_cleanly(const std::string& env, const std::string& options, const std::string& float_options = "") {
  auto devs = run_mfv("devices", env);
  REQUIRE(devs.code == 0);
  const bool fp64 = devs.out.find(" yes ") != std::string::npos;
  for (auto& p : programs()) {
    if (p.fp64 && !fp64) continue;
    const std::string all = options + (p.doubles ? "" : " " + float_options);
    auto r = run_mfv(p.args, env + " MFV_CL_OPTIONS='" + all + "'");
    CAPTURE(env, all, p.args, r.out);
    CHECK(r.out.find("kernel build failed") == std::string::npos);
    CHECK((r.code == 0 || r.code == 1));  // 1: a verdict at these tiny workloads; 2 would be an error
    CHECK(warnings_in(r.out).empty());
  }
}

}  // namespace

TEST_CASE("Every kernel program compiles warning-free with -Werror on PoCL", "[portability][werror]") {
  builds_cleanly("", "-Werror");
}

TEST_CASE("Every kernel program compiles warning-free on Intel's CPU runtime with no float promoted to double",
          "[portability][werror][intel]") {
  std::string dir = vendor_dir("intel");
  if (!dir.empty()) builds_cleanly(vendor_env("intel", dir), "", "-Werror=double-promotion");
}

TEST_CASE("Every kernel program compiles without a warning on Oclgrind", "[portability][werror][oclgrind]") {
  std::string dir = vendor_dir("oclgrind");
  if (!dir.empty()) builds_cleanly(vendor_env("oclgrind", dir), "-Werror");
}

namespace {

// kernels/ copied into `dir` with `line` appended to common.cl (which every
// program includes first).
void plant_in_common(const std::filesystem::path& dir, const std::string& line) {
  namespace fs = std::filesystem;
  // with kernels/abi/, the headers kernel files include
  fs::copy(fs::path(MFV_TEST_DATA_DIR) / "../../kernels", dir, fs::copy_options::recursive);
  std::ofstream(dir / "common.cl", std::ios::app) << "\n" << line << "\n";
}

}  // namespace

TEST_CASE("The -Werror builds fail on a planted warning and a planted float-to-double promotion",
          "[portability][werror]") {
  mfv::test::Scratch unused("mfv_werror_unused"), promo("mfv_werror_promotion");
  // clang's default -Wunused-value
  plant_in_common(unused.dir, "static inline void mfv_planted(__global float* a) { a[0]; }");
  // x * 0.5: computed in double on a device with fp64 (-Wdouble-promotion)
  plant_in_common(promo.dir, "static inline float mfv_planted(float x) { return x * 0.5; }");
  const std::string agree = " agree --samples 64 --only 'D ggx'";
  auto r = run_mfv("--kernel-dir " + unused.dir.string() + agree, "MFV_CL_OPTIONS=-Werror");
  CAPTURE(r.out);
  CHECK(r.code == 2);
  CHECK(r.out.find("kernel build failed") != std::string::npos);
  r = run_mfv("--kernel-dir " + unused.dir.string() + agree);  // without -Werror: a warning only
  CHECK(r.code == 0);
  CHECK(!warnings_in(r.out).empty());
  if (std::string dir = vendor_dir("oclgrind"); !dir.empty()) {
    // Oclgrind ignores -Werror: the warning shows in mfv's output all the same
    r = run_mfv("--kernel-dir " + unused.dir.string() + agree, vendor_env("oclgrind", dir) + " MFV_CL_OPTIONS=-Werror");
    CAPTURE(r.out);
    CHECK(!warnings_in(r.out).empty());
  }
  if (std::string dir = vendor_dir("intel"); !dir.empty()) {
    r = run_mfv("--kernel-dir " + promo.dir.string() + agree,
                vendor_env("intel", dir) + " MFV_CL_OPTIONS=-Werror=double-promotion");
    CAPTURE(r.out);
    CHECK(r.code == 2);
    CHECK(r.out.find("increases floating-point precision") != std::string::npos);
  }
}

TEST_CASE("MFV_CL_OPTIONS that is not build options or that the implementation refuses is one error line",
          "[portability][werror]") {
  for (const char* bad : {"Werror", "-Werror;rm", "-I/tmp/x y", "-D'X'"}) {
    auto r = run_mfv("agree --samples 64 --only 'D ggx'", std::string("MFV_CL_OPTIONS=\"") + bad + "\"");
    CAPTURE(bad, r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: MFV_CL_OPTIONS", 0) == 0);
  }
  auto r = run_mfv("agree --samples 64 --only 'D ggx'", "MFV_CL_OPTIONS=-no-such-option");
  CAPTURE(r.out);
  CHECK(r.code == 2);
  CHECK(r.out.rfind("mfv: error: kernel build failed", 0) == 0);
}

TEST_CASE("Every kernel program compiles warning-free with -Werror on rusticl without fp64",
          "[portability][werror][rusticl]") {
  // opt-in as the rusticl conformance test (tests/test_portability.cpp)
  if (!std::getenv("MFV_PORTABILITY_RUSTICL")) {
    skip("rusticl -Werror test: set MFV_PORTABILITY_RUSTICL=1");
    return;
  }
  std::string dir = vendor_dir("rusticl");
  if (!dir.empty()) builds_cleanly(vendor_env("rusticl", dir), "-Werror");
}
