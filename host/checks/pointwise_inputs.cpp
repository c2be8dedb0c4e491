#include "checks/pointwise_inputs.hpp"

#include "catalog/catalog.hpp"
#include "catalog/models.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace mfv {
namespace {

const double* const kTiny = kTinyCos;

// Sampling range of one parameter: log-uniform where it spans decades.
void put_range(DrawRanges& r, int slot, const Param* p) {
  double lo = p ? p->lo : 0.0, hi = p ? p->hi : 1.0;
  bool log_scale = hi > 100.0 * std::max(lo, 1e-300);
  if (log_scale && lo <= 0.0) lo = 1e-3 * std::max(1.0, hi * 1e-6);  // an exponent from 0: sample from ~1
  r[3 * slot] = static_cast<float>(lo);
  r[3 * slot + 1] = static_cast<float>(hi);
  r[3 * slot + 2] = log_scale ? 1.0f : 0.0f;
}

const Param* param(const Term* t, size_t i) { return t && i < t->params.size() ? &t->params[i] : nullptr; }

}  // namespace

DrawRanges draw_ranges(const Term* d, const Term* g, const Term* f, const Model* model, bool diffuse,
                       const Param* eta) {
  DrawRanges ranges{};
  if (model) {  // a whole model: its own parameters in every slot, 0 past its count
    for (int k = 0; k < pw::PW_PARAMS; ++k) {
      put_range(ranges, k, size_t(k) < model->params.size() ? &model->params[size_t(k)] : nullptr);
      if (size_t(k) >= model->params.size()) ranges[3 * k + 1] = 0.0f;
    }
    return ranges;
  }
  put_range(ranges, 0, param(d, 0));
  put_range(ranges, 1, param(g, 0));
  put_range(ranges, 2, eta ? eta : param(f, 0));
  put_range(ranges, 3, param(f, 1));
  for (int k = 4; k < pw::PW_PARAMS; ++k) put_range(ranges, k, nullptr);  // [0, 1]
  ranges[3 * 6 + 1] = 0.0f;                                               // p[6]: whole models only
  ranges[3 * 5 + 1] = 0.0f;                                               // p5: whole models only
  if (!diffuse) ranges[3 * 4 + 1] = 0.0f;                                 // no diffuse outside the BRDF
  return ranges;
}

double round_to(double x, bool fp64) { return fp64 ? x : static_cast<double>(static_cast<float>(x)); }
double one_plus_ulps(int k, bool fp64) { return 1.0 + k * (fp64 ? 0x1p-52 : 0x1p-23); }
double one_minus_ulp(bool fp64) { return fp64 ? std::nextafter(1.0, 0.0) : std::nextafterf(1.0f, 0.0f); }

// ---- The cosine grid (issue 6, "Sweep") ------------------------------------
// cosθ ∈ {0, 1e-7, 1e-4, ..., 1 - 1e-7, 1, 1 + 1 ulp}, plus values whose
// square underflows (a unit vector can have such a z), and below the horizon.

std::vector<CosClass> cos_classes(bool fp64) {
  return {
      {"grazing",
       "cos in {0, 2^-149, 1e-30, 1e-20, 1e-7, 1e-4, 1e-3, 1e-2}",
       {0.0, kTiny[0], kTiny[1], kTiny[2], 1e-7, 1e-4, 1e-3, 1e-2}},
      {"mid", "cos in {0.1, 0.3, 0.5, 0.7, 0.9}", {0.1, 0.3, 0.5, 0.7, 0.9}},
      {"normal",
       "cos in {1-1e-2, 1-1e-4, 1-1e-7, 1-1ulp, 1}",
       {1 - 1e-2, 1 - 1e-4, 1 - 1e-7, one_minus_ulp(fp64), 1.0}},
      {"tan_zero", "cos = 1 exactly: tan = 0, sin² = 0", {1.0}},
      {"above_one",
       "cos in {1+1ulp, 1+2ulp, 1+4ulp}: dot products that rounded above 1",
       {one_plus_ulps(1, fp64), one_plus_ulps(2, fp64), one_plus_ulps(4, fp64)}},
      {"below_horizon", "cos in {-2^-149, -1e-7, -0.5, -1}", {-kTiny[0], -1e-7, -0.5, -1.0}},
  };
}

