// Tests of the scalar double-precision reference terms (host/reference/).
//
// The expected values come from the seeds' closed forms, from physics
// (normalisation, limits, total internal reflection) and from known answers
// computed independently with mpmath at 50 significant digits from the exact
// double inputs.  No value here is computed by the function under test.
// This file: Λ, G1 and G2; test_reference_terms.cpp: D and F.
#include "reference_terms.hpp"

using namespace reference_terms_test;

// ============================ Λ and G1 =====================================

TEST_CASE("Lambda_beckmann and Lambda_ggx match 50-digit known answers", "[reference][g][lambda][beckmann][ggx]") {
  struct Case {
    Scalar2 fn;
    const char* name;
    double NoV, alpha, expected, rel;
  };
  const auto c = GENERATE(values<Case>({
      // far tail: erf(a) − 1 would cancel to 0; −erfc(a) keeps it
      // (here −erfc(a)/2 and exp(−a²)/(2a√π) agree to 1/(2a²) ≈ 1e-3, so the
      //  half-ULP rounding of a² (a² ≈ 547) is amplified to ~7e-11)
      {ref::Lambda_beckmann, "Lambda_beckmann", 0.99, 0.3, 2.3947631422930436116e-243, 2e-10},
      {ref::Lambda_beckmann, "Lambda_beckmann", 0.7, 0.3, 8.2662951755159191814e-8, 1e-12},
      {ref::Lambda_beckmann, "Lambda_beckmann", 0.5, 0.3, 3.6280264080609828393e-4, 1e-13},
      {ref::Lambda_beckmann, "Lambda_beckmann", 0.2, 0.5, 0.30305753634283684599, 1e-13},
      {ref::Lambda_beckmann, "Lambda_beckmann", 0.05, 1.0, 5.1489555599470455614, 1e-13},
      // near normal incidence: (−1 + sqrt(1 + x))/2 would cancel
      {ref::Lambda_ggx, "Lambda_ggx", 0.9999999, 0.01, 5.0000007473433201722e-12, 1e-13},
      {ref::Lambda_ggx, "Lambda_ggx", 0.999, 0.05, 1.2518759359353966584e-6, 1e-13},
      {ref::Lambda_ggx, "Lambda_ggx", 0.5, 0.3, 0.063471383479232239709, 1e-13},
      {ref::Lambda_ggx, "Lambda_ggx", 0.2, 0.5, 0.82287565553229522968, 1e-13},
      {ref::Lambda_ggx, "Lambda_ggx", 0.05, 1.0, 9.4999999999999994449, 1e-13},
  }));
  CAPTURE(c.name, c.NoV, c.alpha);
  CHECK_THAT(c.fn(c.NoV, c.alpha), WithinRel(c.expected, c.rel));
}

TEST_CASE("Lambda is zero at normal incidence and infinite below the horizon", "[reference][g][lambda]") {
  const double alpha = GENERATE(0.05, 0.3, 1.0);
  CAPTURE(alpha);
  for (double NoV : {1.0, kAboveOne, 1.0 + 1e-9}) {
    CAPTURE(NoV);
    CHECK(ref::Lambda_beckmann(NoV, alpha) == 0.0);
    CHECK(ref::Lambda_ggx(NoV, alpha) == 0.0);
  }
  for (double NoV : {0.0, -0.0, -0.5}) {
    CAPTURE(NoV);
    CHECK(std::isinf(ref::Lambda_beckmann(NoV, alpha)));
    CHECK(std::isinf(ref::Lambda_ggx(NoV, alpha)));
  }
  for (double NoV : {kDenormMin, 1e-200}) {  // tanθ overflows to +inf
    CAPTURE(NoV);
    CHECK_FALSE(std::isnan(ref::Lambda_beckmann(NoV, alpha)));
    CHECK_FALSE(std::isnan(ref::Lambda_ggx(NoV, alpha)));
  }
}

