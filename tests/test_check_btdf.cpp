// mfv check on a user's btdf or bsdf (issue 29; docs/cli/check.md,
// "Transmission"): a correct Walter GGX rough dielectric written for these
// tests (tests/data/btdf/, not from kernels/) passes the registry's
// transmission kinds, each named plant fails the kind that sees its bug, and
// bad input gets one line and exit 2.
#include "run_mfv.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>

#include <regex>
#include <string>

using namespace mfv::test;

namespace {

const std::string kBtdfData = std::string(MFV_TEST_DATA_DIR) + "/btdf/";
const char* kTransmissionChecks = "--check bsdf_furnace transmission_masking bsdf_avg_reciprocity bsdf_reciprocity";
// those a file without D and G1 runs (transmission_masking needs both)
const char* kBsdfChecks = "--check bsdf_furnace bsdf_avg_reciprocity bsdf_reciprocity";

bool has_line(const std::string& out, const std::string& verdict, const std::string& check) {
  return std::regex_search(out, std::regex("(^|\n)" + verdict + " +" + check + " "));
}

bool one_error_line(const Run& r) {
  return r.code == 2 && r.out.rfind("mfv: error: ", 0) == 0 && r.out.find('\n') == r.out.size() - 1;
}

// A named defect: in FILE (tests/data/btdf/), text FROM becomes TO.
struct Plant {
  const char* name;
  const char* file;
  const char* from;
  const char* to;
};

// Walter et al. 2007 eq. 21 without eta_o^2 in the numerator: not reciprocal
// in the radiance form's generalized sense, and T_avg(1/eta) != T_avg(eta)/eta^2.
const Plant kNoEta2 = {"btdf without eta_o^2", "walter_ggx.cl", "* eo * eo * (1.0f - F)", "* (1.0f - F)"};
// The Jacobian's denominator as (i.h + o.h)^2: it vanishes at o = -i, where
// E_T diverges (absolute indices: symmetric in i and o, so only the furnace sees it).
const Plant kJacobianSum = {"btdf with the Jacobian (i.h + o.h)^2", "walter_ggx.cl", "float den = ei * ih + eo * oh;",
                            "float den = ih + oh;"};
// The same in the flip form (relative index): no longer symmetric, so the
// generalized reciprocity sees it too.
const Plant kJacobianSumFlip = {"bsdf with the Jacobian (i.h + o.h)^2 (flip form)", "walter_ggx.glsl",
                                "float den = ih + eta * oh;", "float den = ih + oh;"};
// No orientation test: refracted directions on the incident side of the facet
// counted. Symmetric in i and o (reciprocity holds); E_T exceeds 1 at alpha = 1.
const Plant kSameSide = {"btdf counting refracted directions on the incident side", "walter_ggx.cl",
                         "  if (ih * wi.z <= 0.0f || oh * wo.z <= 0.0f) return (float3)(0.0f);\n", "\n"};

std::string planted(const Scratch& s, const Plant& p) {
  std::string text = slurp(kBtdfData + p.file);
  const size_t at = text.find(p.from);
  REQUIRE(at != std::string::npos);
  text.replace(at, std::string(p.from).size(), p.to);
  return s.file(p.file, text);
}

Run check(const std::string& file, const std::string& args) {
  Run r = run_mfv("check --brdf " + file + " " + args);
  INFO(file << " " << args << "\n" << r.out);
  return r;
}

}  // namespace

TEST_CASE("A correct user BTDF (Walter GGX, brdf and btdf) passes every transmission check on seeds 1 to 3",
          "[check][cli][btdf]") {
  for (int seed : {1, 2, 3}) {
    CAPTURE(seed);
    Run r = check(kBtdfData + "walter_ggx.cl", std::string(kTransmissionChecks) + " masking --seed " +
                                                   std::to_string(seed));
    INFO(r.out);
    CHECK(r.code == 0);
    for (auto* c : {"bsdf_furnace", "transmission_masking", "bsdf_avg_reciprocity", "bsdf_reciprocity", "masking"})
      CHECK(has_line(r.out, "pass", c));
    // E_R and E_T are reported apart
    CHECK(r.out.find("E_R = ") != std::string::npos);
    CHECK(r.out.find("E_T = ") != std::string::npos);
  }
}

TEST_CASE("A correct GLSL bsdf (one function for both hemispheres, the flip form) passes every check on seeds 1 to 3",
          "[check][cli][btdf]") {
  for (int seed : {1, 2, 3}) {
    CAPTURE(seed);
    Run r = check(kBtdfData + "walter_ggx.glsl", "--seed " + std::to_string(seed));
    INFO(r.out);
    CHECK(r.code == 0);
    for (auto* c : {"furnace", "energy", "reciprocity", "finite", "bsdf_furnace", "bsdf_avg_reciprocity",
                    "bsdf_reciprocity"})
      CHECK(has_line(r.out, "pass", c));
  }
}

