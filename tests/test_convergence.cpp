// mfv convergence: the quadrature truth against closed forms, every estimator
// unbiased on smooth cases (device and reference, same samples), RQMC's
// slope beating MC's, a planted wrong pdf caught, bad input, report files.
#include "catalog/catalog.hpp"
#include "checks/convergence.hpp"
#include "checks/integrate.hpp"
#include "kernel_dir.hpp"
#include "numeric/hemisphere_quadrature.hpp"
#include "run_mfv.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace mfv;

namespace {

ConvergenceOptions smooth_options() {
  ConvergenceOptions o;
  o.cases = {{"ggx", 0.5, 0.5}, {"beckmann", 0.1, 0.3}};
  o.checks = {"d_norm", "albedo"};
  o.min_log2 = 12;
  o.max_log2 = 13;
  o.ref_max_log2 = 12;
  o.quad_max_order = 6;
  return o;
}

const ConvergenceSeries* find(const ConvergenceReport& r, const std::string& check, const std::string& est,
                              const std::string& engine, size_t k = 0) {
  for (auto& s : r.series)
    if (s.check == check && s.estimator == est && s.engine == engine && s.case_index == k) return &s;
  return nullptr;
}

}  // namespace

TEST_CASE("the product rule reproduces closed forms, stiff lobes and grazing views included", "[convergence]") {
  const ProductRule rule{16, 4, 8};
  for (const char* d : {"ggx", "beckmann"})
    for (double a : {1e-3, 1e-2, 0.5}) {
      const Term& t = find_term(d);
      const double v = integrate_normals([&](const glm::dvec3& m) { return t.ref_d(m.z, a) * m.z; }, rule).value;
      INFO(d << " alpha " << a);
      CHECK(std::fabs(v - 1.0) < 1e-9);  // ∫ D (m·n) dm = 1
    }
  // over half vectors with the horizon cut: Lambert's albedo is 1, ∫ (3/2π) cos² = 1, at any view
  for (double co : {1.0, 0.5, 0.05, 1e-3}) {
    const glm::dvec3 o(std::sqrt(1 - co * co), 0, co);
    INFO("cos_o " << co);
    CHECK(std::fabs(integrate_reflected([](const glm::dvec3& i) { return i.z / M_PI; }, o, rule).value - 1) < 1e-10);
    CHECK(std::fabs(integrate_reflected([](const glm::dvec3& i) { return 1.5 / M_PI * i.z * i.z; }, o, rule).value -
                    1) < 1e-10);
  }
}

TEST_CASE("every estimator is unbiased on smooth cases, on the device and in the reference", "[convergence]") {
  Runtime rt("", "");
  const ConvergenceReport r = run_convergence(rt, smooth_options());
  int tested = 0;
  for (auto& s : r.series) {
    INFO(s.check << " " << r.cases[s.case_index].name() << " " << s.estimator << " " << s.engine << " z " << s.z);
    if (s.estimator == "quadrature") {
      CHECK(s.levels.back().rmse < 1e-6);  // order 6 already
      continue;
    }
    ++tested;
    CHECK(s.consistent);
    CHECK(std::fabs(s.z) < 5);
  }
  CHECK(tested == 2 * (2 * 4 + 2 * 6));  // device and reference; d_norm without dsample and vndf
  // the truth's two refinements agree far below the tolerances measured
  for (auto& row : r.truth)
    for (auto& t : row) CHECK(t.error < 1e-9);
  CHECK(std::fabs(r.truth[0][0].quadrature_check - 1) < 1e-9);
}

TEST_CASE("device estimators and their reference twins agree on the same samples", "[convergence]") {
  Runtime rt("", "");
  TermSelection sel;
  for (const char* id : {"ggx", "beckmann", "smith_ggx_correlated", "smith_beckmann", "schlick"}) {
    const Term& t = find_term(id);
    (t.kind == Kind::D ? sel.d : t.kind == Kind::G ? sel.g : sel.f).push_back(&t);
  }
  Integrator in(rt, sel);
  std::vector<IntegralSpec> specs;
  uint32_t stream = 0;
  for (const ConvergenceCase& c : {ConvergenceCase{"ggx", 0.01, 0.05}, ConvergenceCase{"beckmann", 0.3, 0.7}})
    for (const char* check : {"d_norm", "albedo"})
      for (const char* e : {"uniform", "cosine", "dsample", "vndf", "rqmc"}) {
        if (!estimator_applies(e, check)) continue;
        IntegralSpec s;
        s.check = static_cast<int32_t>(std::string(check) == "d_norm" ? IntegralKind::DNorm : IntegralKind::Albedo);
        s.d = term_index(find_term(c.d));
        s.g = term_index(find_term(c.d == "ggx" ? "smith_ggx_correlated" : "smith_beckmann"));
        s.f = term_index(find_term("schlick"));
        s.pd = s.pg = s.width = float(c.alpha);
        s.f0 = 0.04f;
        s.cos_o = float(c.cos_o);
        s.estimator = estimator_id(e, c);
        s.stream = stream++;
        specs.push_back(s);
      }
  const auto agree = compare_with_reference(in, specs, 512, 7);
  for (size_t j = 0; j < specs.size(); ++j) {
    INFO("spec " << j << " estimator " << specs[j].estimator << " kernel " << agree[j].kernel_mean << " reference "
                 << agree[j].reference_mean);
    CHECK(agree[j].disagreement < 1e-4);
  }
}

