// KHR_materials_sheen (issue 21): the Charlie sheen D and its visibility as
// catalog terms, the E_sheen table of mfv energy, the gltf_sheen layering, and
// the planted defects the checks must catch.
#include "catalog/models.hpp"
#include "checks/suite.hpp"
#include "device_fixture.hpp"
#include "numeric/hemisphere_quadrature.hpp"
#include "reference/model_gltf.hpp"
#include "reference/reference.hpp"
#include "suite_verdicts.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace mfv;
using mfv::test::verdict_of;

namespace {

// E_sheen(mu, alpha) = ∫ D V (n·l) dl of the double reference, by product Gauss-Legendre over half vectors.
double sheen_albedo_quadrature(double mu, double alpha) {
  const glm::dvec3 v(std::sqrt((1.0 - mu) * (1.0 + mu)), 0.0, mu);
  auto f = [&](const glm::dvec3& l) {
    const glm::dvec3 s = l + v;
    const double len = std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
    const double NoH = s.z / len, sin2H = (s.x * s.x + s.y * s.y) / (len * len), VoH = 0.5 * len;
    return ref::D_charlie_cs(NoH * NoH, sin2H, alpha) * ref::G_charlie_sheen(l.z, v.z, NoH, VoH, alpha) / (4.0 * v.z);
  };
  return integrate_reflected(f, v, ProductRule{12, 4, 8, 1e-9}).value;
}

// The verdict of `check` on `model` with one line of a kernel file replaced.
Verdict planted_verdict(const std::string& file, const std::string& from, const std::string& to,
                        const std::string& check, const std::string& model) {
  SuiteOptions o;
  o.checks = {check};
  o.models = {model};
  o.reference_samples = 0;  // the plant is in the kernel only: test the statistics alone
  return verdict_of(test::planted_suite(file, from, to, o), check, model);
}

// E(cos_l) = ∫ f(l, v) (n·v) dv of a whole model's double reference, by a
// midpoint rule in (cos θ_v, φ_v) (dv = d cos θ dφ): 400 x 800 cells.
double model_albedo_midpoint(double (*f)(const glm::dvec3&, const glm::dvec3&, const double*), const double* p,
                             double cos_l) {
  const glm::dvec3 l(std::sqrt((1.0 - cos_l) * (1.0 + cos_l)), 0.0, cos_l);
  const int nt = 400, np = 800;
  double sum = 0;
  for (int i = 0; i < nt; ++i) {
    const double ct = (i + 0.5) / nt, st = std::sqrt((1.0 - ct) * (1.0 + ct));
    for (int j = 0; j < np; ++j) {
      const double phi = 2.0 * M_PI * (j + 0.5) / np;
      sum += f(l, glm::dvec3(st * std::cos(phi), st * std::sin(phi), ct), p) * ct;
    }
  }
  return sum * 2.0 * M_PI / (double(nt) * np);
}

}  // namespace

TEST_CASE("gltf_sheen gains energy at grazing light through its clamped albedo table (why its energy may fail)",
          "[reference][sheen][models]") {
  // the red sheen chrome's red channel: base chrome alpha 0.25, sheen 1 at sheenRoughness 0.3
  const double p[7] = {0.25, 1.0, 1.0, 0.04, 0.3, 1.0, 0.0};
  // the table reads E_sheen(1/32) below mu = 1/32 (0.752) where the lobe reflects ~0.81
  CHECK(ref::sheen_table_side() == 16);
  CHECK(ref::sheen_albedo_table(0.006, 0.3) == Approx(ref::sheen_albedo_table(1.0 / 32, 0.3)).epsilon(1e-12));
  CHECK(ref::sheen_albedo_table(0.006, 0.3) < sheen_albedo_quadrature(0.006, 0.3) - 0.04);
  // so the layered model reflects more than it receives at grazing light, and less away from it
  const double grazing = model_albedo_midpoint(ref::model_gltf_sheen, p, 0.00599484);
  const double away = model_albedo_midpoint(ref::model_gltf_sheen, p, 0.05);
  INFO("E(0.006) = " << grazing << ", E(0.05) = " << away);
  CHECK(grazing > 1.04);
  CHECK(away < 0.99);
}

TEST_CASE("The Charlie D integrates to one and its visibility is the height-correlated form", "[reference][d][sheen]") {
  for (double alpha : {1e-3, 0.01, 0.1, 0.5, 1.0}) {
    CAPTURE(alpha);
    auto g = [&](const glm::dvec3& m) { return ref::D_charlie(m.z, alpha) * m.z; };
    CHECK(integrate_normals(g, ProductRule{}).value == Approx(1.0).epsilon(1e-9));
    // Estevez and Kulla 2017 eq. 2 at one point: sin²θ = 0.75
    CHECK(ref::D_charlie(0.5, alpha) == Approx((2.0 + 1.0 / alpha) * std::pow(0.75, 0.5 / alpha) / (2.0 * M_PI)));
    CHECK(ref::D_charlie(0.0, alpha) == 0.0);
    CHECK(ref::D_charlie(1.0 + 1e-12, alpha) == 0.0);  // no facet at the normal
  }
  // the spec's V = 1 / ((1 + Λ(v) + Λ(l)) 4 (n·v)(n·l)), returned as G
  const double L = ref::Lambda_charlie(0.3, 0.4), V = ref::Lambda_charlie(0.8, 0.4);
  CHECK(ref::G_charlie_sheen(0.3, 0.8, 0.9, 0.7, 0.4) == Approx(1.0 / (1.0 + L + V)));
  CHECK(ref::G1_charlie(0.3, 0.4) == Approx(1.0 / (1.0 + L)));
  CHECK(ref::G_charlie_sheen(0.0, 0.8, 0.9, 0.7, 0.4) == 0.0);
}

