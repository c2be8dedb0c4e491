// The conformance suite (mfv run): every check fails on a planted bad model
// and passes on the correct one; verdicts are stable across seeds; the gate's
// exit code and outputs are what a CI needs.
#include "checks/suite.hpp"
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "suite_verdicts.hpp"

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
#include <sstream>
#include <string>

using namespace mfv;
using namespace mfv::test;

namespace {

SuiteOptions only(std::vector<std::string> checks, std::vector<std::string> models) {
  SuiteOptions o;
  o.checks = std::move(checks);
  o.models = std::move(models);
  o.seed = 7;
  return o;
}

}  // namespace

TEST_CASE("d_norm fails on a D scaled by 1.01 and passes on the correct one", "[device][suite][planted]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  auto opt = only({"d_norm"}, {"ggx"});
  SuiteReport good = run_suite(*rt, opt);
  CHECK(verdict_of(good, "d_norm", "ggx") == Verdict::Pass);
  CHECK(good.gate_ok());

  SuiteReport bad = test::planted_suite("terms_d.cl", "real d = R(1.0) / (MFV_PI * a2 * k * k);",
                                        "real d = R(1.01) / (MFV_PI * a2 * k * k);", opt);
  CHECK(verdict_of(bad, "d_norm", "ggx") == Verdict::Fail);
  CHECK_FALSE(bad.gate_ok());
  // the reference still evaluates the true D, so the same-sample comparison
  // catches the plant independently of the statistics
  CHECK_FALSE(bad.reference_ok());

  // the stratified d_norm integrals resolve far smaller errors: 1e-4 fails too
  auto opt2 = opt;
  opt2.reference_samples = 0;
  CHECK(verdict_of(test::planted_suite("terms_d.cl", "real d = R(1.0) / (MFV_PI * a2 * k * k);",
                                       "real d = R(1.0001) / (MFV_PI * a2 * k * k);", opt2),
                   "d_norm", "ggx") == Verdict::Fail);
}

TEST_CASE("masking fails on a G1 that does not belong to its D and passes on the correct one",
          "[device][suite][planted]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  auto opt = only({"masking"}, {"ggx/smith_ggx"});
  opt.reference_samples = 0;  // the plant is in the kernel only; test the statistics alone
  SuiteReport good = run_suite(*rt, opt);
  CHECK(verdict_of(good, "masking", "ggx/smith_ggx") == Verdict::Pass);

  // GGX's G1 built on Beckmann's Lambda
  test::check_planted_fails("terms_g.cl", "return R(1.0) / (R(1.0) + Lambda_ggx(NoV, alpha));",
                            "return R(1.0) / (R(1.0) + Lambda_beckmann(NoV, alpha));", opt, "masking", "ggx/smith_ggx");
}

TEST_CASE("furnace and energy fail on a BRDF that adds energy and pass on the correct one",
          "[device][suite][planted]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  auto opt = only({"furnace", "energy"}, {"ggx/smith_ggx_correlated"});
  opt.reference_samples = 0;
  opt.scale = 4;  // a 10 % excess needs about 4x the default samples per integral to stand out
  SuiteReport good = run_suite(*rt, opt);
  CHECK(verdict_of(good, "furnace", "ggx/smith_ggx_correlated/none") == Verdict::Pass);
  CHECK(verdict_of(good, "energy", "ggx/smith_ggx_correlated/schlick") == Verdict::Pass);

  // 10 % more specular than the model
  SuiteReport bad = test::planted_suite("brdf.cl", "return kd * MFV_INV_PI + spec / (R(4.0) * NoL) / NoV;",
                                        "return kd * MFV_INV_PI + R(1.1) * spec / (R(4.0) * NoL) / NoV;", opt);
  CHECK(verdict_of(bad, "furnace", "ggx/smith_ggx_correlated/none") == Verdict::Fail);
  CHECK(verdict_of(bad, "energy", "ggx/smith_ggx_correlated/schlick") == Verdict::Fail);
  CHECK_FALSE(bad.gate_ok());
}