TEST_CASE("Smith G1 is 1/(1 + Lambda) for GGX and Beckmann", "[reference][g][lambda]") {
  const double alpha = GENERATE(0.05, 0.3, 1.0, 2.0);
  const double NoV = GENERATE(as<double>{}, kBelowOne, 1e-9, 0.01, 0.2, 0.5, 0.9, 0.999);
  CAPTURE(alpha, NoV);
  // G1_smith_ggx is seed 000's 2 / (1 + sqrt(1 + α² tan²θ)), a different
  // expression from 1 / (1 + Λ_ggx): agreement checks both.
  CHECK_THAT(ref::G1_smith_ggx(NoV, alpha), WithinRel(1.0 / (1.0 + ref::Lambda_ggx(NoV, alpha)), 1e-14));
  CHECK_THAT(ref::G1_smith_beckmann(NoV, alpha), WithinRel(1.0 / (1.0 + ref::Lambda_beckmann(NoV, alpha)), 1e-15));
}

TEST_CASE("Every G1 is one at normal incidence", "[reference][g][g1]") {
  for (const auto& g : all_g1()) {
    CAPTURE(g.name, g.param);
    CHECK(g.fn(1.0, g.param) == 1.0);
  }
}

TEST_CASE("Every G1 is one when NoV rounds above one, as seed 000 asks", "[reference][g][g1]") {
  const double NoV = GENERATE(as<double>{}, kAboveOne, 1.0000000000000002, 1.0 + 1e-12, 1.0 + 1e-6);
  for (const auto& g : all_g1()) {
    CAPTURE(g.name, g.param, NoV);
    const double value = g.fn(NoV, g.param);
    CHECK_FALSE(std::isnan(value));
    CHECK(value == 1.0);
  }
}

TEST_CASE("Every G1 is continuous just below normal incidence", "[reference][g][g1]") {
  const double NoV = GENERATE(as<double>{}, kBelowOne, 1.0 - 1e-15, 1.0 - 1e-12);
  for (const auto& g : all_g1()) {
    CAPTURE(g.name, g.param, NoV);
    const double value = g.fn(NoV, g.param);
    CHECK(value <= 1.0);
    CHECK_THAT(value, WithinAbs(1.0, 1e-5));
  }
}

TEST_CASE("Every G1 tends to zero at grazing and is zero below the horizon", "[reference][g][g1]") {
  for (const auto& g : all_g1()) {
    for (double NoV : {0.0, -0.0, -kDenormMin, -0.3, -1.0}) {
      CAPTURE(g.name, g.param, NoV);
      CHECK(g.fn(NoV, g.param) == 0.0);
    }
    // tanθ ≥ 1e12 (and +inf from ~1e-162 down): G1 ≤ C / (width · tanθ)
    for (double NoV : {1e-12, 1e-100, 1e-200, kDenormMin}) {
      CAPTURE(g.name, g.param, NoV);
      const double value = g.fn(NoV, g.param);
      CHECK(std::isfinite(value));
      CHECK(value >= 0.0);
      CHECK(value <= 1e-5);
    }
  }
}

TEST_CASE("Every G1 is non-decreasing in NoV and at most one", "[reference][g][g1]") {
  for (const auto& g : all_g1()) {
    // Seed 000's rational (Beckmann approx and Phong) overshoots 1 by up to
    // 6.1e-5 just below its cut-off a = 1.6 and then drops to exactly 1:
    // see the next test.  The exact forms get no slack.
    const bool rational = g.name == "G1_smith_beckmann_approx" || g.name == "G1_smith_phong";
    const double slack = rational ? 1e-4 : 0.0;
    double previous = 0.0;
    for (int i = 0; i <= 2000; ++i) {
      const double NoV = i / 2000.0;
      const double value = g.fn(NoV, g.param);
      CAPTURE(g.name, g.param, NoV, previous, value);
      CHECK(value >= previous - slack);
      CHECK(value <= 1.0 + slack);
      previous = value;
    }
  }
}

