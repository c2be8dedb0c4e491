// mfv check's reader of the user's file (host/user/source_reader.cpp): the
// contract's functions and `// mfv: param` lines are found where the
// compiler sees them, whatever comments, strings, macros and conditional
// compilation surround them (issue 28: a `/* */` comment used to end the
// reading, so a D that integrates to 2 was silently skipped).
#include "checks/suite.hpp"
#include "test_files.hpp"
#include "user/source_reader.hpp"
#include "user/user_brdf.hpp"
#include "user/user_detail.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>

#include <regex>

using namespace mfv;
using namespace mfv::test;

namespace {

const std::string kBrdf =
    "float3 brdf(float3 wi, float3 wo, const float* params) { return (float3)(params[0] * 0.3f); }\n";
const std::string kD = "float D(float3 m, const float* params) { return m.z > 0.0f ? M_1_PI_F : 0.0f; }\n";
const std::string kParam = "// mfv: param alpha 0.01 1 default 0.3 roughness\n";

UserBrdf load(const Scratch& s, const std::string& text, UserParamArgs args = {}) {
  return load_user_brdf(s.file("f.cl", text), args);
}

}  // namespace

TEST_CASE("A /* */ comment anywhere in the user's file changes nothing the reader finds", "[check][reader]") {
  const Scratch s("mfv_reader");
  const std::vector<std::string> comments = {
      "/* one line */\n",      "/* several\n   lines, with float D(float3 m, const float* p) { inside\n */\n",
      "/** doc comment **/\n", "/* // a line comment inside */\n",
      "/*/ tricky */\n",       "// float D(float3 m) {\n"};
  for (auto& c : comments) {
    INFO(c);
    // before brdf, between brdf and D, after D
    for (const std::string& text :
         {kParam + c + kBrdf + kD, kParam + kBrdf + c + kD, kParam + kBrdf + kD + c, c + kParam + kBrdf + c + kD}) {
      UserBrdf u = load(s, text);
      CHECK(u.has_d);
      CHECK(u.params.size() == 1);
      CHECK(u.roughness == 0);
    }
  }
  // a declaration inside a block comment or an #if 0 is no declaration
  UserBrdf u = load(s, kParam + "/*\n// mfv: param f0 0 1\n*/\n#if 0\n// mfv: param g 0 1\n#endif\n" + kBrdf);
  CHECK(u.params.size() == 1);
}

TEST_CASE("Strings, line splices and macros do not mislead the reader", "[check][reader]") {
  const Scratch s("mfv_reader");
  UserBrdf u =
      load(s, kParam + "#define NOTE \"float D(float3 m, const float* p) {\"\n" +
                  "constant char* note = \"/* not a comment\";\n" + kBrdf + "#define LONG_MACRO(x) \\\n  (x)\n");
  CHECK(!u.has_d);
  CHECK(u.sources.back().text.find("not a comment") != std::string::npos);
  CHECK_THROWS_WITH(load(s, kParam + "/* never closed\n" + kBrdf), Catch::Contains(":2: this /* comment never ends"));
}

TEST_CASE("Conditional compilation decides which functions exist, and an undefined macro in #if is an error",
          "[check][reader]") {
  const Scratch s("mfv_reader");
  CHECK(!load(s, kParam + kBrdf + "#if 0\n" + kD + "#endif\n").has_d);
  CHECK(load(s, kParam + kBrdf + "#if 1 /* on */\n" + kD + "#endif\n").has_d);
  CHECK(load(s, kParam + "#define WITH_D 1\n" + kBrdf + "#if WITH_D && defined(WITH_D)\n" + kD + "#endif\n").has_d);
  const std::string quality = kParam + kBrdf + "#if QUALITY == HIGH\n" + kD + "#else\n#endif\n";
  CHECK_THROWS_WITH(load(s, quality), Catch::Contains("f.cl:3: #if reads 'QUALITY', which is not defined") &&
                                          Catch::Contains("--define QUALITY=VALUE"));
  UserParamArgs a;
  a.defines = {"QUALITY=2", "HIGH=2"};
  CHECK(load(s, quality, a).has_d);
  a.defines = {"QUALITY=1", "HIGH=2"};
  CHECK(!load(s, quality, a).has_d);
  CHECK_THROWS_WITH(load(s, kParam + kBrdf + "#ifdef X\n"), Catch::Contains("f.cl:3: this #if has no #endif"));
}

TEST_CASE("The tokenizer keeps offsets and lines, and knows comments from code", "[check][reader]") {
  auto t = tokenize("x", "a /* b\n c */ 1.5e-3f \"s/*\" // d\n#define X \\\n 2\n'\\''");
  REQUIRE(t.size() == 7);
  CHECK(t[1].kind == Token::BlockComment);
  CHECK(t[2].kind == Token::Number);
  CHECK(t[2].text == "1.5e-3f");
  CHECK(t[2].line == 2);
  CHECK(t[3].kind == Token::String);
  CHECK(t[4].kind == Token::LineComment);
  CHECK(t[5].kind == Token::Directive);
  CHECK(t[5].text == "#define X  2");
  CHECK(t[6].kind == Token::Char);
  CHECK(t[6].line == 5);
}

TEST_CASE("The user grids reach the declared roughness range's ends, down to a declared alpha of 1e-4",
          "[check][reader]") {
  // issue 28: the furnace, energy, agree and d_norm grids started at alpha = 0.01
  // whatever the file declared, so its narrowest lobes were never tested
  const Scratch s("mfv_reader_grid");
  const UserBrdf u = load(s, "// mfv: param alpha 1e-4 0.7 default 0.3 roughness\n" + kBrdf);
  for (const std::vector<double>& alphas : {suite_alphas(), suite_norm_alphas(), std::vector<double>{0.01, 0.5}}) {
    for (size_t most : {size_t(6), size_t(64)}) {
      const auto grid = user_detail::roughness_grid(u, alphas, most);
      REQUIRE(grid.size() >= 2);
      CHECK(grid.front()[0] == Approx(1e-4));
      CHECK(grid.back()[0] == Approx(0.7));
      for (auto& v : grid) CHECK((v[0] >= 1e-4 && v[0] <= 0.7));
    }
  }
  // planted: a range the suite's widths cover already adds no end point of its own
  const UserBrdf inside = load(s, "// mfv: param alpha 0.01 1 default 0.3 roughness\n" + kBrdf);
  const auto grid = user_detail::roughness_grid(inside, {0.01, 0.1, 1.0}, 64);
  CHECK(grid.size() == 3);
}