TEST_CASE("reciprocity fails on a BRDF that evaluates F at n.l and passes on the correct one",
          "[device][suite][planted]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  auto opt = only({"reciprocity"}, {"ggx/smith_ggx/schlick"});
  SuiteReport good = run_suite(*rt, opt);
  CHECK(verdict_of(good, "reciprocity", "ggx/smith_ggx/schlick") == Verdict::Pass);

  test::check_planted_fails("brdf.cl", "eval_F(f, VoH, f0, f1)", "eval_F(f, NoL, f0, f1)", opt, "reciprocity",
                            "ggx/smith_ggx/schlick");
}

TEST_CASE("The catalog's known failures show as xfail with their reason", "[device][suite]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  SuiteReport rep =
      run_suite(*rt, only({"d_norm", "masking"}, {"beckmann_ct82", "ggx/smith_beckmann", "cook_torrance"}));
  const GroupResult* ct82 = group(rep, "d_norm", "beckmann_ct82");
  REQUIRE(ct82);
  CHECK(ct82->verdict == Verdict::XFail);
  CHECK(ct82->reason.find("pi/4") != std::string::npos);
  // and the estimate is pi/4 (seed 001's 4 m^2 in place of pi m^2)
  const PointResult& w = rep.points[ct82->worst];
  CHECK(std::fabs(w.estimate - M_PI / 4) < 6 * w.stderr_ + 1e-3);
  CHECK(verdict_of(rep, "masking", "ggx/smith_beckmann") == Verdict::XFail);
  // V-cavity masking is exact for its own microsurface: it conserves
  // projected area under every proper D (Heitz 2014 §5.3)
  CHECK(verdict_of(rep, "masking", "ggx/cook_torrance") == Verdict::Pass);
  CHECK(verdict_of(rep, "masking", "beckmann_ct82/cook_torrance") == Verdict::XFail);
  CHECK(rep.gate_ok());
}

TEST_CASE("The default suite gives no unexpected verdict under 20 seeds (at a quarter of its samples)",
          "[device][suite][seeds]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  // A quarter of the default samples keeps CI short and is the harder case
  // for the expected failures (they must still show); the false-alarm rate
  // does not depend on the sample count. scripts/seed-sweep.sh runs the full
  // default under 20 seeds.
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    SuiteOptions opt;
    opt.seed = seed;
    opt.scale = 0.25;
    opt.reference_every = 997;
    SuiteReport rep = run_suite(*rt, opt);
    CAPTURE(seed, rep.reference_worst, rep.reference_worst_at);
    CHECK(rep.reference_ok());
    for (auto& g : rep.groups) {
      if (g.verdict != Verdict::Fail && g.verdict != Verdict::XPass) continue;
      CAPTURE(g.check, g.model, verdict_name(g.verdict), g.reason);
      CHECK(false);
    }
  }
}

TEST_CASE("mfv run exits 1 on a planted failure, 0 on the correct model, and writes its reports whole",
          "[device][suite][cli]") {
  if (!test::device_runtime()) return;
  namespace fs = std::filesystem;
  const Scratch scratch("mfv_run_out");
  const fs::path out = scratch.dir / "out";
  Run good = run_mfv("run --check d_norm reciprocity --model ggx/smith_ggx/schlick ggx --out " + out.string());
  CAPTURE(good.out);
  CHECK(good.code == 0);
  CHECK(good.out.find("gate: ok") != std::string::npos);
  auto j = nlohmann::json::parse(slurp(out / "results.json"));
  CHECK(j["schema"] == "mfv-run/1");
  for (const char* k : {"device", "build", "timings", "run", "tool"}) CHECK(j.contains(k));
  CHECK(j["run"].contains("seed"));
  CHECK(j["tool"].contains("commit"));
  CHECK(j["device"].contains("driver"));
  REQUIRE(j["results"].size() > 0);
  for (auto& r : j["results"])
    for (const char* k : {"check", "D", "G", "F", "params", "estimate", "stderr", "bound", "samples", "verdict"})
      CHECK(r.contains(k));
  std::string junit = slurp(out / "junit.xml");
  CHECK(junit.find("<testsuites ") != std::string::npos);
  CHECK(junit.find("</testsuites>") != std::string::npos);
  CHECK(slurp(out / "report.md").find("Gate: **ok**") != std::string::npos);

  const test::PlantedKernelDir dir("terms_d.cl", "real d = R(1.0) / (MFV_PI * a2 * k * k);",
                                   "real d = R(1.01) / (MFV_PI * a2 * k * k);");
  Run bad = run_mfv("--kernel-dir " + dir.path() + " run --check d_norm --model ggx --out " + out.string());
  CAPTURE(bad.out);
  CHECK(bad.code == 1);
  CHECK(bad.out.find("gate: FAILED") != std::string::npos);
  CHECK(slurp(out / "junit.xml").find("<failure") != std::string::npos);
}

