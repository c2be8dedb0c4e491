// The anisotropic fast paths of Integrator::run (kernels/aniso_values.cl:
// d_norm_aniso_values + sum_pairs, masking_aniso_values and
// albedo_aniso_values + sum_values) take the samples the general `integrate`
// kernel takes and give the same estimates, in a program of several terms
// (the select-form eval_D_aniso / eval_G_aniso / eval_G1_aniso), over strong
// anisotropy both ways, near-zero widths, grazing views and view azimuths
// along t, along b and between. A kernel that took other samples than
// `integrate` is caught (planted below).
#include "catalog/catalog.hpp"
#include "checks/integrate.hpp"
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "runtime/dispatch.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <string>

using namespace mfv;

namespace {

TermSelection aniso_selection() {
  TermSelection sel;
  sel.d = {&find_term("aniso_ggx"), &find_term("aniso_beckmann"), &find_term("ggx")};
  sel.g = {&find_term("smith_aniso_ggx"), &find_term("smith_aniso_beckmann"), &find_term("smith_ggx"),
           &find_term("smith_beckmann")};
  sel.f = {&find_term("none"), &find_term("schlick")};
  return sel;
}

IntegralSpec aniso(IntegralKind kind, const char* d, const char* g, const char* f, double ax, double ay, double co,
                   double phi) {
  MicrofacetIntegral m;
  m.kind = kind;
  m.d = &find_term(d);
  m.g = g ? &find_term(g) : nullptr;
  m.f = f ? &find_term(f) : nullptr;
  m.pd = m.pg = m.width = ax;
  m.pd2 = m.pg2 = ay;
  m.f0 = 0.04;
  m.cos_o = co, m.phi_o = phi;
  return spec_of(m);
}

// d_norm, masking and furnace albedo integrals of both anisotropic families
std::vector<IntegralSpec> aniso_specs() {
  struct View {
    double co, phi;
  };
  const std::vector<std::pair<double, double>> widths = {{0.05, 0.5}, {1.0, 0.1}, {1e-3, 0.3}};
  const std::vector<View> views = {{0.3, 2.5}, {1e-3, M_PI / 2}, {0.95, 0.0}, {0.6, M_PI / 4}};
  std::vector<IntegralSpec> specs;
  for (auto [d, g] : {std::pair<const char*, const char*>{"aniso_ggx", "smith_aniso_ggx"},
                      {"aniso_beckmann", "smith_aniso_beckmann"}})
    for (auto [ax, ay] : widths) {
      specs.push_back(aniso(IntegralKind::DNorm, d, nullptr, nullptr, ax, ay, 1.0, 0.0));
      for (auto v : views) {
        specs.push_back(aniso(IntegralKind::Masking, d, g, nullptr, ax, ay, v.co, v.phi));
        specs.push_back(aniso(IntegralKind::Masking, d, "smith_beckmann", nullptr, ax, ay, v.co, v.phi));
        specs.push_back(aniso(IntegralKind::Albedo, d, g, "none", ax, ay, v.co, v.phi));
        specs.push_back(aniso(IntegralKind::Albedo, d, g, "schlick", ax, ay, v.co, v.phi));
      }
    }
  for (size_t i = 0; i < specs.size(); ++i) specs[i].stream = uint32_t(i);
  return specs;
}

// The largest relative difference of the means and standard errors of the
// fast path and `integrate` over `specs`.
struct Difference {
  double mean = 0, stderr_ = 0;
};
Difference fast_against_general(Runtime& rt, const std::vector<IntegralSpec>& specs) {
  Integrator in(rt, aniso_selection());
  in.set_albedo_fast_path(true);
  const auto fast = in.run(specs, 40000, 11);
  in.set_albedo_fast_path(false);
  const auto general = in.run(specs, 40000, 11);
  REQUIRE(fast.size() == general.size());
  Difference worst;
  for (size_t i = 0; i < fast.size(); ++i) {
    INFO("integral " << i << " (check " << specs[i].check << "): fast " << fast[i].mean << " +- " << fast[i].stderr_
                     << ", general " << general[i].mean << " +- " << general[i].stderr_);
    REQUIRE(fast[i].samples == general[i].samples);
    REQUIRE(std::isfinite(general[i].mean));
    worst.mean = std::max(worst.mean, std::fabs(fast[i].mean - general[i].mean) / std::max(1.0, general[i].mean));
    worst.stderr_ =
        std::max(worst.stderr_, std::fabs(fast[i].stderr_ - general[i].stderr_) / std::max(1e-6, general[i].stderr_));
  }
  return worst;
}

}  // namespace

TEST_CASE("the anisotropic fast paths give the general kernel's estimates", "[integrate][device][aniso]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  // the same float samples, summed in double in another order (as
  // tests/test_integrate.cpp): 40000 float values of at most ~1e3 each sum
  // with relative rounding far below 1e-12 of the mean
  const Difference d = fast_against_general(*rt, aniso_specs());
  CHECK(d.mean <= 1e-12);
  CHECK(d.stderr_ <= 1e-9);
}

TEST_CASE("the anisotropic fast paths are checked against integrate (planted)", "[integrate][device][aniso][planted]") {
  if (!test::device_runtime()) return;
  // each kernel planted to store its sample 1.001 times: the comparison above
  // must see it, and so each kernel is the one Integrator::run launches
  for (const char* kernel : {"d_norm_aniso_values", "masking_aniso_values", "albedo_aniso_values"}) {
    CAPTURE(kernel);
    const std::string at = std::string("MFV_SAMPLE_VALUES(") + kernel + ",";
    test::PlantedKernelDir dir("aniso_values.cl", at, at + " 1.001f * ");
    Runtime rt = dir.runtime();
    const Difference d = fast_against_general(rt, aniso_specs());
    CHECK(d.mean > 1e-4);
  }
}