TEST_CASE("Seed 000's rational G1 overshoots one by at most 6.1e-5 below a = 1.6", "[reference][g][beckmann]") {
  // Walter et al. 2007's fit, as the seed prints it, is not clamped: at
  // a = 1.6 it evaluates to 11.23936 / 11.23872 = 1 + 5.7e-5, and the step to
  // 1 at the cut-off is a small discontinuity.  The reference keeps the
  // formula as printed; this test pins the size of the overshoot.
  double worst = 0.0;
  double worst_a = 0.0;
  for (int i = 0; i < 4000; ++i) {
    const double a = 1.0 + 0.6 * i / 4000.0;        // [1, 1.6)
    const double NoV = a / std::sqrt(1.0 + a * a);  // alpha = 1: a = 1 / tanθ
    const double value = ref::G1_smith_beckmann_approx(NoV, 1.0);
    if (value - 1.0 > worst) {
      worst = value - 1.0;
      worst_a = a;
    }
  }
  CAPTURE(worst, worst_a);
  CHECK(worst > 5e-5);
  CHECK(worst < 6.2e-5);
  const double a_cut = 1.6001;  // just past the cut-off (the NoV round trip perturbs a)
  CHECK(ref::G1_smith_beckmann_approx(a_cut / std::sqrt(1.0 + a_cut * a_cut), 1.0) == 1.0);
}

TEST_CASE("Seed 000's Beckmann rational G1 is within 0.4% of the exact Smith G1", "[reference][g][beckmann]") {
  // With alpha = 1, a = 1 / tanθ, so NoV = a / sqrt(1 + a²).
  const auto sweep = [] {
    std::vector<double> a{1.6, std::nextafter(1.6, 0.0), 1e-6, 1e-3};
    for (int i = 0; i <= 400; ++i) a.push_back(std::pow(10.0, -3.0 + 4.0 * i / 400.0));
    return a;
  }();
  for (double a : sweep) {
    const double NoV = a / std::sqrt(1.0 + a * a);
    const double exact = 1.0 / (1.0 + ref::Lambda_beckmann(NoV, 1.0));
    const double approx = ref::G1_smith_beckmann_approx(NoV, 1.0);
    CAPTURE(a, NoV, exact, approx);
    CHECK_THAT(approx, WithinRel(exact, 0.004));
  }
}

TEST_CASE("G1_smith_phong is the Beckmann rational at alpha_b = sqrt(2 / (alpha_p + 2))", "[reference][g][phong]") {
  const double alpha_p = GENERATE(0.0, 1.0, 10.0, 1000.0);
  const double NoV = GENERATE(0.01, 0.1, 0.3, 0.6, 0.9);
  CAPTURE(alpha_p, NoV);
  // seed 000: a = sqrt(alpha_p/2 + 1)/tanθ = 1/(alpha_b tanθ) with that alpha_b
  const double alpha_b = std::sqrt(2.0 / (alpha_p + 2.0));
  CHECK_THAT(ref::G1_smith_phong(NoV, alpha_p), WithinRel(ref::G1_smith_beckmann_approx(NoV, alpha_b), 1e-13));
}

// ============================ G2 ===========================================

TEST_CASE("Every G2 is zero when light or view is below the horizon", "[reference][g][g2]") {
  struct Pair {
    double NoL, NoV;
  };
  const auto p = GENERATE(values<Pair>({{0.0, 0.5},
                                        {0.5, 0.0},
                                        {-0.0, 0.7},
                                        {-kDenormMin, 0.7},
                                        {0.7, -kDenormMin},
                                        {-0.2, 0.5},
                                        {0.5, -0.2},
                                        {-1.0, -1.0},
                                        {0.0, 0.0}}));
  for (const auto& g : all_g2()) {
    CAPTURE(g.name, g.param, p.NoL, p.NoV);
    CHECK(g.fn(p.NoL, p.NoV, 0.8, 0.9, g.param) == 0.0);
  }
}

