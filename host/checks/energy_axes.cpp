#include "checks/energy_axes.hpp"

#include "catalog/roughness.hpp"
#include "util/error.hpp"
#include "util/parse.hpp"

#include <fmt/format.h>

#include <cmath>

namespace mfv {

namespace {

constexpr uint64_t kMaxAxis = 1024;  // values per axis

uint64_t axis_count(const std::string& what, const std::string& form, const std::string& text, uint64_t lo) {
  const uint64_t n = parse_unsigned(fmt::format("{} {}", what, form), text, kMaxAxis);
  if (n < lo) throw Error(fmt::format("{} {}:{}: needs at least {} values", what, form, text, lo));
  return n;
}

}  // namespace

std::vector<double> parse_energy_axis(const std::string& what, const std::string& text) {
  if (text.empty()) throw Error(fmt::format("{}: empty (a list '0.1,0.5,1' or lin:A:B:N, centers:N, edges:N)", what));
  const std::vector<std::string> f = split(text, ':');
  std::vector<double> v;
  if (f.size() > 1) {
    const std::string& form = f[0];
    if (form == "lin" && f.size() == 4) {
      const double a = parse_finite(what + " lin:A", f[1]), b = parse_finite(what + " lin:B", f[2]);
      const uint64_t n = axis_count(what, "lin:A:B", f[3], 1);
      if (n == 1 && a != b) throw Error(fmt::format("{} {}: one value needs A = B", what, text));
      for (uint64_t i = 0; i < n; ++i) v.push_back(n == 1 ? a : a + (b - a) * double(i) / double(n - 1));
      if (n > 1) v.back() = b;  // exactly B, not B up to rounding
    } else if (form == "log" && f.size() == 4) {
      const double a = parse_finite(what + " log:A", f[1]), b = parse_finite(what + " log:B", f[2]);
      const uint64_t n = axis_count(what, "log:A:B", f[3], 2);
      if (!(a > 0 && b > 0)) throw Error(fmt::format("{} {}: log spacing needs A, B > 0", what, text));
      for (uint64_t i = 0; i < n; ++i) v.push_back(a * std::pow(b / a, double(i) / double(n - 1)));
      v.front() = a, v.back() = b;  // exactly A and B
    } else if ((form == "centers" || form == "centres") && f.size() == 2) {
      const uint64_t n = axis_count(what, "centers", f[1], 1);
      for (uint64_t i = 0; i < n; ++i) v.push_back((double(i) + 0.5) / double(n));
    } else if (form == "edges" && f.size() == 2) {
      const uint64_t n = axis_count(what, "edges", f[1], 2);
      for (uint64_t i = 0; i < n; ++i) v.push_back(double(i) / double(n - 1));
    } else {
      throw Error(fmt::format("{} '{}': not a list or lin:A:B:N, log:A:B:N, centers:N, edges:N", what, text));
    }
    return v;
  }
  const std::vector<std::string> parts = split(text, ',');
  if (parts.size() > kMaxAxis) throw Error(fmt::format("{}: more than {} values", what, kMaxAxis));
  if (text.back() == ',') throw Error(fmt::format("{} '{}': empty value after the last comma", what, text));
  for (size_t i = 0; i < parts.size(); ++i) v.push_back(parse_finite(fmt::format("{} value {}", what, i + 1), parts[i]));
  return v;
}

std::pair<double, double> parse_energy_point(const std::string& text) {
  const std::vector<std::string> f = split(text, ',');
  if (f.size() != 2 || text.back() == ',') throw Error(fmt::format("--at '{}': want MU,ALPHA (e.g. 0.5,0.25)", text));
  return {parse_finite("--at MU", f[0]), parse_finite("--at ALPHA", f[1])};
}

RoughnessAxis parse_roughness_axis(const std::string& text) {
  if (text == "alpha") return RoughnessAxis::Alpha;
  if (text == "r2") return RoughnessAxis::R2;
  throw Error(fmt::format("--roughness '{}': want alpha (the width) or r2 (alpha = r², r perceptual)", text));
}

void set_energy_axes(EnergyOptions& opt, const std::vector<double>& mu, const std::vector<double>& width,
                     RoughnessAxis param, bool paired) {
  const char* wname = param == RoughnessAxis::R2 ? "roughness r" : "alpha";
  for (double m : mu)
    if (!(m >= 0 && m <= 1)) throw Error(fmt::format("mu = {}: a view cosine must be in [0, 1]", m));
  for (double w : width)
    if (!(w >= 0 && w <= (param == RoughnessAxis::R2 ? std::sqrt(10.0) : 10.0)))
      throw Error(fmt::format("{} = {}: must be in [0, {}] (alpha <= 10)", wname, w,
                              param == RoughnessAxis::R2 ? "sqrt(10)" : "10"));
  if (paired && mu.size() != width.size()) throw Error("points: as many mu as widths");
  opt.mu_axis = mu;
  opt.alpha_axis.clear();
  opt.roughness.clear();
  for (double w : width) opt.alpha_axis.push_back(param == RoughnessAxis::R2 ? alpha_from_perceptual(w) : w);
  if (param == RoughnessAxis::R2) opt.roughness = width;
  opt.paired = paired;
}

}  // namespace mfv