TEST_CASE("RQMC converges faster than MC on a smooth albedo", "[convergence]") {
  Runtime rt("", "");
  ConvergenceOptions o;
  o.cases = {{"ggx", 0.5, 0.5}};
  o.checks = {"albedo"};
  o.estimators = {"vndf", "rqmc"};
  o.min_log2 = 7;
  o.max_log2 = 15;
  o.reference = false;
  const ConvergenceReport r = run_convergence(rt, o);
  const double mc = find(r, "albedo", "vndf", "device")->slope, qmc = find(r, "albedo", "rqmc", "device")->slope;
  INFO("slopes: vndf " << mc << ", rqmc " << qmc);
  CHECK(mc > -0.75);
  CHECK(mc < -0.3);
  CHECK(qmc < -0.8);
  CHECK(qmc < mc - 0.25);
}

TEST_CASE("a planted wrong pdf makes its estimator inconsistent with the truth", "[convergence]") {
  // uniform hemisphere weighted by π instead of 2π: the pdf of a unit disk, not of the hemisphere
  const mfv::test::PlantedKernelDir dir("convergence.cl", "real inv_pdf = est == MFV_EST_UNIFORM ? R(2.0) * MFV_PI",
                                        "real inv_pdf = est == MFV_EST_UNIFORM ? MFV_PI");
  Runtime rt = dir.runtime();
  ConvergenceOptions o;
  o.cases = {{"ggx", 0.5, 0.5}};
  o.checks = {"albedo"};
  o.estimators = {"uniform", "cosine"};
  o.min_log2 = o.max_log2 = o.ref_max_log2 = 13;
  const ConvergenceReport r = run_convergence(rt, o);
  const auto* bad = find(r, "albedo", "uniform", "device");
  INFO("planted z " << bad->z);
  CHECK_FALSE(bad->consistent);
  CHECK(std::fabs(bad->z) > 20);
  CHECK(find(r, "albedo", "cosine", "device")->consistent);
  CHECK(find(r, "albedo", "uniform", "reference")->consistent);  // the twin keeps the right pdf
}

TEST_CASE("mfv convergence rejects bad input with one line and exit 2", "[convergence][cli]") {
  for (const char* args :
       {"--estimator bogus", "--check masking", "--case phong:0.1:0.5", "--case ggx:0:0.5", "--case ggx:2:0.5",
        "--case ggx:nan:0.5", "--case ggx:0.1:0", "--case ggx:0.1:nan", "--case ggx:0.1", "--case ggx:0.1:0.5x",
        "--check d_norm --estimator vndf", "--replicates 1", "--min-log2 3", "--max-log2 40"}) {
    auto r = mfv::test::run_mfv(std::string("convergence ") + args);
    INFO(args << ": " << r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: ", 0) == 0);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  }
}

TEST_CASE("mfv convergence writes its report", "[convergence][cli]") {
  namespace fs = std::filesystem;
  const mfv::test::Scratch scratch("mfv_convergence");
  const fs::path dir = scratch.dir;
  // --out without a folder writes results/convergence under the working directory
  auto r = mfv::test::run_mfv(
      "convergence --case ggx:0.01:0.05 --check albedo --estimator uniform --estimator rqmc "
      "--estimator quadrature --min-log2 7 --max-log2 9 --ref-max-log2 8 --quad-max-order 4 "
      "--out",
      "cd " + dir.string() + " &&");
  INFO(r.out);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("target (GGX alpha = 0.01") != std::string::npos);
  const fs::path out = dir / "results" / "convergence";
  std::ifstream in(out / "convergence.json");
  const auto j = nlohmann::json::parse(in);
  CHECK(j["schema"] == "mfv-convergence/1");
  CHECK(j["series"].size() == 5);  // uniform and rqmc on device and reference, quadrature in the reference
  CHECK(j["target"]["measured"] == true);
  CHECK(j["target"]["ratio"].get<double>() > 100);
  CHECK(fs::exists(out / "convergence.md"));
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0)
    CHECK(fs::exists(out / "plots/albedo_ggx_a0.01_cos0.05.png"));
}