TEST_CASE("Every G2 built on the half vector is zero when the facet faces away (VoH <= 0)", "[reference][g][g2]") {
  const double VoH = GENERATE(0.0, -0.0, -0.5);
  for (const auto& g : all_g2()) {
    if (g.name == "G_implicit" || g.name == "G_hammon_002" || g.name == "G_hammon_clamped" ||
        g.name == "G_neubelt_sheen")
      continue;  // no h in them
    CAPTURE(g.name, g.param, VoH);
    CHECK(g.fn(0.6, 0.7, 0.8, VoH, g.param) == 0.0);
  }
}

TEST_CASE("Every G2 is one when light, view and normal coincide", "[reference][g][g2]") {
  for (const auto& g : all_g2()) {
    CAPTURE(g.name, g.param);
    CHECK(g.fn(1.0, 1.0, 1.0, 1.0, g.param) == 1.0);
  }
}

TEST_CASE("G_hammon_002 reproduces seed 002's visibility", "[reference][g][g2][hammon]") {
  SECTION("one at normal incidence for every alpha") {
    const double alpha = GENERATE(0.0, 0.05, 0.3, 1.0, 0.01, 0.7);
    CAPTURE(alpha);
    // 4 · 0.5 / max(0.01, mix(2, 2, alpha)) = 1
    CHECK_THAT(ref::G_hammon_002(1.0, 1.0, 1.0, 1.0, alpha), WithinULP(1.0, 0));
  }
  SECTION("known values") {
    // NoL = NoV = 0.5, alpha = 0.5: mix(0.5, 1, 0.5) = 0.75, G = 4·0.25·0.5/0.75 = 2/3
    CHECK_THAT(ref::G_hammon_002(0.5, 0.5, 0.9, 0.9, 0.5), WithinRel(2.0 / 3.0, 1e-15));
    // alpha = 0 is 2 NoL NoV in the denominator: G = 4 NoL NoV · 0.5 / (2 NoL NoV) = 1
    CHECK_THAT(ref::G_hammon_002(0.3, 0.8, 0.9, 0.9, 0.0), WithinRel(1.0, 1e-15));
    // the 0.01 floor: NoL = NoV = 1e-3, alpha = 0 → V = 50, G = 4e-6 · 50 = 2e-4
    CHECK_THAT(ref::G_hammon_002(1e-3, 1e-3, 0.9, 0.9, 0.0), WithinRel(2e-4, 1e-13));
  }
}

TEST_CASE("Height-correlated Smith-GGX is never darker than the separable product", "[reference][g][g2][ggx]") {
  const double alpha = GENERATE(0.01, 0.05, 0.3, 1.0, 2.0);
  for (double NoL : {1e-9, 0.01, 0.1, 0.5, 0.9, kBelowOne, 1.0}) {
    for (double NoV : {1e-9, 0.01, 0.1, 0.5, 0.9, kBelowOne, 1.0}) {
      CAPTURE(alpha, NoL, NoV);
      const double correlated = ref::G_smith_ggx_correlated(NoL, NoV, 0.9, 0.9, alpha);
      const double separable = ref::G_smith_ggx(NoL, NoV, 0.9, 0.9, alpha);
      // Where Λ(l) or Λ(v) is 0 the two are equal in exact arithmetic and
      // differ by rounding only: allow 4 ULP.
      CHECK(correlated >= separable * (1.0 - 4.0 * kEps));
      CHECK(correlated <= 1.0);
    }
  }
  // and strictly brighter where both directions are masked (50-digit value)
  const double correlated = ref::G_smith_ggx_correlated(0.3, 0.8, 0.9, 0.9, 0.5);
  CHECK_THAT(correlated, WithinRel(0.67883168962511077704, 1e-13));
  CHECK(correlated > ref::G_smith_ggx(0.3, 0.8, 0.9, 0.9, 0.5));
}

