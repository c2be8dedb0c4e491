// Anisotropic GGX and Beckmann (issue 8): the reference terms against
// quadrature (normalisation, projected area = cos_o (1 + Λ(α(φ_o)))), the
// isotropic limit in the reference and in the kernels, edge cases, the
// kernel/reference agreement, and mfv run's d_norm and masking passing on
// the correct terms and failing on planted defects.
#include "catalog/catalog.hpp"
#include "checks/suite.hpp"
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "numeric/quadrature.hpp"
#include "reference/reference.hpp"
#include "runtime/dispatch.hpp"
#include "suite_verdicts.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <functional>
#include <limits>

using namespace mfv;

namespace {

glm::dvec3 dir(double cos_theta, double phi) {
  double s = std::sqrt((1 - cos_theta) * (1 + cos_theta));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

// ∫ over the upper hemisphere of f(m) dm by Gauss-Legendre in the slope
// radius r = tanθ (mapped from t in [0, 1) by r = t/(1-t), geometric panels
// towards the peak at r = 0) and in φ. Smooth for the widths used here.
double hemisphere(const std::function<double(const glm::dvec3&)>& f) {
  GaussRule g = gauss_legendre(24);
  auto panels = geometric_panels(1e-4, 6);
  double sum = 0;
  const int n_phi = 256;
  for (size_t p = 0; p + 1 < panels.size(); ++p) {
    double a = panels[p], b = panels[p + 1];
    for (size_t i = 0; i < g.x.size(); ++i) {
      double t = 0.5 * (a + b) + 0.5 * (b - a) * g.x[i];
      double r = t / (1 - t), dr = 1 / ((1 - t) * (1 - t));
      double c = 1 / std::sqrt(1 + r * r);
      // dm = sinθ dθ dφ = (r / (1 + r²)^{3/2}) dr dφ
      double jac = r * c * c * c * dr * 0.5 * (b - a) * g.w[i];
      for (int k = 0; k < n_phi; ++k) {
        double phi = 2 * M_PI * (k + 0.5) / n_phi;
        sum += f({r * c * std::cos(phi), r * c * std::sin(phi), c}) * jac * (2 * M_PI / n_phi);
      }
    }
  }
  return sum;
}

// ULP of a float at |x|
double float_ulp(double x) {
  int e;
  std::frexp(std::max(std::fabs(x), double(std::numeric_limits<float>::min())), &e);
  return std::ldexp(1.0, e - 24);
}

SuiteOptions only(std::vector<std::string> checks, std::vector<std::string> models, double scale) {
  SuiteOptions o;
  o.checks = std::move(checks);
  o.models = std::move(models);
  o.seed = 11;
  o.scale = scale;
  return o;
}

using mfv::test::group;
using mfv::test::verdict_of;

}  // namespace

TEST_CASE("Anisotropic reference D and G1 reduce to the isotropic terms at alpha_x = alpha_y", "[reference][aniso]") {
  for (double a : {1e-4, 0.05, 0.3, 1.0, 3.0})
    for (double c : {1.0, 0.999999, 0.9, 0.5, 0.1, 1e-3})
      for (double phi : {0.0, 0.7, M_PI / 2, 2.5}) {
        glm::dvec3 m = dir(c, phi);
        CAPTURE(a, c, phi);
        CHECK(ref::D_ggx_aniso(m, a, a) == Approx(ref::D_ggx(c, a)).epsilon(1e-12));
        CHECK(ref::D_beckmann_aniso(m, a, a) == Approx(ref::D_beckmann(c, a)).epsilon(1e-12).margin(1e-300));
        CHECK(ref::G1_smith_ggx_aniso(m, a, a) == Approx(ref::G1_smith_ggx(c, a)).epsilon(1e-12));
        CHECK(ref::G1_smith_beckmann_aniso(m, a, a) == Approx(ref::G1_smith_beckmann(c, a)).epsilon(1e-12));
      }
}

TEST_CASE("Anisotropic reference terms: the normal, the horizon, tan = 0 and widths near zero", "[reference][aniso]") {
  // m = n: 1 / (π ax ay), also at widths near zero
  for (auto [ax, ay] : {std::pair{0.05, 0.5}, {1e-7, 1e-3}, {10.0, 1e-7}}) {
    CHECK(ref::D_ggx_aniso({0, 0, 1}, ax, ay) == Approx(1 / (M_PI * ax * ay)).epsilon(1e-15));
    CHECK(ref::D_beckmann_aniso({0, 0, 1}, ax, ay) == Approx(1 / (M_PI * ax * ay)).epsilon(1e-15));
    CHECK(ref::G1_smith_ggx_aniso({0, 0, 1}, ax, ay) == 1.0);  // tanθ = 0
    CHECK(ref::G1_smith_beckmann_aniso({0, 0, 1}, ax, ay) == 1.0);
    CHECK(ref::G1_smith_ggx_aniso({1, 0, 0}, ax, ay) == 0.0);  // grazing: fully masked
    CHECK(ref::G1_smith_beckmann_aniso({0, 1, 0}, ax, ay) == 0.0);
  }
  CHECK(ref::D_ggx_aniso({1, 0, 0}, 0.05, 0.5) == 0.0);  // below and at the horizon: χ+(m·n)
  CHECK(ref::D_beckmann_aniso({0.6, 0, -0.8}, 0.05, 0.5) == 0.0);
  // the projected width: alpha_x along t, alpha_y along b, sqrt of the mean square on the diagonal
  CHECK(ref::alpha_projected(dir(0.5, 0.0), 0.05, 0.5) == Approx(0.05));
  CHECK(ref::alpha_projected(dir(0.5, M_PI / 2), 0.05, 0.5) == Approx(0.5));
  CHECK(ref::alpha_projected(dir(0.5, M_PI / 4), 0.05, 0.5) == Approx(std::sqrt(0.5 * (0.05 * 0.05 + 0.25))));
}

TEST_CASE("Anisotropic D integrates to one and its projected area is cos_o (1 + Lambda(alpha(phi_o))), by quadrature",
          "[reference][aniso]") {
  const double ax = 0.2, ay = 0.6;
  using DFn = double (*)(const glm::dvec3&, double, double);
  using LFn = double (*)(const glm::dvec3&, double, double);
  struct Family {
    const char* name;
    DFn d;
    LFn lambda;
    double (*lambda_iso)(double, double);
  };
  for (Family f : {Family{"ggx", ref::D_ggx_aniso, ref::Lambda_ggx_aniso, ref::Lambda_ggx},
                   Family{"beckmann", ref::D_beckmann_aniso, ref::Lambda_beckmann_aniso, ref::Lambda_beckmann}}) {
    CAPTURE(f.name);
    double norm = hemisphere([&](const glm::dvec3& m) { return f.d(m, ax, ay) * m.z; });
    CHECK(norm == Approx(1.0).epsilon(1e-7));
    // planted: normalised by 1/(π ax²) instead of 1/(π ax ay) integrates to ay/ax
    double bad = hemisphere([&](const glm::dvec3& m) { return f.d(m, ax, ay) * (ay / ax) * m.z; });
    CHECK(std::fabs(bad - 1.0) > 1.0);
    for (double phi : {0.0, M_PI / 2, M_PI / 4})
      for (double co : {0.9, 0.3, 0.05}) {
        CAPTURE(phi, co);
        glm::dvec3 o = dir(co, phi);
        double area = hemisphere([&](const glm::dvec3& m) { return f.d(m, ax, ay) * std::max(0.0, glm::dot(o, m)); });
        double lambda = f.lambda(o, ax, ay);
        CHECK(area / co == Approx(1.0 + lambda).epsilon(2e-6));
        // the width alpha_x alone (no azimuth) misses it wherever phi_o != 0
        double wrong = 1.0 + f.lambda_iso(co, ax);
        if (phi != 0.0 && co < 0.5) CHECK(std::fabs(area / co - wrong) > 1e-2 * (area / co));
      }
  }
}

TEST_CASE("Anisotropic kernel terms equal the isotropic kernel terms at alpha_x = alpha_y to float precision",
          "[device][aniso]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  TermSelection sel;
  sel.d = {&find_term("ggx"), &find_term("beckmann"), &find_term("aniso_ggx"), &find_term("aniso_beckmann")};
  sel.g = {&find_term("smith_ggx"), &find_term("smith_beckmann"), &find_term("smith_aniso_ggx"),
           &find_term("smith_aniso_beckmann")};
  sel.g1 = true;
  // out[8 i + k]: D and G1 of both families, isotropic and anisotropic, at point i
  std::string src =
      fmt::format(R"(
__kernel void iso_limit(__global const float* in, __global float* out) {{
  size_t i = get_global_id(0);
  real c = in[4 * i], phi = in[4 * i + 1], a = in[4 * i + 2];
  real s = sqrt(sin2_from_cos(c)), hx = s * cos(phi), hy = s * sin(phi), s2 = hx * hx + hy * hy;
  out[8 * i + 0] = eval_D({0}, c, s2, a);
  out[8 * i + 1] = eval_D_aniso({1}, c, s2, hx, hy, a, a);
  out[8 * i + 2] = eval_D({2}, c, s2, a);
  out[8 * i + 3] = eval_D_aniso({3}, c, s2, hx, hy, a, a);
  out[8 * i + 4] = eval_G1({4}, c, a);
  out[8 * i + 5] = eval_G1_aniso({5}, c, hx, hy, a, a);
  out[8 * i + 6] = eval_G1({6}, c, a);
  out[8 * i + 7] = eval_G1_aniso({7}, c, hx, hy, a, a);
}}
)",
                  term_index(*sel.d[0]), term_index(*sel.d[2]), term_index(*sel.d[1]), term_index(*sel.d[3]),
                  term_index(*sel.g[0]), term_index(*sel.g[2]), term_index(*sel.g[1]), term_index(*sel.g[3]));
  cl::Program prog = rt->build({"common.cl", "terms_d.cl", "terms_g.cl", "terms_f.cl"}, {}, generate_dispatch(sel), "",
                               {{"iso_limit.cl", src, ""}});
  std::vector<float> in;
  for (float a : {1e-6f, 1e-3f, 0.05f, 0.3f, 1.0f, 4.0f})
    for (float c : {1.0f, 0.9999999f, 0.99f, 0.7f, 0.3f, 0.02f, 1e-5f})
      for (float phi : {0.0f, 0.4f, 1.5707964f, 2.3f, 4.0f}) in.insert(in.end(), {c, phi, a, 0.0f});
  size_t n = in.size() / 4;
  cl::Buffer ib(rt->context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, in.size() * sizeof(float), in.data());
  cl::Buffer ob(rt->context(), CL_MEM_WRITE_ONLY, 8 * n * sizeof(float));
  cl::Kernel k(prog, "iso_limit");
  k.setArg(0, ib);
  k.setArg(1, ob);
  rt->queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n));
  std::vector<float> out(8 * n);
  rt->queue().enqueueReadBuffer(ob, CL_TRUE, 0, out.size() * sizeof(float), out.data());
  double worst = 0;
  for (size_t i = 0; i < n; ++i)
    for (int j = 0; j < 8; j += 2) {
      float iso = out[8 * i + j], an = out[8 * i + j + 1];
      CAPTURE(in[4 * i], in[4 * i + 1], in[4 * i + 2], j, iso, an);
      REQUIRE(std::isfinite(iso));
      REQUIRE(std::isfinite(an));
      double ulps = std::fabs(double(iso) - double(an)) / float_ulp(iso);
      worst = std::max(worst, ulps);
      // a few roundings apart: (hx/a)² + (hy/a)² against (hx² + hy²)/a²; Beckmann's
      // exp(-x) turns a relative rounding of x into x times that in D
      double c = in[4 * i], a = in[4 * i + 2], x = j == 2 ? (1 - c * c) / (c * c * a * a) : 0.0;
      CHECK(ulps <= 8 + 4 * x);
    }
  WARN("isotropic limit, kernel: worst " << worst << " ulps");
}

