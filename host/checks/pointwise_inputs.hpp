// The inputs of the pointwise harness (checks/pointwise.hpp), random and
// extreme, in one place:
//  - random: mfv agree draws its records on the device (kernels/agree.cl)
//    from Philox; the host gives the parameter ranges (draw_ranges);
//  - extreme: the deterministic classes of mfv stability and of the census
//    of mfv check: cosines (grazing down to 2^-149, near the normal, tanθ = 0,
//    dot products that rounded above 1, below the horizon) and direction
//    pairs (mirror, grazing, opposite: h ~ 0/0, non-unit, ...).
#pragma once

#include "abi/pointwise.h"

#include <glm/vec3.hpp>

#include <array>
#include <string>
#include <vector>

namespace mfv {

struct Param;
struct Term;
struct Model;

// ---- Random: the draw ranges of kernels/agree.cl ---------------------------

// Per parameter slot p[0..6] (lo, hi, log flag): log-uniform where a range
// spans decades; hi = 0 pins a slot at 0.
using DrawRanges = std::array<float, pw::PW_RANGE>;
// The ranges of one case: the terms' parameters (D, G, F p0, F p1), kd in
// [0, 1] for an assembled BRDF (diffuse = true), 0 elsewhere; a whole model:
// its own parameters in every slot, 0 past its count. A rough dielectric
// BTDF (eta given): slot 2 takes the BSDF's declared eta range in place of
// the dielectric F term's.
DrawRanges draw_ranges(const Term* d, const Term* g, const Term* f, const Model* model, bool diffuse,
                       const Param* eta = nullptr);

// ---- Extreme: the classes of the sweep ---------------------------------------

// The format's rounding of x, its 1 + k ulp and 1 - 1 ulp.
double round_to(double x, bool fp64);
double one_plus_ulps(int k, bool fp64);
double one_minus_ulp(bool fp64);

// Cosines whose square underflows in float: the smallest subnormal 2^-149,
// 1e-30 and 1e-20 (a unit float vector can have such a z). Float64 kernels
// are swept on the same values: the corresponding double extremes (cos below
// ~1e-154) are beyond what the double reference itself can judge.
inline constexpr double kTinyCos[3] = {0x1p-149, 1e-30, 1e-20};

// Cosine classes: grazing (down to 2^-149), mid, normal, tan_zero,
// above_one (dot products that rounded above 1), below_horizon.
struct CosClass {
  std::string name, what;
  std::vector<double> values;
  bool in_domain = true;
};
std::vector<CosClass> cos_classes(bool fp64);
// Every cosine of the classes, sorted, once each.
std::vector<double> all_cos(bool fp64);

// Direction pairs (wi = light, wo = view, n = +z): mirror, near_mirror,
// grazing, normal, mid, opposite (h ~ 0/0), below_horizon, non_unit.
struct Pair {
  glm::dvec3 wi, wo;
};
struct PairSet {
  std::string name, what, expect;
  std::vector<Pair> pairs;
};
std::vector<PairSet> pair_sets(bool fp64);

// The unit direction at this cosine and azimuth (sinθ without cancellation),
// its mirror about the normal and its turn by a about the normal.
glm::dvec3 dir(double cos_theta, double phi);
glm::dvec3 mirror(const glm::dvec3& w);
glm::dvec3 rot_z(const glm::dvec3& w, double a);

}  // namespace mfv