TEST_CASE("Separable Smith G2 terms are the product of their G1", "[reference][g][g2]") {
  const double alpha = GENERATE(0.05, 0.3, 1.0);
  const double NoL = GENERATE(0.05, 0.5, 0.95);
  const double NoV = GENERATE(0.1, 0.7);
  CAPTURE(alpha, NoL, NoV);
  CHECK_THAT(ref::G_smith_ggx(NoL, NoV, 0.9, 0.9, alpha),
             WithinULP(ref::G1_smith_ggx(NoL, alpha) * ref::G1_smith_ggx(NoV, alpha), 0));
  CHECK_THAT(ref::G_smith_beckmann(NoL, NoV, 0.9, 0.9, alpha),
             WithinULP(ref::G1_smith_beckmann(NoL, alpha) * ref::G1_smith_beckmann(NoV, alpha), 0));
  CHECK_THAT(ref::G_smith_beckmann_approx(NoL, NoV, 0.9, 0.9, alpha),
             WithinULP(ref::G1_smith_beckmann_approx(NoL, alpha) * ref::G1_smith_beckmann_approx(NoV, alpha), 0));
  const double alpha_p = 2.0 / (alpha * alpha) - 2.0;
  CHECK_THAT(ref::G_smith_phong(NoL, NoV, 0.9, 0.9, alpha_p),
             WithinULP(ref::G1_smith_phong(NoL, alpha_p) * ref::G1_smith_phong(NoV, alpha_p), 0));
}

TEST_CASE("G_cook_torrance and G_kelemen follow their closed forms on real directions",
          "[reference][g][g2][cook-torrance]") {
  SECTION("l = v: h = v, VoH = 1, so G_ct = min(1, 2 cos²θ) and G_kelemen = cos²θ") {
    const double theta = GENERATE(0.1, 0.5, 1.0, 1.3, 1.5, 1.57);
    CAPTURE(theta);
    const Dots d = dots_from_angles(theta, theta, 0.0);
    const double c = std::cos(theta);
    CHECK_THAT(ref::G_cook_torrance(d.NoL, d.NoV, d.NoH, d.VoH, 0.0), WithinRel(std::min(1.0, 2.0 * c * c), 1e-12));
    CHECK_THAT(ref::G_kelemen(d.NoL, d.NoV, d.NoH, d.VoH, 0.0), WithinRel(c * c, 1e-12));
    CHECK_THAT(ref::G_implicit(d.NoL, d.NoV, d.NoH, d.VoH, 0.0), WithinRel(c * c, 1e-12));
  }
  SECTION("mirror pair (phi = pi, equal angles): h = n and VoH = NoL = NoV") {
    const double theta = GENERATE(0.1, 0.5, 1.0, 1.3, 1.5);
    CAPTURE(theta);
    const Dots d = dots_from_angles(theta, theta, kPi);
    // Kelemen: cos²θ / cos²θ = 1; V-cavity: min(1, 2 cosθ / cosθ, ...) = 1
    CHECK_THAT(ref::G_kelemen(d.NoL, d.NoV, d.NoH, d.VoH, 0.0), WithinRel(1.0, 1e-12));
    CHECK_THAT(ref::G_cook_torrance(d.NoL, d.NoV, d.NoH, d.VoH, 0.0), WithinRel(1.0, 1e-12));
  }
  SECTION("the V-cavity G lies in [0, 1] and is symmetric in l and v") {
    const double theta_l = GENERATE(0.0, 0.3, 0.9, 1.4, 1.55);
    const double theta_v = GENERATE(0.2, 0.8, 1.2, 1.5);
    const double phi = GENERATE(0.0, 1.0, 2.5, 3.14);
    CAPTURE(theta_l, theta_v, phi);
    const Dots a = dots_from_angles(theta_l, theta_v, phi);
    const Dots b = dots_from_angles(theta_v, theta_l, phi);
    const double g_ab = ref::G_cook_torrance(a.NoL, a.NoV, a.NoH, a.VoH, 0.0);
    const double g_ba = ref::G_cook_torrance(b.NoL, b.NoV, b.NoH, b.VoH, 0.0);
    CHECK(g_ab >= 0.0);
    CHECK(g_ab <= 1.0);
    CHECK_THAT(g_ab, WithinRel(g_ba, 1e-12));
  }
}
