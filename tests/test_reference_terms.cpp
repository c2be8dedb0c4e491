// Tests of the scalar double-precision reference terms (host/reference/).
//
// The expected values come from the seeds' closed forms, from physics
// (normalisation, limits, total internal reflection) and from known answers
// computed independently with mpmath at 50 significant digits from the exact
// double inputs.  No value here is computed by the function under test.
// This file: D and F; test_reference_terms_g.cpp: Λ, G1 and G2.
#include "reference_terms.hpp"

using namespace reference_terms_test;

// ============================ D ============================================

TEST_CASE("D_ggx and D_beckmann peak at exactly 1/(pi alpha^2) at normal incidence", "[reference][d][ggx][beckmann]") {
  const double alpha = GENERATE(0.05, 1e-3, 0.3, 1.0, 0.123456789, 2.0);
  CAPTURE(alpha);
  const double expected = 1.0 / (kPi * (alpha * alpha));
  CHECK_THAT(ref::D_ggx(1.0, alpha), WithinULP(expected, 1));
  CHECK_THAT(ref::D_beckmann(1.0, alpha), WithinULP(expected, 1));
}

TEST_CASE("D_phong peaks at (alpha_p + 2) / (2 pi) at normal incidence", "[reference][d][phong]") {
  const double alpha_p = GENERATE(0.0, 1000.0, 1e6, 1.0, 10.0, 37.5);
  CAPTURE(alpha_p);
  CHECK_THAT(ref::D_phong(1.0, alpha_p), WithinULP((alpha_p + 2.0) / (2.0 * kPi), 1));
}

TEST_CASE("D_blinn_rho peaks at 1/(pi rho^2) and equals D_phong with alpha_p = 2/rho^2 - 2", "[reference][d][blinn]") {
  const double rho = GENERATE(0.05, 0.3, 1.0, 0.7);
  const double NoH = GENERATE(1.0, 0.999, 0.9, 0.5, 0.1);
  CAPTURE(rho, NoH);
  CHECK_THAT(ref::D_blinn_rho(1.0, rho), WithinULP(1.0 / (kPi * rho * rho), 2));
  const double alpha_p = 2.0 / (rho * rho) - 2.0;
  const double expected = ref::D_phong(NoH, alpha_p);
  CHECK_THAT(ref::D_blinn_rho(NoH, rho), WithinRel(expected, 1e-12) || WithinAbs(0.0, 1e-300));
}

TEST_CASE("D_ggx matches seed 000's second GGX form and seed 002's distribution", "[reference][d][ggx]") {
  const double alpha = GENERATE(0.05, 0.3, 1.0, 1e-3);
  const double NoH = GENERATE(1e-6, 0.1, 0.5, 0.9, 0.99);
  CAPTURE(alpha, NoH);
  // seed 000: alpha² / (π ((N·H)²(alpha² − 1) + 1)²); seed 002 writes the
  // same with r = alpha².  Away from NoH = 1 this form is accurate.
  const double d = NoH * NoH * (alpha * alpha - 1.0) + 1.0;
  const double expected = alpha * alpha / (kPi * d * d);
  CHECK_THAT(ref::D_ggx(NoH, alpha), WithinRel(expected, 1e-10));
}

TEST_CASE("D_beckmann matches seed 004's Beckmann form in rho", "[reference][d][beckmann]") {
  const double rho = GENERATE(0.05, 0.3, 1.0);
  const double NoH = GENERATE(0.2, 0.5, 0.9, 0.99, 0.999999);
  CAPTURE(rho, NoH);
  // seed 004: exp(−(1 − (h·n)²) / ((h·n)² rho²)) / (π rho² (h·n)⁴)
  const double c2 = NoH * NoH;
  const double expected = std::exp(-(1.0 - c2) / (c2 * rho * rho)) / (kPi * rho * rho * c2 * c2);
  CHECK_THAT(ref::D_beckmann(NoH, rho), WithinRel(expected, 1e-9) || WithinAbs(0.0, 1e-300));
}

TEST_CASE("Every D treats NoH rounded above one as normal incidence", "[reference][d]") {
  const double NoH = GENERATE(as<double>{}, kAboveOne, 1.0000000000000002, 1.0 + 1e-12);
  for (const auto& d : all_d()) {
    CAPTURE(d.name, d.param, NoH);
    const double value = d.fn(NoH, d.param);
    CHECK_FALSE(std::isnan(value));
    CHECK(value == d.fn(1.0, d.param));
  }
}

TEST_CASE("Every D vanishes at and below the horizon and stays finite near it", "[reference][d]") {
  for (const auto& d : all_d()) {
    for (double NoH : {0.0, -0.0, -kDenormMin, -1e-300, -0.5, -1.0}) {
      CAPTURE(d.name, d.param, NoH);
      CHECK(d.fn(NoH, d.param) == 0.0);
    }
    for (double NoH : {kDenormMin, 1e-300, 1e-160, 1e-80, 1e-12}) {
      CAPTURE(d.name, d.param, NoH);
      const double value = d.fn(NoH, d.param);
      CHECK(std::isfinite(value));
      CHECK(value >= 0.0);
    }
  }
}

