// The command line: listings, and one-line errors with exit code 2 on bad input.
#include "catalog/bsdfs.hpp"
#include "catalog/catalog.hpp"
#include "catalog/models.hpp"

#include "run_mfv.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <map>
#include <string>

namespace {

using mfv::test::Run;
using mfv::test::run_mfv;

size_t lines(const std::string& s) {
  size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

}  // namespace

TEST_CASE("mfv list shows every catalog term with its source", "[cli]") {
  Run r = run_mfv("list");
  REQUIRE(r.code == 0);
  for (auto& t : mfv::catalog()) {
    CAPTURE(t.id);
    CHECK(r.out.find(" " + t.id + " ") != std::string::npos);
    CHECK(r.out.find(t.source) != std::string::npos);
  }
}

TEST_CASE("mfv list --json is valid JSON with ranges for every parameter", "[cli]") {
  Run r = run_mfv("list --json");
  REQUIRE(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  // terms, then whole models, then the rough dielectric BTDFs
  REQUIRE(j.size() == mfv::catalog().size() + mfv::models().size() + mfv::bsdfs().size());
  for (auto& t : j) {
    CAPTURE(t["id"]);
    for (auto& p : t["params"]) CHECK(p["min"].get<double>() <= p["max"].get<double>());
  }
  CHECK(j[4]["known_bad"].get<std::string>().find("pi/4") != std::string::npos);
}

TEST_CASE("mfv list --json shows each BSDF's transmission checks with the verdict the catalog expects",
          "[cli][transmission]") {
  Run r = run_mfv("list --json");
  REQUIRE(r.code == 0);
  std::map<std::string, std::map<std::string, std::string>> expect;  // bsdf -> check -> expect
  for (auto& e : nlohmann::json::parse(r.out))
    if (e["kind"] == "bsdf")
      for (auto& c : e["checks"]) expect[e["id"]][c["check"]] = c["expect"];
  REQUIRE(expect.size() == mfv::bsdfs().size());
  CHECK(expect["walter_ggx_correlated"] == std::map<std::string, std::string>{{"agree", "hold"},
                                                                             {"stability", "hold"},
                                                                             {"bsdf_furnace", "hold"},
                                                                             {"transmission_masking", "hold"},
                                                                             {"bsdf_avg_reciprocity", "hold"},
                                                                             {"bsdf_reciprocity", "hold"}});
  CHECK(expect["walter_ggx_no_eta2"]["bsdf_furnace"] == "fail");
  CHECK(expect["walter_ggx_no_eta2"]["bsdf_reciprocity"] == "fail");
  CHECK(expect["walter_ggx_no_eta2"]["bsdf_avg_reciprocity"] == "fail");
  CHECK(expect["walter_ggx_jacobian_sum"]["bsdf_avg_reciprocity"] != "hold");  // may: its averages diverge
  CHECK(expect["walter_ggx_no_eta2"]["transmission_masking"] == "hold");
  CHECK(expect["walter_ggx_same_side"]["bsdf_reciprocity"] == "hold");  // dropping chi+ is symmetric in i and o
  CHECK(expect["walter_ggx_beckmann_g1"]["transmission_masking"] == "fail");
  r = run_mfv("list");
  CHECK(r.out.find("checks: agree hold; stability hold; bsdf_furnace hold; transmission_masking hold; "
                   "bsdf_avg_reciprocity hold; bsdf_reciprocity hold") != std::string::npos);
}

TEST_CASE("mfv devices lists at least one OpenCL device", "[cli][device]") {
  Run r = run_mfv("devices");
  if (r.code == 2 && r.out.find("no OpenCL platform") != std::string::npos) {
    WARN("no OpenCL platform: " << r.out);
    return;
  }
  REQUIRE(r.code == 0);
  CHECK(lines(r.out) >= 2);
  CHECK(r.out.find("fp64") != std::string::npos);
}

TEST_CASE("Bad input gets a one-line error naming the cause and exit code 2", "[cli][errors]") {
  struct Case {
    const char* args;
    const char* expect;
  };
  auto c =
      GENERATE(Case{"eval nosuchterm", "unknown term 'nosuchterm'"}, Case{"eval ggx --param alpha=-1", "out of range"},
               Case{"eval ggx --param alpha=nan", "is NaN"}, Case{"eval ggx --param alpha=abc", "not a number"},
               Case{"eval ggx --param eta=1.5", "belongs to none"},
               Case{"eval ggx/smith_ggx/schlick --param f0=1.5", "out of range"},
               Case{"eval ggx/schlick/smith_ggx", "must name a D, a G and an F"},
               Case{"eval ggx/smith_ggx/schlick --wi 1,2", "three comma-separated"},
               Case{"eval ggx/smith_ggx/schlick --alpha 0", "positive"}, Case{"eval ggx --g1", "no Smith G1"},
               Case{"--device no-such-device eval ggx", "no OpenCL device matches"},
               Case{"--device 99 eval ggx", "no OpenCL device with index 99"}, Case{"agree --samples -5", "--samples"},
               Case{"agree --samples 0", "--samples"},
               Case{"agree --only nothing-matches --samples 10", "matches no agreement case"},
               Case{"--kernel-dir /no/such/dir list", "--kernel-dir"}, Case{"frobnicate", "frobnicate"});
  CAPTURE(c.args);
  Run r = run_mfv(c.args);
  CAPTURE(r.out);
  CHECK(r.code == 2);
  CHECK(r.out.find(c.expect) != std::string::npos);
  CHECK(lines(r.out) == 1);
  CHECK(r.out.rfind("mfv: error: ", 0) == 0);
}
