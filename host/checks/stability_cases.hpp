// mfv stability's cases (internal to host/checks/stability*.cpp): each case
// is a kernel mode, its terms or model, its regions and its sweep points,
// each point one pointwise record (kernels/abi/pointwise.h) in double before
// the harness rounds it to the working precision.
#pragma once

#include "checks/pointwise.hpp"
#include "checks/stability.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <functional>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

namespace mfv {
struct Term;
struct Model;
struct Bsdf;
}  // namespace mfv

namespace mfv::stability_detail {

using namespace mfv::pw;  // the record's named slots and modes

constexpr int kIn = pw::PW_RECORD;  // numbers per record
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One record's numbers (inputs at their named slots; the value slots unused here).
using In = std::array<double, kIn>;

// A record of two directions and parameters p[0..] (the rest 0).
inline In record(const glm::dvec3& wi, const glm::dvec3& wo, std::initializer_list<double> params) {
  In r{};
  r[PW_WI_X] = wi.x, r[PW_WI_Y] = wi.y, r[PW_WI_Z] = wi.z;
  r[PW_WO_X] = wo.x, r[PW_WO_Y] = wo.y, r[PW_WO_Z] = wo.z;
  int k = PW_P0;
  for (double p : params) r[size_t(k++)] = p;
  return r;
}
inline glm::dvec3 wi_of(const In& r) { return {r[PW_WI_X], r[PW_WI_Y], r[PW_WI_Z]}; }
inline glm::dvec3 wo_of(const In& r) { return {r[PW_WO_X], r[PW_WO_Y], r[PW_WO_Z]}; }

struct Point {
  In in{};
  int region = 0;
  double theta = kNaN, alpha = kNaN;  // scan points only: where they go on the plots
};

struct Region {
  std::string name, what;
  bool in_domain = true;
  std::string expect;
};

struct CaseDef {
  StabilityCase info;
  PwMode mode = PW_D;
  const Term* d = nullptr;
  const Term* g = nullptr;
  const Term* f = nullptr;
  const Model* model = nullptr;  // PW_MODEL: the kernel's `d` argument carries its number
  int variant = -1;
  int f_code = -1;  // PW_BTDF: the BTDF's code (kernels/abi/bsdf.h), passed as the kernel's `f`
  std::vector<Region> regions;
  std::vector<Point> points;
  std::function<double(const In&)> ref;  // the double reference on the rounded inputs
  std::function<std::string(const In&)> describe;
  int add_region(Region r) {
    regions.push_back(std::move(r));
    return static_cast<int>(regions.size()) - 1;
  }
};

std::string hx(double x);  // hex-float
// θ grid of the plots' scans: (θ, cosθ) near the normal and near grazing.
std::vector<std::pair<double, double>> scan_angles();
extern const std::vector<double> kScanAlphas;

// The cases: one term (or its Smith G1), one D x G x F BRDF, one whole model
// (at its catalog cases or the points --scene gives), every alternative formulation.
CaseDef term_case(const Term& t, bool g1, bool fp64);
CaseDef brdf_case(const Term& d, const Term& g, const Term& f, bool fp64);
CaseDef model_case(const Model& m, const StabilityOptions& opt);
std::vector<CaseDef> variant_cases(bool fp64);
// stability_btdf.cpp; scene_points: (alpha, eta) of a scene's refracting materials
CaseDef btdf_case(const Bsdf& b, bool fp64, const std::vector<std::array<double, 2>>& scene_points = {});

}  // namespace mfv::stability_detail
