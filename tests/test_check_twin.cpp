// mfv check's double twin of user code (issue 28 item 2): the user's file
// compiled again with its float types double, so that a verdict separates a
// wrong formula from float conditioning. A correct float32 GGX written the
// textbook way (examples/shading/textbook_ggx.glsl) passes d_norm and agree
// at alpha >= 1e-3; named plants in the same file still fail, as formula
// errors.
#include "run_mfv.hpp"
#include "skip.hpp"
#include "test_files.hpp"
#include "user/user_detail.hpp"
#include "user/user_twin.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <regex>
#include <string>

using namespace mfv::test;

namespace {

const std::string kTextbook = std::string(MFV_KERNEL_SOURCE_DIR) + "/../examples/shading/textbook_ggx.glsl";
const std::string kClaim = " --as ggx/smith_ggx_correlated/schlick --map alpha=roughness^2";

bool has_line(const std::string& out, const std::string& verdict, const std::string& check) {
  return std::regex_search(out, std::regex("(^|\n)" + verdict + " +" + check + " "));
}

// A named defect in textbook_ggx.glsl: text FROM becomes TO.
struct Plant {
  const char* name;
  const char* from;
  const char* to;
};

const Plant kPlants[] = {
    // a floor inside D's denominator: the narrow lobe's peak is cut (d_norm << 1 at alpha 1e-3)
    {"textbook_floor_in_d", "return a2 / (PI * f * f);", "return a2 / max(PI * f * f, 1e-4);"},
    // D without 1/pi: d_norm and agree read pi
    {"textbook_missing_pi", "return a2 / (PI * f * f);", "return a2 / (f * f);"},
    // D flushed to 0 below 1e-6 (an early out): only a narrow lobe's far tails move, all below 1e-6 of
    // its peak, where a floor of 1e-6 of the setting's largest value (agree's before) read no error
    {"textbook_flush_tail", "return a2 / (PI * f * f);", "float d = a2 / (PI * f * f);\n    return d < 1e-6 ? 0.0 : d;"},
};

std::string planted(const Scratch& s, const std::string& name) {
  for (auto& p : kPlants)
    if (name == p.name) {
      std::string text = slurp(kTextbook);
      size_t at = text.find(p.from);
      REQUIRE(at != std::string::npos);
      text.replace(at, std::string(p.from).size(), p.to);
      return s.file(name + ".glsl", text);
    }
  FAIL("no plant " << name);
  return "";
}

bool no_twin(const Run& r) { return r.out.find("no double twin (the device has no cl_khr_fp64)") != std::string::npos; }

}  // namespace

TEST_CASE("The twin's text drops the f suffix of floating literals, #define bodies included, line for line",
          "[check][twin]") {
  const std::string in =
      "const float PI = 3.14159265f;\n#define HALF 0.5f\nfloat f(float x) { return x * 2.0F + 1e-3f + 0x1p-3f + 3; }\n"
      "// 1.0f in a comment\n";
  const std::string out = mfv::twin_text("t.cl", in);
  CHECK(out ==
        "const float PI = 3.14159265;\n#define HALF 0.5\nfloat f(float x) { return x * 2.0 + 1e-3 + 0x1p-3f + 3; }\n"
        "// 1.0f in a comment\n");
}

TEST_CASE("A textbook float32 GGX passes d_norm and agree at alpha >= 1e-3 through its double twin on seeds 1 to 3",
          "[device][check][cli][twin]") {
  for (int seed : {1, 2, 3}) {
    Run r = run_mfv("check --brdf " + kTextbook + kClaim + " --check d_norm agree --seed " + std::to_string(seed));
    INFO(seed << ": " << r.out);
    if (no_twin(r)) return skip("the device has no cl_khr_fp64: no double twin");
    CHECK(r.code == 0);
    CHECK(has_line(r.out, "pass", "d_norm"));
    CHECK(has_line(r.out, "pass", "agree"));
    CHECK(r.out.find("the double twin agrees; float conditioning (within the derived bound)") != std::string::npos);
  }
}

