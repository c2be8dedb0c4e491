// TermTwins::g_separable and g_correlated_lambda: a G term so marked is
// G1(n·l) G1(n·v), or 1 / (1 + Λ(n·l) + Λ(n·v)), under its χ+ factors, bit
// for bit, which the furnace truth relies on to take G1(n·v) or Λ(n·v) once
// a view (checks/furnace_views.cpp, issue 30).
#include "catalog/catalog.hpp"
#include "reference/reference.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace mfv;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// G from its one-direction parts as the twin's marks say.
double g_of_parts(const ref::TermTwins& t, double nol, double nov, double voh, double w) {
  if (!(nol > 0.0 && nov > 0.0 && voh > 0.0)) return 0.0;
  if (t.g_separable) return t.ref_g1(nol, w) * t.ref_g1(nov, w);
  return 1.0 / (1.0 + t.g_correlated_lambda(nol, w) + t.g_correlated_lambda(nov, w));
}

// The first input at which ref_g differs from g_of_parts (as hex floats), "" where none does.
std::string first_difference(const ref::TermTwins& t, double lo, double hi) {
  std::vector<double> cosines = {0.0,  -0.0,  -0.5, 1e-300, 1e-12, 1e-6,  0.01,  0.3,
                                 0.5,  0.7,   0.99, 1.0 - 0x1p-52,  1.0, 1.0 + 0x1p-52, 1.01};
  std::vector<double> widths = {lo, hi, 0.5 * (lo + hi), 1e-4, 0.01, 0.3, 1.0};
  std::mt19937_64 rng(30);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 200; ++k) cosines.push_back(u(rng));
  for (int k = 0; k < 20; ++k) widths.push_back(lo + (hi - lo) * u(rng) * u(rng));
  for (double w : widths) {
    if (!(w >= lo && w <= hi)) continue;
    for (size_t a = 0; a < cosines.size(); ++a)
      for (size_t b = 0; b < cosines.size(); b += 7) {
        const double nol = cosines[a], nov = cosines[b], voh = cosines[(a + b) % cosines.size()];
        const double g = t.ref_g(nol, nov, 0.9, voh, w);
        const double parts = g_of_parts(t, nol, nov, voh, w);
        char where[160];
        std::snprintf(where, sizeof where, "NoL %a NoV %a VoH %a width %a: G %a, from its parts %a", nol, nov, voh, w,
                      g, parts);
        if (!same_bits(g, parts)) return where;
      }
  }
  return "";
}

}  // namespace

TEST_CASE("Every G term marked separable is its G1(n.l) G1(n.v) bit for bit", "[catalog][g][separable]") {
  size_t marked = 0;
  for (const Term* t : all_terms_of(Kind::G)) {
    if (!t->g_separable) continue;
    ++marked;
    CAPTURE(t->id);
    REQUIRE(t->ref_g1);
    REQUIRE(!t->params.empty());  // the width (an anisotropic term's isotropic slice: alpha_x)
    CHECK(first_difference(*t, t->params[0].lo, t->params[0].hi) == "");
  }
  CHECK(marked >= 6);  // smith_beckmann_approx, smith_beckmann, smith_phong, smith_ggx, the two anisotropic
}

TEST_CASE("Every G term marked height-correlated is 1/(1 + Lambda(n.l) + Lambda(n.v)) bit for bit",
          "[catalog][g][separable]") {
  size_t marked = 0;
  for (const Term* t : all_terms_of(Kind::G)) {
    if (!t->g_correlated_lambda) continue;
    ++marked;
    CAPTURE(t->id);
    CHECK_FALSE(t->g_separable);
    REQUIRE(!t->params.empty());
    CHECK(first_difference(*t, t->params[0].lo, t->params[0].hi) == "");
  }
  CHECK(marked >= 2);  // smith_ggx_correlated, charlie_sheen
}

TEST_CASE("The check finds a height-correlated G marked separable, and a separable one marked correlated",
          "[catalog][g][separable][planted]") {
  ref::TermTwins planted = find_term("smith_ggx_correlated");  // 1/(1 + Λ(l) + Λ(v)) with its G1_smith_ggx
  planted.g_correlated_lambda = nullptr;
  planted.g_separable = true;
  CHECK(first_difference(planted, 1e-7, 10.0) != "");
  planted = find_term("smith_ggx");  // G1(l) G1(v)
  planted.g_separable = false;
  planted.g_correlated_lambda = ref::Lambda_ggx;
  CHECK(first_difference(planted, 1e-7, 10.0) != "");
}
