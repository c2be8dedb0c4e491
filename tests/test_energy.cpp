// mfv energy: closed forms, the alpha -> 0 limit, the reference on identical
// samples, the baseline gate on a planted change, and bad options.
#include "catalog/catalog.hpp"
#include "catalog/roughness.hpp"
#include "checks/energy.hpp"
#include "checks/integrate.hpp"
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "reference/estimators.hpp"
#include "runtime/dispatch.hpp"

#include "run_mfv.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

using namespace mfv;
using Catch::Matchers::WithinAbs;

namespace {

using mfv::test::Run;
using mfv::test::run_mfv;

// Mean and standard error over `reps` randomizations of an RQMC albedo integral.
Cell device_albedo(Runtime& rt, const std::string& d, const std::string& g, double alpha, double mu, int reps,
                   uint64_t points) {
  TermSelection sel;
  sel.d = {&find_term(d)};
  sel.g = {&find_term(g)};
  sel.f = {&find_term("none")};
  Integrator in(rt, sel);
  std::vector<IntegralSpec> specs;
  for (int r = 0; r < reps; ++r) {
    IntegralSpec s;
    s.check = static_cast<int32_t>(IntegralKind::AlbedoRqmc);
    s.d = term_index(find_term(d));
    s.g = term_index(find_term(g));
    s.f = term_index(find_term("none"));
    s.pd = float(native_from_alpha(find_term(d).roughness, alpha));
    s.pg = float(native_from_alpha(find_term(g).roughness, alpha));
    s.width = float(alpha);
    s.cos_o = float(mu);
    s.stream = uint32_t(r);
    specs.push_back(s);
  }
  auto est = in.run(specs, points, 11);
  double sum = 0, ss = 0;
  for (auto& e : est) sum += e.mean;
  const double mean = sum / reps;
  for (auto& e : est) ss += (e.mean - mean) * (e.mean - mean);
  return {mean, std::sqrt(ss / (reps - 1) / reps)};
}

}  // namespace

TEST_CASE("GGX at alpha = 1 and normal view with a Smith G has albedo 1 - ln 2", "[energy][reference]") {
  // With alpha = 1, D_ggx = 1/pi and G1(n) = 1, so E(1) = 2 int_0^{pi/4} G1(2t) sin 2t dt
  // with G1(theta) = 2 cos/(1 + cos): 2 int (sin 2t - tan t) dt = 1 - ln 2.
  const double exact = 1.0 - std::log(2.0);
  for (const char* g : {"smith_ggx", "smith_ggx_correlated"}) {
    CAPTURE(g);
    ref::IntegralRef r;
    r.kind = ref::Integral::AlbedoRqmc;
    r.brdf = {&find_term("ggx"), &find_term(g), &find_term("none"), 1.0, 1.0, 0, 0, 0};
    r.width = 1.0;
    r.cos_o = 1.0;
    double sum = 0, ss = 0;
    const int reps = 8, n = 2048;
    for (int rep = 0; rep < reps; ++rep) {
      r.stream = uint32_t(rep);
      double m = 0;
      for (int k = 0; k < n; ++k) m += ref::sample_value(r, 3, uint64_t(k));
      sum += m / n;
      ss += (m / n) * (m / n);
    }
    const double mean = sum / reps, se = std::sqrt(std::max(0.0, ss / reps - mean * mean) / (reps - 1));
    CAPTURE(mean, se);
    CHECK_THAT(mean, WithinAbs(exact, std::max(5 * se, 1e-5)));
    CHECK(se < 5e-4);
  }
}

TEST_CASE("the device reaches 1 - ln 2 for GGX at alpha = 1, normal view, Smith G", "[device][energy]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  Cell c = device_albedo(*rt, "ggx", "smith_ggx_correlated", 1.0, 1.0, 8, 4096);
  CAPTURE(c.mean, c.se);
  CHECK_THAT(c.mean, WithinAbs(1.0 - std::log(2.0), std::max(5 * c.se, 2e-5)));
}

TEST_CASE("E tends to 1 as alpha tends to 0 for a Smith G at non-grazing view", "[device][energy]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  for (double mu : {0.3, 0.7}) {
    Cell c = device_albedo(*rt, "ggx", "smith_ggx", 1e-3, mu, 8, 4096);
    CAPTURE(mu, c.mean, c.se);
    CHECK_THAT(c.mean, WithinAbs(1.0, std::max(5 * c.se, 2e-3)));
  }
}