TEST_CASE("d_norm and masking pass on the anisotropic terms and fail on planted defects", "[device][aniso][planted]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  SuiteReport good = run_suite(*rt, only({"d_norm", "masking"}, {"aniso_"}, 0.25));
  for (const char* d : {"aniso_ggx", "aniso_beckmann"}) CHECK(verdict_of(good, "d_norm", d) == Verdict::Pass);
  CHECK(verdict_of(good, "masking", "aniso_ggx/smith_aniso_ggx") == Verdict::Pass);
  CHECK(verdict_of(good, "masking", "aniso_beckmann/smith_aniso_beckmann") == Verdict::Pass);
  // the isotropic G1 at alpha_x is right for views along t only: expected to fail elsewhere
  CHECK(verdict_of(good, "masking", "aniso_ggx/smith_ggx") == Verdict::XFail);
  CHECK(verdict_of(good, "masking", "aniso_beckmann/smith_beckmann") == Verdict::XFail);
  CHECK(good.gate_ok());

  // D normalised by 1/(π ax²) instead of 1/(π ax ay)
  test::check_planted_fails("terms_d.cl", "return R(1.0) / (MFV_PI * ax * ay * k * k);",
                            "return R(1.0) / (MFV_PI * ax * ax * k * k);", only({"d_norm"}, {"aniso_ggx"}, 0.25),
                            "d_norm", "aniso_ggx");
  // G1 with alpha_x for every azimuth instead of alpha(phi_o)
  test::check_planted_fails(
      "terms_g.cl", "real tx = ax * vx, ty = ay * vy;", "real tx = ax * vx, ty = ax * vy;",
      only({"masking"}, {"aniso_ggx/smith_aniso_ggx"}, 0.25), "masking", "aniso_ggx/smith_aniso_ggx");
}
