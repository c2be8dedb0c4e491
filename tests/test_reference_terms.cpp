// Tests of the scalar double-precision reference terms (host/reference/).
//
// The expected values come from the seeds' closed forms, from physics
// (normalisation, limits, total internal reflection) and from known answers
// computed independently with mpmath at 50 significant digits from the exact
// double inputs.  No value here is computed by the function under test.
#include <catch2/catch.hpp>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "reference/reference.hpp"

namespace ref = mfv::ref;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using Catch::Matchers::WithinULP;

namespace {

constexpr double kPi = 3.14159265358979323846264338327950288;
const double kDenormMin = std::numeric_limits<double>::denorm_min();
const double kAboveOne = std::nextafter(1.0, 2.0);  // 1 + 2^-52
const double kBelowOne = std::nextafter(1.0, 0.0);  // 1 - 2^-53
constexpr double kEps = std::numeric_limits<double>::epsilon();

using Scalar2 = double (*)(double, double);
using Term3 = double (*)(double, double, double);
using G2Fn = double (*)(double, double, double, double, double);

struct Named1 {  // a D, Λ or G1 with one parameter value
    std::string name;
    Scalar2 fn;
    double param;
    double width;  // angular width in θ (radians), for the quadrature's grading
};

struct NamedG2 {
    std::string name;
    G2Fn fn;
    double param;
};

// ---- quadrature -----------------------------------------------------------
// Adaptive Simpson on [a, b] with Richardson correction; deterministic.
double simpson_step(const std::function<double(double)>& f, double a, double b, double fa,
                    double fm, double fb, double whole, double eps, int depth) {
    const double m = 0.5 * (a + b);
    const double lm = 0.5 * (a + m);
    const double rm = 0.5 * (m + b);
    const double flm = f(lm);
    const double frm = f(rm);
    const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    const double delta = left + right - whole;
    if (depth <= 0 || std::fabs(delta) <= 15.0 * eps) return left + right + delta / 15.0;
    return simpson_step(f, a, m, fa, flm, fm, left, 0.5 * eps, depth - 1) +
           simpson_step(f, m, b, fm, frm, fb, right, 0.5 * eps, depth - 1);
}

double adaptive_simpson(const std::function<double(double)>& f, double a, double b, double eps) {
    const double fa = f(a);
    const double fm = f(0.5 * (a + b));
    const double fb = f(b);
    const double whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
    return simpson_step(f, a, b, fa, fm, fb, whole, eps, 40);
}

// 2π ∫_0^{π/2} D(cosθ) cosθ sinθ dθ  (= ∫_H D(m)(m·n) dω_m for isotropic D).
// The θ range is cut at width/8 · 2^k so a peak of that width (roughness
// only, never D's formula: docs/design.md §3) is resolved before the tail.
double projected_integral(Scalar2 D, double param, double width) {
    const auto integrand = [&](double theta) {
        return D(std::cos(theta), param) * std::cos(theta) * std::sin(theta);
    };
    std::vector<double> cuts{0.0};
    for (double t = width / 8.0; t < 0.5 * kPi; t *= 2.0) cuts.push_back(t);
    cuts.push_back(0.5 * kPi);
    double sum = 0.0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
        sum += adaptive_simpson(integrand, cuts[i], cuts[i + 1], 1e-13);
    return 2.0 * kPi * sum;
}

double phong_width(double alpha_p) { return std::sqrt(2.0 / (alpha_p + 2.0)); }

// ---- geometry: dot products of a real (l, v) pair, formed with GLM --------
struct Dots {
    double NoL, NoV, NoH, VoH;
};

Dots dots_from_angles(double theta_l, double theta_v, double phi) {
    const glm::dvec3 n(0.0, 0.0, 1.0);
    const glm::dvec3 l(std::sin(theta_l), 0.0, std::cos(theta_l));
    const glm::dvec3 v(std::sin(theta_v) * std::cos(phi), std::sin(theta_v) * std::sin(phi),
                       std::cos(theta_v));
    const glm::dvec3 h = glm::normalize(l + v);
    return {glm::dot(n, l), glm::dot(n, v), glm::dot(n, h), glm::dot(v, h)};
}

// ---- independent closed forms (tests only) --------------------------------
// seed 000, "The exact formulation": F = ½ (g−c)²/(g+c)² (1 + (c(g+c)−1)²/(c(g−c)+1)²),
// g = sqrt(η² − 1 + c²), valid outside total internal reflection.
double fresnel_seed000(double c, double eta) {
    const double g = std::sqrt(eta * eta - 1.0 + c * c);
    const double q1 = (g - c) / (g + c);
    const double q2 = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * q1 * q1 * (1.0 + q2 * q2);
}

// Born & Wolf's real form of the conductor Fresnel reflectance (a², b² of
// eta² − sin²θ = (a + i b)²), written independently of the complex form.
double fresnel_conductor_born_wolf(double c, double n, double k) {
    const double s2 = 1.0 - c * c;
    const double t0 = n * n - k * k - s2;
    const double a2b2 = std::sqrt(t0 * t0 + 4.0 * n * n * k * k);
    const double a = std::sqrt(0.5 * (a2b2 + t0));
    const double rs = (a2b2 - 2.0 * a * c + c * c) / (a2b2 + 2.0 * a * c + c * c);
    const double st = s2 / c;  // sinθ tanθ
    const double rp = rs * (a2b2 - 2.0 * a * st + st * st) / (a2b2 + 2.0 * a * st + st * st);
    return 0.5 * (rs + rp);
}

std::vector<Named1> all_g1() {
    std::vector<Named1> v;
    for (double a : {0.001, 0.05, 0.3, 1.0, 2.0}) {
        v.push_back({"G1_smith_beckmann", ref::G1_smith_beckmann, a, a});
        v.push_back({"G1_smith_beckmann_approx", ref::G1_smith_beckmann_approx, a, a});
        v.push_back({"G1_smith_ggx", ref::G1_smith_ggx, a, a});
    }
    for (double ap : {0.0, 1.0, 10.0, 1000.0, 1e6})
        v.push_back({"G1_smith_phong", ref::G1_smith_phong, ap, phong_width(ap)});
    return v;
}

std::vector<NamedG2> all_g2() {
    std::vector<NamedG2> v{{"G_implicit", ref::G_implicit, 0.0},
                           {"G_kelemen", ref::G_kelemen, 0.0},
                           {"G_cook_torrance", ref::G_cook_torrance, 0.0}};
    for (double a : {0.05, 0.3, 1.0}) {
        v.push_back({"G_smith_beckmann_approx", ref::G_smith_beckmann_approx, a});
        v.push_back({"G_smith_beckmann", ref::G_smith_beckmann, a});
        v.push_back({"G_smith_ggx", ref::G_smith_ggx, a});
        v.push_back({"G_smith_ggx_correlated", ref::G_smith_ggx_correlated, a});
        v.push_back({"G_hammon_002", ref::G_hammon_002, a});
    }
    for (double ap : {10.0, 1000.0}) v.push_back({"G_smith_phong", ref::G_smith_phong, ap});
    return v;
}

std::vector<Named1> all_d() {
    std::vector<Named1> v;
    for (double a : {0.05, 0.3, 1.0}) {
        v.push_back({"D_ggx", ref::D_ggx, a, a});
        v.push_back({"D_beckmann", ref::D_beckmann, a, a});
        v.push_back({"D_blinn_rho", ref::D_blinn_rho, a, a});
        v.push_back({"D_beckmann_ct82", ref::D_beckmann_ct82, a, a});
    }
    for (double ap : {10.0, 1000.0})
        v.push_back({"D_phong", ref::D_phong, ap, phong_width(ap)});
    return v;
}

}  // namespace

