#include "user/user_twin.hpp"

#include "runtime/integrator.hpp"
#include "user/source_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace mfv {

namespace {

// The suffix to drop from a literal token: 1 for "2.5f"/"2.5F", else 0.
size_t float_suffix(const Token& t) {
  if (t.kind != Token::Number || !floating_literal(t.text)) return 0;
  const char c = t.text.back();
  return c == 'f' || c == 'F' ? 1 : 0;
}

}  // namespace

std::string twin_text(const std::string& path, const std::string& text) {
  std::string out;
  size_t at = 0;
  for (const Token& t : tokenize(path, text)) {
    if (t.kind == Token::Directive) {
      // a one-line #define's body (a directive with line splices stays as written)
      const std::string raw = text.substr(t.begin, t.end - t.begin);
      if (raw != t.text || raw.find("define") == std::string::npos) continue;
      const size_t hash = raw.find('#');
      out += text.substr(at, t.begin - at) + raw.substr(0, hash + 1) + twin_text(path, raw.substr(hash + 1));
      at = t.end;
      continue;
    }
    const size_t drop = float_suffix(t);
    if (drop == 0) continue;
    out += text.substr(at, t.end - drop - at);
    at = t.end;
  }
  return out + text.substr(at);
}

UserBrdf twin_of(const UserBrdf& u) {
  UserBrdf t = u;
  for (auto& s : t.sources) s.text = twin_text(s.name, s.text);
  return t;
}

std::vector<double> twin_rounding(Runtime& rt, const cl::Program& f, const cl::Program& d,
                                  const std::vector<IntegralSpec>& specs, uint32_t n, uint64_t seed) {
  std::vector<double> out(specs.size(), 0.0);
  if (specs.empty() || n == 0) return out;
  const std::vector<double> kf = program_sample_values<double>(rt, f, specs, n, seed);
  const std::vector<double> kd = program_sample_values<double>(rt, d, specs, n, seed);
  for (size_t j = 0; j < specs.size(); ++j) {
    double sum = 0, sq = 0;
    uint32_t m = 0;
    for (uint32_t k = 0; k < n; ++k) {
      const double a = kf[j * n + k], b = kd[j * n + k];
      if (!std::isfinite(a) || !std::isfinite(b)) continue;
      sum += a - b;
      sq += (a - b) * (a - b);
      ++m;
    }
    if (m < 2) continue;
    const double mean = sum / m, var = std::max(0.0, (sq - m * mean * mean) / (m - 1));
    out[j] = std::fabs(mean) + 3.0 * std::sqrt(var / m);
  }
  return out;
}

void explain_twin_verdicts(SuiteReport& rep, double z_threshold) {
  for (auto& p : rep.points) {
    if (p.bounded || p.rounding_bound <= 0 || p.inconclusive) continue;
    const double dev = p.upper_only ? p.deviation : std::fabs(p.deviation);
    const double noise = z_threshold * p.stderr_;
    if (p.failed)
      p.detail = fmt::format(
          "formula error: off by {:.3g}, beyond noise ({:.2g}) and the float rounding the double twin measures "
          "({:.2g})",
          p.deviation, noise, p.rounding_bound);
    else if (dev > noise)
      p.detail = fmt::format(
          "float conditioning (within the derived bound): off by {:.3g}, beyond noise ({:.2g}) but within the float "
          "rounding the double twin measures ({:.2g})",
          p.deviation, noise, p.rounding_bound);
  }
}

}  // namespace mfv