TEST_CASE("mfv run rejects bad options with one clear line and exit code 2", "[suite][cli]") {
  struct Case {
    const char* args;
    const char* says;
  };
  auto c =
      GENERATE(Case{"run --samples -5", "--samples must be a positive count"},
               Case{"run --samples 0", "--samples must be a positive count"},
               Case{"run --scale -1", "--scale must be a positive number"},
               Case{"run --scale nan", "--scale: 'nan' is not a finite number"},
               Case{"run --check bogus", "unknown check 'bogus'"}, Case{"run --model nosuchmodel", "no model matches"});
  CAPTURE(c.args);
  Run r = run_mfv(c.args);
  CHECK(r.code == 2);
  CHECK(r.out.find(c.says) != std::string::npos);
  CHECK(r.out.find("mfv: error:") == 0);
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
}

TEST_CASE("mfv run --out onto a regular file fails cleanly and leaves the file as it was", "[suite][cli]") {
  namespace fs = std::filesystem;
  const Scratch scratch("mfv_not_a_dir");
  const fs::path f = scratch.file("results", "earlier results\n");
  Run r = run_mfv("run --check d_norm --model ggx --out " + f.string());
  CAPTURE(r.out);
  CHECK(r.code == 2);
  CHECK(r.out.find("mfv: error:") != std::string::npos);
  CHECK(slurp(f) == "earlier results\n");
}

TEST_CASE("The integrals stay finite and accurate at the extremes: alpha = 1e-4 and a view 1e-4 above the horizon",
          "[device][suite][edge]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  SuiteReport rep =
      run_suite(*rt, only({"d_norm", "masking", "furnace"}, {"ggx/smith_ggx_correlated", "beckmann/smith_beckmann"}));
  size_t at_extreme = 0;
  for (auto& p : rep.points) {
    CAPTURE(p.check, p.d->id, p.estimate, p.stderr_);
    REQUIRE(std::isfinite(p.estimate));
    REQUIRE(std::isfinite(p.stderr_));
    const bool tiny_alpha = p.params.count("alpha") && p.params.at("alpha") <= 1e-4;
    const bool grazing = p.params.count("cos_o") && p.params.at("cos_o") <= 1.0001e-4;
    if (p.check == "d_norm" && tiny_alpha) {
      ++at_extreme;
      // a million stratified samples, as cheap as at alpha = 0.5: within 1e-3 by far
      CHECK(std::fabs(p.estimate - 1.0) < 1e-5);
      CHECK(p.stderr_ < 1e-6);
    }
    if (grazing) {
      ++at_extreme;
      if (p.check == "masking") CHECK(std::fabs(p.estimate - 1.0) < 6 * p.stderr_);
      if (p.check == "furnace") CHECK(p.estimate <= 1.0 + 6 * p.stderr_);
    }
  }
  CHECK(at_extreme >= 2 + 4 * 12);  // d_norm for both Ds; 12 widths x (masking, furnace) x 2 models
  CHECK(rep.gate_ok());
}