TEST_CASE("The committed E_sheen table is the quadrature of the reference sheen lobe", "[reference][sheen][energy]") {
  // The table (kernels/model_gltf.cl, from mfv energy) against an independent
  // deterministic quadrature: every grid value within 5 of the table's
  // standard errors (<= 1e-3, see its header) plus the rule's error (< 1e-4).
  const int n = ref::sheen_table_side();
  REQUIRE(n * n == int(ref::sheen_table_values().size()));
  for (int j = 0; j < n; j += 5)
    for (int m = 0; m < n; m += 3) {
      const double mu = (m + 0.5) / n, alpha = std::pow(10.0, -3.0 + 3.0 * j / (n - 1));
      CAPTURE(mu, alpha);
      CHECK(ref::sheen_albedo_table(mu, alpha) == Approx(sheen_albedo_quadrature(mu, alpha)).margin(5e-3));
    }
}

TEST_CASE("mfv run checks the Charlie lobe: d_norm, masking, furnace, and gltf_sheen's energy and reciprocity",
          "[device][suite][sheen]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  SuiteOptions opt;
  opt.checks = {"d_norm", "masking", "furnace", "energy", "reciprocity"};
  opt.models = {"charlie", "gltf_sheen["};
  SuiteReport rep = run_suite(*rt, opt);
  for (auto& g : rep.groups) {
    CAPTURE(g.check, g.model, g.reason);
    CHECK((g.verdict == Verdict::Pass || g.verdict == Verdict::XFail));
  }
  CHECK(verdict_of(rep, "d_norm", "charlie") == Verdict::Pass);
  // the fitted visibility under-masks at grazing for small widths: derived expected failures (docs/scenes.md)
  CHECK(verdict_of(rep, "furnace", "charlie/charlie_sheen/none") == Verdict::XFail);
  CHECK(verdict_of(rep, "masking", "charlie/charlie_sheen") == Verdict::XFail);
  CHECK(verdict_of(rep, "energy", "gltf_sheen[velvet,s=1,sr=0.01]") != Verdict::Fail);  // may fail (the catalog)
  // gains 5.7 % at cos_l = 0.006 through its clamped table (the test above): may fail
  CHECK(verdict_of(rep, "energy", "gltf_sheen[red sheen chrome,R,sr=0.3]") != Verdict::Fail);
  CHECK(rep.gate_ok());
}

TEST_CASE("A Charlie D without its normalisation fails d_norm", "[device][suite][sheen][planted]") {
  if (!test::device_runtime()) return;
  CHECK(planted_verdict("terms_d.cl", "return (R(2.0) + R(1.0) / alpha) * (R(0.5) * MFV_INV_PI)",
                        "return (R(0.5) * MFV_INV_PI)", "d_norm", "charlie") == Verdict::Fail);
}

TEST_CASE("gltf_sheen's albedo scaling by min instead of max, or none, fails energy",
          "[device][suite][sheen][planted]") {
  if (!test::device_runtime()) return;
  const std::string kRed = "gltf_sheen[red sheen chrome,R,sr=0.3]", kLine = "real max3 = max(sheen, p[6]);";
  // min3 of a red sheen is 0; and no albedo scaling at all. The case may fail
  // as it is (its clamped table gains 5.7 % at cos_l = 0.006), so the plants
  // are told apart by size: the unscaled base adds ~0.8 at grazing light.
  for (const char* plant : {"real max3 = min(sheen, p[6]);", "real max3 = R(0.0);"}) {
    CAPTURE(plant);
    SuiteOptions o;
    o.checks = {"energy"};
    o.models = {kRed};
    o.reference_samples = 0;
    const SuiteReport rep = test::planted_suite("model_gltf.cl", kLine, plant, o);
    const GroupResult* g = test::group(rep, "energy", kRed);
    REQUIRE(g != nullptr);
    CHECK(g->verdict == Verdict::XFail);
    CHECK(rep.points[g->worst].estimate > 1.3);
  }
}

TEST_CASE("gltf_clearcoat_aniso checks the coat and the anisotropic base: a defect in either lobe fails energy",
          "[device][suite][clearcoat][planted]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  const std::string kCase = "gltf_clearcoat_aniso[coated aniso chrome,r=0.5,s=0.8,ccr=0.3]";
  SuiteOptions opt;
  opt.checks = {"energy", "reciprocity"};
  opt.models = {"gltf_clearcoat_aniso["};
  SuiteReport rep = run_suite(*rt, opt);
  CHECK(verdict_of(rep, "energy", kCase) == Verdict::Pass);
  CHECK(verdict_of(rep, "reciprocity", kCase) == Verdict::XFail);  // the coat's Fresnel at n.V (the spec)
  CHECK(rep.gate_ok());
  // the base: the anisotropic D normalised by alpha_b² instead of alpha_t alpha_b (x2.9)
  CHECK(planted_verdict("model_gltf.cl", "D_ggx_aniso(h.z, h.x, h.y, alpha, alpha_b) * G",
                        "D_ggx_aniso(h.z, h.x, h.y, alpha, alpha_b) * (alpha / alpha_b) * G", "energy",
                        kCase) == Verdict::Fail);
  // the coat: its D four times too large
  CHECK(planted_verdict("model_gltf.cl", "over_4_cosines(D_ggx(h.z, s2, ca) *",
                        "over_4_cosines(R(4.0) * D_ggx(h.z, s2, ca) *", "energy", kCase) == Verdict::Fail);
}