TEST_CASE("Through the double twin a formula error still fails: a floor in D and a missing 1/pi, named formula errors",
          "[device][check][cli][twin][planted]") {
  const Scratch s("mfv_twin");
  Run fl = run_mfv("check --brdf " + planted(s, "textbook_floor_in_d") + " --check d_norm");
  INFO(fl.out);
  if (no_twin(fl)) return skip("the device has no cl_khr_fp64: no double twin");
  CHECK(fl.code == 1);
  CHECK(has_line(fl.out, "FAIL", "d_norm"));
  CHECK(fl.out.find("formula error: off by") != std::string::npos);
  Run pi = run_mfv("check --brdf " + planted(s, "textbook_missing_pi") + kClaim + " --check agree");
  INFO(pi.out);
  CHECK(pi.code == 1);
  CHECK(has_line(pi.out, "FAIL", "agree"));
  CHECK(pi.out.find("formula error: brdf(wi=") != std::string::npos);
}

TEST_CASE("agree's measure reads a value's own rounding near 0 as no error and a formula error near 0 as one",
          "[check][twin][agree]") {
  using mfv::user_detail::agree_error;
  using mfv::user_detail::rounding_at;
  const double nan = std::numeric_limits<double>::quiet_NaN(), fmin = std::numeric_limits<float>::min();
  // a reference of 1e-9 where the float code's terms are of order 1: it rounds by 6e-8 (kf - kd), and
  // the twin's value, formula for formula the claimed model's, differs from the reference by less
  const double rv = 1e-9, kd = float(rv + 4e-17), kf = kd + 6e-8;
  CHECK(agree_error(kd, rv, 0, rounding_at(kd, kf)) == 0);
  CHECK(agree_error(kf, rv, 0, rounding_at(kf, nan)) > 1);  // the float value itself, judged alone: 60x
  // twice the reference there (a formula error near 0) is one: far beyond the float code's rounding
  const double twice = float(2 * rv), kf2 = float(twice + 1e-16);
  CHECK(agree_error(twice, rv, 0, rounding_at(twice, kf2)) == Approx(1).epsilon(1e-6));
  // no rounding at all: exactly the relative error
  CHECK(agree_error(1.5, 1.0, 0, 0) == 0.5);
  // below FLT_MIN float holds 2^-150 absolute: a subnormal reference rounded to float reads 0, twice it does not
  const double sub = 1e-40;
  CHECK(agree_error(double(float(sub)), sub, 0, rounding_at(double(float(sub)), nan)) == 0);
  CHECK(agree_error(double(float(2 * sub)), sub, 0, rounding_at(double(float(2 * sub)), nan)) ==
        Approx(sub / fmin).epsilon(1e-3));
  CHECK(std::isinf(agree_error(nan, 1.0, 0, 0)));
}

TEST_CASE("Through the double twin a formula error in a narrow lobe's far tails fails agree, correct files pass",
          "[device][check][cli][twin][planted]") {
  const Scratch s("mfv_twin");
  const std::string flushed = planted(s, "textbook_flush_tail");
  for (int seed : {1, 2, 3}) {
    Run r = run_mfv("check --brdf " + flushed + kClaim + " --check agree --seed " + std::to_string(seed));
    INFO(seed << ": " << r.out);
    if (no_twin(r)) return skip("the device has no cl_khr_fp64: no double twin");
    CHECK(r.code == 1);
    CHECK(has_line(r.out, "FAIL", "agree"));
    CHECK(r.out.find("formula error: brdf(wi=") != std::string::npos);
  }
  // engine-style files, correct, whose values near 0 (grazing, f0 = 0 near the specular peak) are
  // conditioned: pass on seeds 1 to 3 (the textbook file is the test above)
  const std::string shading = std::string(MFV_KERNEL_SOURCE_DIR) + "/../examples/shading/";
  for (int seed : {1, 2, 3})
    for (const std::string& d : {std::string("glsl"), std::string("hlsl")}) {
      Run r = run_mfv("check --include " + shading + "engine_brdf." + d + " --brdf " + shading + "check_engine." + d +
                      kClaim + " --check agree --seed " + std::to_string(seed));
      INFO(d << " seed " << seed << ": " << r.out);
      CHECK(r.code == 0);
      CHECK(has_line(r.out, "pass", "agree"));
    }
}