TEST_CASE("at grazing view the energy estimator reaches 1e-4 with 8 x 8192 points", "[device][energy]") {
  // The conformance proposal leaves the 1/cos_o growth of the integrand to
  // chance (about 1.5e-4 at 16 x 16384 points here); visible normals take it.
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  Cell c = device_albedo(*rt, "ggx", "smith_ggx_correlated", 0.069, 1.0 / 64, 8, 8192);
  CAPTURE(c.mean, c.se);
  CHECK(c.se < 1e-4);
  CHECK(c.se > 0);
}

TEST_CASE("the visible-normal proposal is unbiased for Ds of other shapes, and a wrong proposal pdf is caught",
          "[device][energy][planted]") {
  // E by mfv energy's estimator (a GGX-shaped visible-normal proposal, 8 x 4096
  // RQMC points) against the conformance suite's independent cosine + Cauchy
  // estimator (2^20 iid samples), at grazing view and where Phong's tails are
  // heavier than GGX's (alpha = 0.8: ap = 1.1).
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  struct Case {
    const char *d, *g;
    double alpha, mu;
  };
  const std::vector<Case> cases = {{"phong", "smith_phong", 0.8, 0.05},
                                   {"beckmann", "smith_beckmann", 0.5, 0.05},
                                   {"ggx", "cook_torrance", 0.2, 0.3}};
  TermSelection sel;
  for (const Case& k : cases) {
    sel.d.push_back(&find_term(k.d));
    sel.g.push_back(&find_term(k.g));
  }
  sel.f = {&find_term("none")};
  auto spec = [](const Case& k, IntegralKind kind, uint32_t stream) {
    IntegralSpec s;
    s.check = static_cast<int32_t>(kind);
    s.d = term_index(find_term(k.d));
    s.g = term_index(find_term(k.g));
    s.f = term_index(find_term("none"));
    s.pd = float(native_from_alpha(find_term(k.d).roughness, k.alpha));
    s.pg = float(native_from_alpha(find_term(k.g).roughness, k.alpha));
    s.width = float(k.alpha);
    s.cos_o = float(k.mu);
    s.stream = stream;
    return s;
  };
  const int reps = 8;
  auto worst_z = [&](Runtime& r) {
    Integrator in(r, sel);
    std::vector<IntegralSpec> qmc, iid;
    for (const Case& k : cases) {
      for (int j = 0; j < reps; ++j) qmc.push_back(spec(k, IntegralKind::AlbedoRqmc, uint32_t(j)));
      iid.push_back(spec(k, IntegralKind::Albedo, 99));
    }
    auto q = in.run(qmc, 4096, 11);
    auto m = in.run(iid, uint64_t(1) << 20, 5);
    double worst = 0;
    for (size_t c = 0; c < cases.size(); ++c) {
      std::vector<Estimate> mine(q.begin() + long(c) * reps, q.begin() + long(c + 1) * reps);
      double sum = 0, ss = 0;
      for (auto& e : mine) sum += e.mean;
      const double mean = sum / reps;
      for (auto& e : mine) ss += (e.mean - mean) * (e.mean - mean);
      const double se = std::sqrt(ss / (reps - 1) / reps);
      const double z = std::abs(mean - m[c].mean) / std::hypot(se, m[c].stderr_);
      UNSCOPED_INFO(cases[c].d << "/" << cases[c].g << ": " << mean << " +- " << se << " vs " << m[c].mean << " +- "
                               << m[c].stderr_ << ", z = " << z);
      worst = std::max(worst, z);
    }
    return worst;
  };
  CHECK(worst_z(*rt) < 5);
  // the proposal's pdf 3 % too high: E 3 % too low
  const test::PlantedKernelDir k("estimators.cl", "return w2 / (MFV_PI * k * k) / (R(2.0)",
                                 "return R(1.03) * w2 / (MFV_PI * k * k) / (R(2.0)");
  Runtime planted = k.runtime();
  CHECK(worst_z(planted) > 5);
}