TEST_CASE("A btdf that returns a negative value fails bsdf_reciprocity, naming the pair", "[check][cli][btdf]") {
  const Scratch s("mfv_check_btdf");
  // planted: the transmitted value's sign flipped where wi is below (light leaving)
  std::string t = slurp(kBtdfData + "walter_ggx.cl");
  const std::string from = "  return (float3)(v);\n}\n\n// optional";
  const size_t at = t.find(from);
  REQUIRE(at != std::string::npos);
  t.replace(at, from.size(), "  return (float3)(wi.z < 0.0f ? -v : v);\n}\n\n// optional");
  Run r = check(s.file("negative.cl", t), "--check bsdf_reciprocity");
  INFO(r.out);
  CHECK(r.code == 1);
  CHECK(has_line(r.out, "FAIL", "bsdf_reciprocity"));
  CHECK(r.out.find("beyond rounding inf") != std::string::npos);
}

TEST_CASE("Each planted BTDF bug fails the transmission check that sees it, on seeds 1 to 3",
          "[check][cli][btdf][planted]") {
  const Scratch s("mfv_check_btdf");
  struct Case {
    const Plant* plant;
    std::vector<std::pair<const char*, const char*>> lines;  // (verdict, check)
  };
  const Case cases[] = {
      {&kNoEta2, {{"FAIL", "bsdf_reciprocity"}, {"FAIL", "bsdf_avg_reciprocity"}}},
      {&kJacobianSum, {{"FAIL", "bsdf_furnace"}}},
      {&kJacobianSumFlip, {{"FAIL", "bsdf_reciprocity"}, {"FAIL", "bsdf_furnace"}}},
      {&kSameSide, {{"FAIL", "bsdf_furnace"}, {"pass", "bsdf_reciprocity"}}},
  };
  for (const Case& c : cases) {
    const std::string file = planted(s, *c.plant);
    for (int seed : {1, 2, 3}) {
      INFO(c.plant->name << ", seed " << seed);
      Run r = check(file, std::string(kBsdfChecks) + " --seed " + std::to_string(seed));
      INFO(r.out);
      CHECK(r.code == 1);
      for (auto& [verdict, name] : c.lines) CHECK(has_line(r.out, verdict, name));
    }
  }
}

TEST_CASE("mfv check refuses a bad btdf or eta with one line and exit 2", "[check][cli][btdf]") {
  const Scratch s("mfv_check_btdf");
  const std::string good = slurp(kBtdfData + "walter_ggx.cl");
  auto variant = [&](const std::string& name, const std::string& from, const std::string& to) {
    std::string t = good;
    const size_t at = t.find(from);
    REQUIRE(at != std::string::npos);
    t.replace(at, from.size(), to);
    return s.file(name, t);
  };
  // no eta parameter marked
  const std::string no_eta = variant("no_eta.cl", "default 1.5 eta", "default 1.5");
  Run r1 = check(no_eta, "");
  CHECK(one_error_line(r1));
  CHECK(r1.out.find("no parameter is its relative index eta") != std::string::npos);
  // --eta marks it instead
  CHECK(check(no_eta, "--eta eta --check bsdf_reciprocity").code == 0);
  // an eta range that contains 1 (index matched: a Dirac)
  Run r2 = check(variant("eta_one.cl", "eta 1.2 2.5", "eta 0.8 2.5"), "");
  CHECK(one_error_line(r2));
  CHECK(r2.out.find("one side of 1") != std::string::npos);
  // a wrong signature
  Run r3 = check(variant("sig.cl", "float3 btdf(float3 wi, float3 wo, const float* params)",
                         "float btdf(float3 wi, float3 wo, const float* params)"),
                 "");
  CHECK(one_error_line(r3));
  CHECK(r3.out.find("btdf must be 'float3 btdf(float3 wi, float3 wo, const float* params)'") != std::string::npos);
  // eta out of its range, or NaN
  for (const char* args : {"--param eta=3", "--param eta=nan", "--param eta=1", "--eta nothing"}) {
    Run r = check(kBtdfData + "walter_ggx.cl", args);
    INFO(args);
    CHECK(one_error_line(r));
  }
  // a btdf alone: bsdf_furnace needs the reflection too
  const std::string only = s.file(
      "only_btdf.cl", std::regex_replace(good, std::regex("\nfloat3 brdf\\("), "\nfloat3 unused_brdf("));
  Run r4 = check(only, "--check bsdf_furnace");
  CHECK(one_error_line(r4));
  CHECK(r4.out.find("needs brdf too") != std::string::npos);
  // ... and the checks that need no reflection run on it
  Run r5 = check(only, "--check bsdf_reciprocity bsdf_avg_reciprocity");
  CHECK(r5.code == 0);
  // bsdf beside brdf: one or the other
  Run r6 = check(s.file("both.cl", good + "\nfloat3 bsdf(float3 wi, float3 wo, const float* p) { return btdf(wi, wo, p); }\n"),
                 "");
  CHECK(one_error_line(r6));
}
