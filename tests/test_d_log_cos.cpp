// ref::d_of_log_cos (reference/d_log_cos.hpp): the Phong-type Ds from log
// cos θ give their _cs forms' bits, which the furnace truth relies on to take
// log cos θ once a node for every width (checks/furnace_views.cpp, issue 30).
#include "catalog/catalog.hpp"
#include "reference/d_log_cos.hpp"
#include "reference/reference.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace mfv;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The first (cos², sin², width) at which cs differs from lc at log_cos_cs (hex floats), "" where none does.
std::string first_difference(ref::RefDcs cs, ref::RefDlc lc, double lo, double hi) {
  std::vector<double> angles = {0.0, 1e-300, 1e-150, 1e-8, 1e-4, 0.3, 0.7853981633974483, 1.2, 1.5707963, 1.5707963267948966};
  std::vector<double> widths = {lo, hi, 1e-4, 0.01, 0.3, 1.0, 100.0};
  std::mt19937_64 rng(30);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 300; ++k) angles.push_back(1.5707963267948966 * u(rng));
  for (int k = 0; k < 20; ++k) widths.push_back(lo + (hi - lo) * std::pow(u(rng), 4));
  for (double w : widths) {
    if (!(w >= lo && w <= hi)) continue;
    for (double a : angles) {
      // as shading_from gives them: cos² and sin² apart, each may round
      const double c = std::cos(a), s = std::sin(a), cos2 = c * c, sin2 = s * s;
      const double want = cs(cos2, sin2, w);
      const double got = cos2 > 0.0 ? lc(ref::log_cos_cs(std::min(cos2, 1.0), sin2), w) : 0.0;
      if (!same_bits(want, got)) {
        char where[160];
        std::snprintf(where, sizeof where, "cos2 %a sin2 %a width %a: _cs %a, from log cos %a", cos2, sin2, w, want, got);
        return where;
      }
    }
  }
  return "";
}

}  // namespace

TEST_CASE("The Phong-type Ds from log cos theta give their cos2-sin2 forms' bits", "[reference][d][log_cos]") {
  size_t with = 0;
  for (const Term* t : all_terms_of(Kind::D)) {
    CAPTURE(t->id);
    const ref::RefDlc lc = t->ref_d_cs ? ref::d_of_log_cos(t->ref_d_cs) : nullptr;
    if (!lc) continue;
    ++with;
    REQUIRE(!t->params.empty());
    CHECK(first_difference(t->ref_d_cs, lc, t->params[0].lo, t->params[0].hi) == "");
  }
  CHECK(with == 2);  // phong, blinn_rho
  CHECK(ref::d_of_log_cos(ref::D_ggx_cs) == nullptr);
}

TEST_CASE("The log cos theta check finds a D paired with another's form", "[reference][d][log_cos][planted]") {
  CHECK(first_difference(ref::D_phong_cs, ref::D_blinn_rho_lc, 0.01, 1.0) != "");
  CHECK(first_difference(ref::D_blinn_rho_cs, ref::D_phong_lc, 0.01, 1.0) != "");
}