TEST_CASE("energy tables agree with the double reference on identical samples and report their accuracy",
          "[device][energy]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  EnergyOptions o;
  o.models = {"ggx/smith_ggx_correlated", "phong/smith_phong"};
  o.n_mu = 4;
  o.n_alpha = 3;
  o.target = 2e-3;
  o.max_points = 4096;
  o.reference_every = 3;
  EnergyReport rep = run_energy(*rt, o);
  REQUIRE(rep.tables.size() == 2);
  CHECK(rep.reference_compared > 10);
  CHECK(rep.reference_worst <= rep.reference_bound);
  CHECK(rep.samples_per_second > 0);
  for (auto& t : rep.tables)
    for (size_t c = 0; c < t.E.size(); ++c) {
      CAPTURE(t.name(), c, t.E[c].mean);
      CHECK(t.E[c].mean > 0);
      // GGX with its own correlated Smith G loses energy; phong/smith_phong may
      // not (the Beckmann-fit G1 under-masks Phong at alpha = 1: E = 1.1 there)
      if (t.d->id == "ggx") CHECK(t.E[c].mean < 1 + 5 * t.E[c].se);
      CHECK_THAT(t.A[c].mean + t.B[c].mean, WithinAbs(t.E[c].mean, 1e-9));
      CHECK(t.B[c].mean >= 0);
    }
  // E_avg as its own integral agrees with the mu-grid quadrature roughly (4 cells: coarse)
  for (auto& t : rep.tables)
    for (size_t a = 0; a < t.eavg.size(); ++a) {
      CHECK_THAT(t.eavg[a].mean, WithinAbs(t.eavg_quad[a].mean, 0.03));
      // and within their total uncertainties: the quadrature's carries its
      // rule error (|Q_3h - Q_h|), which a noise-only SE left out
      CAPTURE(t.name(), a, t.eavg[a].mean, t.eavg[a].se, t.eavg_quad[a].mean, t.eavg_quad[a].se);
      CHECK(std::fabs(t.eavg[a].mean - t.eavg_quad[a].mean) <= 4 * std::hypot(t.eavg[a].se, t.eavg_quad[a].se));
    }
}

TEST_CASE("the baseline gate flags a D scaled by 1.02 and passes an unchanged rerun with another seed",
          "[device][energy][cli][planted]") {
  if (!test::device_runtime()) return;
  namespace fs = std::filesystem;
  const test::Scratch scratch("mfv_energy_test");
  const fs::path dir = scratch.dir;
  const std::string common = "energy --models ggx/smith_ggx_correlated --grid 4x3 --target 1e-3 --max-points 4096";
  Run first = run_mfv(common + " --seed 1 --out " + (dir / "a").string());
  INFO(first.out);
  REQUIRE(first.code == 0);
  REQUIRE(fs::exists(dir / "a" / "energy.json"));
  REQUIRE(fs::exists(dir / "a" / "kulla_conty.h"));
  REQUIRE(fs::exists(dir / "a" / "csv" / "ggx__smith_ggx_correlated.csv"));
  REQUIRE(fs::exists(dir / "a" / "report.md"));
  CHECK(first.out.find("points/s") != std::string::npos);
  const std::string base = " --baseline " + (dir / "a" / "energy.json").string();
  Run same = run_mfv(common + " --seed 2" + base);
  INFO(same.out);
  CHECK(same.code == 0);
  CHECK(same.out.find("0 moved") != std::string::npos);
  const test::PlantedKernelDir k("terms_d.cl", "real d = R(1.0) / (MFV_PI * a2 * k * k);",
                                 "real d = R(1.02) / (MFV_PI * a2 * k * k);");
  Run planted = run_mfv("--kernel-dir " + k.path() + " " + common + " --seed 3" + base);
  INFO(planted.out);
  CHECK(planted.code == 1);
  CHECK(planted.out.find("MOVED") != std::string::npos);
}

TEST_CASE("mfv energy rejects bad options with one line and exit 2", "[energy][cli]") {
  for (const char* args : {"--grid 32", "--grid 1x32", "--grid 32x32x", "--target 0", "--target nan",
                           "--models no_such_model", "--replicates 1", "--baseline /nonexistent/energy.json"}) {
    Run r = run_mfv(std::string("energy ") + args);
    CAPTURE(args, r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: ", 0) == 0);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  }
}