TEST_CASE("Every correct D integrates to one over the projected hemisphere", "[reference][d][integral]") {
  struct Case {
    const char* name;
    Scalar2 fn;
    double param;
    double width;
  };
  const auto c = GENERATE(values<Case>({
      {"D_ggx", ref::D_ggx, 0.05, 0.05},
      {"D_beckmann", ref::D_beckmann, 0.05, 0.05},
      {"D_phong", ref::D_phong, 1000.0, phong_width(1000.0)},
      {"D_blinn_rho", ref::D_blinn_rho, 0.05, 0.05},
      {"D_ggx", ref::D_ggx, 0.3, 0.3},
      {"D_ggx", ref::D_ggx, 1.0, 1.0},
      {"D_beckmann", ref::D_beckmann, 0.3, 0.3},
      {"D_beckmann", ref::D_beckmann, 1.0, 1.0},
      {"D_phong", ref::D_phong, 10.0, phong_width(10.0)},
      {"D_blinn_rho", ref::D_blinn_rho, 0.3, 0.3},
      {"D_blinn_rho", ref::D_blinn_rho, 1.0, 1.0},
  }));
  CAPTURE(c.name, c.param);
  CHECK_THAT(projected_integral(c.fn, c.param, c.width), WithinRel(1.0, 1e-9));
}

TEST_CASE("D_beckmann_ct82 as written in seed 001 integrates to pi/4, not one", "[reference][d][integral][known-bad]") {
  const double m = GENERATE(0.05, 0.3, 1.0, 0.6);
  CAPTURE(m);
  const double integral = projected_integral(ref::D_beckmann_ct82, m, m);
  CHECK_THAT(integral, WithinRel(kPi / 4.0, 1e-9));
  CHECK_THAT(integral, !WithinRel(1.0, 0.1));
}

// ============================ F ============================================

TEST_CASE("F_none is one everywhere", "[reference][f]") {
  const double VoH = GENERATE(1.0, 0.0, 0.5, -0.5, kAboveOne);
  CAPTURE(VoH);
  CHECK(ref::F_none(VoH, 0.04, 0.0) == 1.0);
}

TEST_CASE("F_schlick is f0 at normal incidence and one at grazing", "[reference][f][schlick]") {
  const double f0 = GENERATE(0.0, 1.0, 0.02, 0.04, 0.08, 0.17, 0.5, 0.95, 0.1234567);
  CAPTURE(f0);
  CHECK_THAT(ref::F_schlick(1.0, f0, 0.0), WithinULP(f0, 0));
  CHECK_THAT(ref::F_schlick(0.0, f0, 0.0), WithinULP(1.0, 0));
  // saturate: a cosine rounded outside [0, 1] is clamped, not extrapolated
  CHECK_THAT(ref::F_schlick(kAboveOne, f0, 0.0), WithinULP(f0, 0));
  CHECK_THAT(ref::F_schlick(-1e-3, f0, 0.0), WithinULP(1.0, 0));
  // mid angle: f0 + (1 − f0) / 32
  CHECK_THAT(ref::F_schlick(0.5, f0, 0.0), WithinRel(f0 + (1.0 - f0) / 32.0, 1e-15));
}

TEST_CASE("F_dielectric at normal incidence is ((eta - 1)/(eta + 1))^2", "[reference][f][dielectric]") {
  const double eta = GENERATE(1.5, 1.33, 2.4, 1.0 / 1.5, 1.0001, 10.0);
  CAPTURE(eta);
  const double r = (eta - 1.0) / (eta + 1.0);
  CHECK_THAT(ref::F_dielectric(1.0, eta, 0.0), WithinRel(r * r, 1e-12));
  CHECK_THAT(ref::F_dielectric(kAboveOne, eta, 0.0), WithinRel(r * r, 1e-12));
}

TEST_CASE("F_dielectric is zero at every angle when eta = 1", "[reference][f][dielectric]") {
  const double VoH = GENERATE(1e-8, 1e-150, 1e-3, 0.1, 0.5, 0.9, kBelowOne, 1.0);
  CAPTURE(VoH);
  CHECK_THAT(ref::F_dielectric(VoH, 1.0, 0.0), WithinAbs(0.0, 1e-15));
}

