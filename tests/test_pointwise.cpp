// The pointwise harness (issue 18): one record layout, defined once in
// kernels/abi/pointwise.h and included by the kernels and the host; the
// loader's include expansion (embedded and --kernel-dir); a layout changed on
// one side only, or a value written to the wrong slot, fails.
#include "agree_options.hpp"
#include "checks/agree.hpp"
#include "checks/pointwise.hpp"
#include "checks/stability.hpp"
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "runtime/kernel_includes.hpp"
#include "stability_options.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>

#include <map>
#include <string>
#include <vector>

using namespace mfv;

namespace {

// A loader over named texts, each as the kernel loader returns it.
struct FakeFiles {
  std::map<std::string, std::string> files;
  int loads = 0;
  std::string operator()(const std::string& name) {
    ++loads;
    auto it = files.find(name);
    if (it == files.end()) throw Error("no kernel file " + name);
    return "#line 1 \"" + name + "\"\n" + it->second;
  }
};

}  // namespace

TEST_CASE("Kernel files include abi/ headers once per program, with #line back into the includer",
          "[pointwise][kernel-include]") {
  FakeFiles f;
  f.files["abi/x.h"] = "#define X 1\n";
  std::set<std::string> seen;
  auto load = [&](const std::string& n) { return f(n); };
  std::string a = expand_kernel_includes("#line 1 \"a.cl\"\nint a;\n#include \"abi/x.h\"\nint b = X;\n", load, seen);
  CHECK(a == "#line 1 \"a.cl\"\nint a;\n#line 1 \"abi/x.h\"\n#define X 1\n#line 4 \"a.cl\"\nint b = X;\n");
  // a second file of the same program: the header is not pasted again
  std::string b = expand_kernel_includes("#line 1 \"b.cl\"\n  #  include \"abi/x.h\"\nint c;\n", load, seen);
  CHECK(b == "#line 1 \"b.cl\"\n#line 3 \"b.cl\"\nint c;\n");
  CHECK(f.loads == 1);
  // includes outside abi/ are the OpenCL compiler's
  std::string c = expand_kernel_includes("#line 1 \"c.cl\"\n#include \"other.h\"\n", load, seen);
  CHECK(c == "#line 1 \"c.cl\"\n#include \"other.h\"\n");
}

TEST_CASE("An include of a missing or self-including abi/ header is an error", "[pointwise][kernel-include][errors]") {
  FakeFiles f;
  f.files["abi/loop.h"] = "#include \"abi/loop.h\"\n";
  std::set<std::string> seen;
  auto load = [&](const std::string& n) { return f(n); };
  CHECK_THROWS_WITH(expand_kernel_includes("#line 1 \"a.cl\"\n#include \"abi/none.h\"\n", load, seen),
                    Catch::Contains("abi/none.h"));
  std::set<std::string> seen2;
  CHECK_THROWS_WITH(expand_kernel_includes("#line 1 \"a.cl\"\n#include \"abi/loop.h\"\n", load, seen2),
                    Catch::Contains("includes itself"));
}

TEST_CASE("The pointwise record layout reads the same in OpenCL C and in C++", "[device][pointwise]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  const std::string probe =
      "#include \"abi/pointwise.h\"\n"
      "__kernel void layout(__global int* o) {\n"
      "  o[0] = PW_RECORD; o[1] = PW_VALUE; o[2] = PW_VALUE_LO; o[3] = PW_P0; o[4] = PW_PG;\n"
      "  o[5] = PW_ALPHA_Y; o[6] = PW_SIN2H; o[7] = PW_M_X; o[8] = PW_USER_G1_WI; o[9] = PW_VARIANT; o[10] = "
      "PW_PARAMS;\n"
      "}\n";
  cl::Program prog = rt->build({"common.cl"}, {}, "", "", {{"layout_probe.cl", probe, ""}});
  cl::Kernel k(prog, "layout");
  std::vector<cl_int> out(11, -1);
  cl::Buffer buf(rt->context(), CL_MEM_WRITE_ONLY, out.size() * sizeof(cl_int));
  k.setArg(0, buf);
  rt->queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(1));
  rt->queue().enqueueReadBuffer(buf, CL_TRUE, 0, out.size() * sizeof(cl_int), out.data());
  using namespace pw;
  const std::vector<cl_int> host = {PW_RECORD, PW_VALUE, PW_VALUE_LO,   PW_P0,      PW_PG,    PW_ALPHA_Y,
                                    PW_SIN2H,  PW_M_X,   PW_USER_G1_WI, PW_VARIANT, PW_PARAMS};
  CHECK(out == host);
  // every slot of a record is inside it, and the outputs do not overlap the inputs
  CHECK(PW_VALUE > PW_M_Z);
  CHECK(PW_USER_G1_WI < PW_RECORD);
}

TEST_CASE("A record layout changed on the kernel side only fails agreement", "[device][pointwise][planted]") {
  if (!test::device_runtime()) return;
  // the kernels read the G's width from p5 (0 for a single term) while the host writes PW_PG = 7
  const test::PlantedKernelDir dir("abi/pointwise.h", "PW_PG = 7,", "PW_PG = 11,");
  Runtime rt = dir.runtime();
  AgreeReport rep = run_agree(rt, test::agree_options({"G1 smith_ggx"}, 2000));
  REQUIRE(!rep.results.empty());
  test::check_every_case_fails(rep);
}

TEST_CASE("A sweep value written to the wrong slot reads as the NaN sentinel and fails the gate",
          "[device][pointwise][stability][planted]") {
  if (!test::device_runtime()) return;
  const test::PlantedKernelDir dir("stability.cl", "g_rec[PW_VALUE] =", "g_rec[PW_VALUE_LO] =");
  Runtime rt = dir.runtime();
  StabilityReport rep = run_stability(rt, test::one_term("F dielectric"));  // --only matches substrings: "F schlick" also picks schlick_f90 and schlick_sg
  REQUIRE(rep.cases.size() == 1);
  CHECK(rep.cases[0].count(&RegionResult::nan, true) == rep.cases[0].count(&RegionResult::points, true));
  CHECK_FALSE(rep.gate_pass());
}

TEST_CASE("The ULP accounting: ULPs of the reference, equal infinities agree, NaN is an infinite error",
          "[pointwise][ulp]") {
  CHECK(ulp_of(1.0, false) == 0x1p-23);
  CHECK(ulp_of(1.0, true) == 0x1p-52);
  CHECK(ulp_of(0.0, false) == std::numeric_limits<float>::denorm_min());
  PointError e = point_error(1.0 + 0x1p-22, 1.0, false);
  CHECK(e.ulps == 2.0);
  CHECK(point_error(INFINITY, INFINITY, false).ulps == 0.0);
  CHECK(std::isinf(point_error(NAN, 1.0, false).ulps));
  CHECK(std::isinf(sweep_ulps(-1e-30, 0.0, false)));
  // the sensitivity of x -> x^2 at 1 to one rounding: 2 units; NaN moves are skipped
  double dev = input_sensitivity(
      2, 1.0, false, [](int j, double b) { return j == 0 ? (1 + b) * (1 + b) : NAN; }, 1.0);
  CHECK_THAT(dev, Catch::Matchers::WithinRel(2 * 0x1p-23, 1e-6));
}