// ============================ D ============================================

TEST_CASE("D_ggx and D_beckmann peak at exactly 1/(pi alpha^2) at normal incidence",
          "[reference][d][ggx][beckmann]") {
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

TEST_CASE("D_blinn_rho peaks at 1/(pi rho^2) and equals D_phong with alpha_p = 2/rho^2 - 2",
          "[reference][d][blinn]") {
    const double rho = GENERATE(0.05, 0.3, 1.0, 0.7);
    const double NoH = GENERATE(1.0, 0.999, 0.9, 0.5, 0.1);
    CAPTURE(rho, NoH);
    CHECK_THAT(ref::D_blinn_rho(1.0, rho), WithinULP(1.0 / (kPi * rho * rho), 2));
    const double alpha_p = 2.0 / (rho * rho) - 2.0;
    const double expected = ref::D_phong(NoH, alpha_p);
    CHECK_THAT(ref::D_blinn_rho(NoH, rho), WithinRel(expected, 1e-12) || WithinAbs(0.0, 1e-300));
}

TEST_CASE("D_ggx matches seed 000's second GGX form and seed 002's distribution",
          "[reference][d][ggx]") {
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

TEST_CASE("Every correct D integrates to one over the projected hemisphere",
          "[reference][d][integral]") {
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

TEST_CASE("D_beckmann_ct82 as written in seed 001 integrates to pi/4, not one",
          "[reference][d][integral][known-bad]") {
    const double m = GENERATE(0.05, 0.3, 1.0, 0.6);
    CAPTURE(m);
    const double integral = projected_integral(ref::D_beckmann_ct82, m, m);
    CHECK_THAT(integral, WithinRel(kPi / 4.0, 1e-9));
    CHECK_THAT(integral, !WithinRel(1.0, 0.1));
}

// ============================ Λ and G1 =====================================

TEST_CASE("Lambda_beckmann and Lambda_ggx match 50-digit known answers",
          "[reference][g][lambda][beckmann][ggx]") {
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

TEST_CASE("Lambda is zero at normal incidence and infinite below the horizon",
          "[reference][g][lambda]") {
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
    CHECK_THAT(ref::G1_smith_ggx(NoV, alpha),
               WithinRel(1.0 / (1.0 + ref::Lambda_ggx(NoV, alpha)), 1e-14));
    CHECK_THAT(ref::G1_smith_beckmann(NoV, alpha),
               WithinRel(1.0 / (1.0 + ref::Lambda_beckmann(NoV, alpha)), 1e-15));
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

TEST_CASE("Every G1 tends to zero at grazing and is zero below the horizon",
          "[reference][g][g1]") {
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

TEST_CASE("Seed 000's rational G1 overshoots one by at most 6.1e-5 below a = 1.6",
          "[reference][g][beckmann]") {
    // Walter et al. 2007's fit, as the seed prints it, is not clamped: at
    // a = 1.6 it evaluates to 11.23936 / 11.23872 = 1 + 5.7e-5, and the step to
    // 1 at the cut-off is a small discontinuity.  The reference keeps the
    // formula as printed; this test pins the size of the overshoot.
    double worst = 0.0;
    double worst_a = 0.0;
    for (int i = 0; i < 4000; ++i) {
        const double a = 1.0 + 0.6 * i / 4000.0;  // [1, 1.6)
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

TEST_CASE("Seed 000's Beckmann rational G1 is within 0.4% of the exact Smith G1",
          "[reference][g][beckmann]") {
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

TEST_CASE("G1_smith_phong is the Beckmann rational at alpha_b = sqrt(2 / (alpha_p + 2))",
          "[reference][g][phong]") {
    const double alpha_p = GENERATE(0.0, 1.0, 10.0, 1000.0);
    const double NoV = GENERATE(0.01, 0.1, 0.3, 0.6, 0.9);
    CAPTURE(alpha_p, NoV);
    // seed 000: a = sqrt(alpha_p/2 + 1)/tanθ = 1/(alpha_b tanθ) with that alpha_b
    const double alpha_b = std::sqrt(2.0 / (alpha_p + 2.0));
    CHECK_THAT(ref::G1_smith_phong(NoV, alpha_p),
               WithinRel(ref::G1_smith_beckmann_approx(NoV, alpha_b), 1e-13));
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

TEST_CASE("Every G2 built on the half vector is zero when the facet faces away (VoH <= 0)",
          "[reference][g][g2]") {
    const double VoH = GENERATE(0.0, -0.0, -0.5);
    for (const auto& g : all_g2()) {
        if (g.name == "G_implicit" || g.name == "G_hammon_002") continue;  // no h in them
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

TEST_CASE("Height-correlated Smith-GGX is never darker than the separable product",
          "[reference][g][g2][ggx]") {
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
               WithinULP(ref::G1_smith_beckmann_approx(NoL, alpha) *
                             ref::G1_smith_beckmann_approx(NoV, alpha), 0));
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
        CHECK_THAT(ref::G_cook_torrance(d.NoL, d.NoV, d.NoH, d.VoH, 0.0),
                   WithinRel(std::min(1.0, 2.0 * c * c), 1e-12));
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

TEST_CASE("F_dielectric with eta < 1 totally reflects beyond the critical angle",
          "[reference][f][dielectric]") {
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

TEST_CASE("F_conductor at normal incidence is ((n-1)^2 + k^2)/((n+1)^2 + k^2)",
          "[reference][f][conductor]") {
    struct Nk {
        double n, k;
    };
    const auto c = GENERATE(values<Nk>(
        {{0.2, 3.4}, {1.2, 7.3}, {0.05, 0.1}, {2.5, 0.0}, {1.0, 1.0}, {1.0, 0.0}, {0.01, 20.0}}));
    CAPTURE(c.n, c.k);
    const double expected = ((c.n - 1.0) * (c.n - 1.0) + c.k * c.k) /
                            ((c.n + 1.0) * (c.n + 1.0) + c.k * c.k);
    CHECK_THAT(ref::F_conductor(1.0, c.n, c.k), WithinRel(expected, 1e-13) || WithinAbs(0.0, 1e-300));
}

TEST_CASE("F_conductor agrees with Born and Wolf's real form and lies in [0, 1]",
          "[reference][f][conductor]") {
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