TEST_CASE("F_dielectric with eta < 1 totally reflects beyond the critical angle", "[reference][f][dielectric]") {
  const double eta = GENERATE(1.0 / 1.5, 1.0 / 1.33, 1.0 / 2.4, 0.99);
  const double cos_critical = std::sqrt(1.0 - eta * eta);
  CAPTURE(eta, cos_critical);
  for (double VoH : {0.0, 1e-9, 0.5 * cos_critical, 0.999 * cos_critical}) {
    CAPTURE(VoH);
    CHECK(ref::F_dielectric(VoH, eta, 0.0) == 1.0);
  }
  for (double VoH : {1.001 * cos_critical, 0.5 + 0.5 * cos_critical, 1.0}) {
    CAPTURE(VoH);
    const double F = ref::F_dielectric(VoH, eta, 0.0);
    CHECK(F < 1.0);
    CHECK(F >= 0.0);
  }
}

TEST_CASE("F_dielectric agrees with seed 000's exact closed form", "[reference][f][dielectric]") {
  const double eta = GENERATE(1.5, 1.33, 2.4, 1.0 / 1.5, 1.2, 4.0);
  const double VoH = GENERATE(1.0, 0.95, 0.8, 0.5, 0.3, 0.1, 0.01);
  CAPTURE(eta, VoH);
  if (eta * eta - 1.0 + VoH * VoH <= 0.0) return;  // TIR: the closed form has no real g
  CHECK_THAT(ref::F_dielectric(VoH, eta, 0.0), WithinRel(fresnel_seed000(VoH, eta), 1e-11));
}

TEST_CASE("F_dielectric and F_conductor match 50-digit known answers", "[reference][f]") {
  struct Case {
    double VoH, n, k, expected;
  };
  SECTION("dielectric") {
    const auto c = GENERATE(values<Case>({
        {0.95, 1.0001, 0.0, 2.5289185896526460427e-9},
        {0.5, 1.5, 0.0, 0.089186712802212783115},
        {0.1, 1.33, 0.0, 0.53898975789199973203},
        {0.8, 1.0 / 1.5, 0.0, 0.11414110022135391524},
        {0.3, 2.4, 0.0, 0.29624640493138528644},
    }));
    CAPTURE(c.VoH, c.n);
    CHECK_THAT(ref::F_dielectric(c.VoH, c.n, 0.0), WithinRel(c.expected, 1e-10));
  }
  SECTION("conductor") {
    const auto c = GENERATE(values<Case>({
        {0.01, 0.2, 3.4, 0.99557412724877962337},
        {0.5, 0.2, 3.4, 0.93253425667753289288},
        {0.1, 1.2, 7.3, 0.85975412293064022016},
        {0.9, 0.05, 0.1, 0.94214893984523313096},
        {0.7, 2.0, 0.5, 0.14784840129396902317},
    }));
    CAPTURE(c.VoH, c.n, c.k);
    CHECK_THAT(ref::F_conductor(c.VoH, c.n, c.k), WithinRel(c.expected, 1e-13));
  }
}

TEST_CASE("F_conductor with k = 0 equals F_dielectric with eta = n", "[reference][f][conductor]") {
  const double n = GENERATE(1.5, 1.33, 2.4, 1.0 / 1.5, 1.0, 1.0 / 2.4);
  const double VoH = GENERATE(1.0, 0.0, 1e-6, 0.01, 0.1, 0.3, 0.5, 0.8, 0.99);
  CAPTURE(n, VoH);
  const double expected = ref::F_dielectric(VoH, n, 0.0);
  CHECK_THAT(ref::F_conductor(VoH, n, 0.0), WithinRel(expected, 1e-12) || WithinAbs(0.0, 1e-15));
}

TEST_CASE("F_conductor at normal incidence is ((n-1)^2 + k^2)/((n+1)^2 + k^2)", "[reference][f][conductor]") {
  struct Nk {
    double n, k;
  };
  const auto c =
      GENERATE(values<Nk>({{0.2, 3.4}, {1.2, 7.3}, {0.05, 0.1}, {2.5, 0.0}, {1.0, 1.0}, {1.0, 0.0}, {0.01, 20.0}}));
  CAPTURE(c.n, c.k);
  const double expected = ((c.n - 1.0) * (c.n - 1.0) + c.k * c.k) / ((c.n + 1.0) * (c.n + 1.0) + c.k * c.k);
  CHECK_THAT(ref::F_conductor(1.0, c.n, c.k), WithinRel(expected, 1e-13) || WithinAbs(0.0, 1e-300));
}

TEST_CASE("F_conductor agrees with Born and Wolf's real form and lies in [0, 1]", "[reference][f][conductor]") {
  const double n = GENERATE(0.05, 0.2, 0.5, 1.2, 2.5);
  const double k = GENERATE(0.01, 0.5, 3.4, 7.3);
  CAPTURE(n, k);
  for (double VoH : {0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.999}) {
    CAPTURE(VoH);
    const double F = ref::F_conductor(VoH, n, k);
    CHECK_THAT(F, WithinRel(fresnel_conductor_born_wolf(VoH, n, k), 1e-9));
    CHECK(F >= 0.0);
    CHECK(F <= 1.0);
  }
  CHECK(ref::F_conductor(0.0, n, k) == 1.0);  // grazing
}