std::vector<double> all_cos(bool fp64) {
  std::vector<double> v;
  for (auto& c : cos_classes(fp64)) v.insert(v.end(), c.values.begin(), c.values.end());
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

glm::dvec3 dir(double cos_theta, double phi) {
  double s = std::sqrt(std::max(0.0, (1.0 - cos_theta) * (1.0 + cos_theta)));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

glm::dvec3 mirror(const glm::dvec3& w) { return {-w.x, -w.y, w.z}; }
glm::dvec3 rot_z(const glm::dvec3& w, double a) {
  return {w.x * std::cos(a) - w.y * std::sin(a), w.x * std::sin(a) + w.y * std::cos(a), w.z};
}

// Direction pairs of the BRDF sweep (wi = light, wo = view, n = +z). Mirror
// pairs put h on the normal exactly (the peak of every D, the place a double
// reference resolves exactly); the rest keep θh >= ~1e-4 or on the normal.
std::vector<PairSet> pair_sets(bool fp64) {
  const double az = 0.3;  // view azimuth: off the axes so x and y both round
  std::vector<PairSet> out;
  {
    PairSet s{"mirror", "wi = mirror of wo, cos in {1e-4, 0.1, 0.5, 0.9, 1-1e-4, 1}: h = n", "", {}};
    for (double c : {1e-4, 0.1, 0.5, 0.9, 1 - 1e-4, 1.0}) {
      glm::dvec3 wo = dir(c, az);
      s.pairs.push_back({mirror(wo), wo});
    }
    out.push_back(s);
  }
  {
    PairSet s{"near_mirror", "mirror turned by 1e-3 or 0.1 rad about n", "", {}};
    for (double c : {1e-4, 0.1, 0.5, 0.9, 1 - 1e-4})
      for (double d : {1e-3, 0.1}) {
        glm::dvec3 wo = dir(c, az);
        s.pairs.push_back({rot_z(mirror(wo), d), wo});
      }
    out.push_back(s);
  }
  {
    PairSet s{"grazing", "cos in {1e-20, 1e-7, 1e-4, 1e-2} with itself or 0.5, azimuth 0, pi/2, pi", "", {}};
    std::vector<double> cs = {kTiny[2], 1e-7, 1e-4, 1e-2};
    for (double a : cs)
      for (double b : {a, 0.5})
        for (double phi : {0.0, M_PI / 2, M_PI}) s.pairs.push_back({dir(a, az + phi), dir(b, az)});
    out.push_back(s);
  }
  {
    PairSet s{"normal", "cos in {1, 1-1ulp, 1-1e-7, 1-1e-4} pairwise, azimuth 0 or pi", "", {}};
    std::vector<double> cs = {1.0, one_minus_ulp(fp64), 1 - 1e-7, 1 - 1e-4};
    for (double a : cs)
      for (double b : cs)
        for (double phi : {0.0, M_PI}) s.pairs.push_back({dir(a, az + phi), dir(b, az)});
    out.push_back(s);
  }
  {
    PairSet s{"mid", "cos in {0.2, 0.5, 0.8} pairwise, azimuth 0, pi/2, pi", "", {}};
    for (double a : {0.2, 0.5, 0.8})
      for (double b : {0.2, 0.5, 0.8})
        for (double phi : {0.0, M_PI / 2, M_PI}) s.pairs.push_back({dir(a, az + phi), dir(b, az)});
    out.push_back(s);
  }
  {
    PairSet s{"opposite", "wi ~ -wo along the horizon, z in {0, 2^-149, 1e-30, 1e-20, 1e-7, 1e-4}: h ~ 0/0", "", {}};
    for (double z : {0.0, kTiny[0], kTiny[1], kTiny[2], 1e-7, 1e-4}) {
      glm::dvec3 wo = dir(z, az);
      s.pairs.push_back({glm::dvec3(-wo.x, -wo.y, z), wo});
      s.pairs.push_back({rot_z(glm::dvec3(-wo.x, -wo.y, z), 1e-7), wo});
    }
    out.push_back(s);
  }
  {
    PairSet s{"below_horizon", "wi or wo (or both) below the horizon, and wi = -wo through the surface", "0", {}};
    glm::dvec3 up = dir(0.5, az);
    for (double z : {-kTiny[0], -1e-7, -0.5}) {
      s.pairs.push_back({dir(z, az + M_PI), up});
      s.pairs.push_back({up, dir(z, az + M_PI)});
      s.pairs.push_back({dir(z, az + M_PI), dir(z, az)});
    }
    s.pairs.push_back({{0, 0, -1}, {0, 0, 1}});
    s.pairs.push_back({{0, 0, 1}, {0, 0, -1}});
    out.push_back(s);
  }
  {
    PairSet s{"non_unit", "mirror and mid pairs scaled by 1 -+ 8 ulp, and z = 1 + 1 ulp", "", {}};
    double e = 8 * (fp64 ? 0x1p-52 : 0x1p-23);
    for (double c : {0.2, 0.9, 1.0})
      for (double k : {1 - e, 1 + e}) {
        glm::dvec3 wo = dir(c, az);
        s.pairs.push_back({mirror(wo) * k, wo * k});
        s.pairs.push_back({dir(0.5, az + 2.0) * k, wo});
      }
    s.pairs.push_back({dir(0.6, 1.0), {0, 0, one_plus_ulps(1, fp64)}});
    s.pairs.push_back({{0, 0, one_plus_ulps(1, fp64)}, {0, 0, one_plus_ulps(1, fp64)}});
    out.push_back(s);
  }
  return out;
}

}  // namespace mfv
