#include "checks/profile.hpp"

#include "util/error.hpp"

#include <fmt/format.h>

#include <cmath>

namespace mfv {

int profile_density(const std::string& name) {
  if (name.empty() || name == "default") return 1;
  if (name == "deep") return 3;
  throw Error(fmt::format("unknown --profile '{}' (profiles: default, deep)", name));
}

namespace {

double between(double a, double b, double t, bool geometric) {
  return geometric ? a * std::pow(b / a, t) : a + (b - a) * t;
}

}  // namespace

std::vector<double> densify(const std::vector<double>& v, int density) {
  if (density <= 1 || v.size() < 2) return v;
  std::vector<double> out;
  for (size_t i = 0; i + 1 < v.size(); ++i) {
    const bool geometric = v[i] > 0 && v[i + 1] > 0;
    for (int k = 0; k < density; ++k) out.push_back(between(v[i], v[i + 1], double(k) / density, geometric));
  }
  out.push_back(v.back());
  return out;
}

std::vector<ParamPoint> densify_points(const Term& f, int density) {
  const std::vector<ParamPoint>& v = f.check_points;
  if (density <= 1 || v.size() < 2 || f.params.empty()) return v;
  std::vector<ParamPoint> out;
  for (size_t i = 0; i + 1 < v.size(); ++i) {
    out.push_back(v[i]);
    for (int k = 1; k < density; ++k) {
      const double t = double(k) / density;
      ParamPoint p{between(v[i].p0, v[i + 1].p0, t, false), between(v[i].p1, v[i + 1].p1, t, false), ""};
      p.label = fmt::format("{}={:.4g}", f.params[0].name, p.p0);
      if (f.params.size() > 1) p.label += fmt::format(",{}={:.4g}", f.params[1].name, p.p1);
      out.push_back(p);
    }
  }
  out.push_back(v.back());
  return out;
}

SuitePlans sample_plans(const SuitePlans& sp, size_t per_plan) {
  auto cut = [&](const Plan& p) {
    Plan q = p;
    q.specs.clear();
    q.points.clear();
    const size_t n = p.specs.size(), k = std::min(n, per_plan);
    for (size_t j = 0; j < k; ++j) {
      const size_t i = j * n / k;
      q.specs.push_back(p.specs[i]);
      q.points.push_back(p.points[i]);
    }
    q.reference_pick = std::vector<size_t>{};
    return q;
  };
  SuitePlans out;
  for (auto& p : sp.plans) out.plans.push_back(cut(p));
  out.reciprocity = cut(sp.reciprocity);
  return out;
}

}  // namespace mfv
