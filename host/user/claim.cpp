#include "user/claim.hpp"

#include "catalog/catalog.hpp"
#include "catalog/roughness.hpp"
#include "util/error.hpp"
#include "util/parse.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace mfv {
namespace {

// The model parameter behind each reference slot: (term, index) or kd.
struct Slot {
  const Term* term;
  size_t index;
  std::string name() const { return term ? term->params[index].name : "kd"; }
};

std::vector<std::pair<int, Slot>> slots_of(const Claim& c) {
  std::vector<std::pair<int, Slot>> s;
  if (!c.d->params.empty()) s.push_back({0, {c.d, 0}});
  if (!c.g->params.empty()) s.push_back({1, {c.g, 0}});
  for (size_t i = 0; i < c.f->params.size(); ++i) s.push_back({int(2 + i), {c.f, i}});
  s.push_back({4, {nullptr, 0}});
  return s;
}

}  // namespace

ref::BrdfSpec Claim::at(const std::vector<double>& values) const {
  double v[5];
  for (int k = 0; k < 5; ++k) {
    const Source& s = slot[k];
    v[k] = s.param < 0 ? s.constant : values[size_t(s.param)] * (s.squared ? values[size_t(s.param)] : 1.0);
  }
  for (auto& [k, sl] : slots_of(*this)) {
    if (sl.term) {
      validate_param(*sl.term, sl.index, v[k]);
    } else if (!(v[k] >= 0.0 && v[k] <= 1.0)) {
      throw Error(fmt::format("--as {}: kd = {} is out of range [0, 1]", spec, v[k]));
    }
  }
  return {d, g, f, v[0], v[1], v[2], v[3], v[4]};
}

double Claim::proposal(const std::vector<double>& values) const {
  if (!d || d->roughness == Roughness::None) return 0.0;
  try {
    return proposal_width(*d, alpha_from_native(d->roughness, at(values).pd));
  } catch (const Error&) {
    return 0.0;
  }
}

std::string Claim::mapping(const UserBrdf& u) const {
  std::string out;
  std::vector<std::string> seen;
  for (auto& [k, sl] : slots_of(*this)) {
    const Source& s = slot[k];
    if (std::find(seen.begin(), seen.end(), sl.name()) != seen.end()) continue;  // D and G share alpha
    seen.push_back(sl.name());
    if (!out.empty()) out += " ";
    out += sl.name() + "=" +
           (s.param < 0 ? fmt::format("{:g}", s.constant) : u.params[size_t(s.param)].name + (s.squared ? "^2" : ""));
  }
  return out;
}

Claim parse_claim(const std::string& as, const std::vector<std::string>& map, const UserBrdf& u) {
  Claim c;
  c.spec = as;
  auto parts = split(as, '/');
  if (parts.size() != 3) throw Error(fmt::format("--as '{}': name a catalog model as D/G/F (see 'mfv list')", as));
  c.d = &find_term(parts[0]);
  c.g = &find_term(parts[1]);
  c.f = &find_term(parts[2]);
  if (c.d->kind != Kind::D || c.g->kind != Kind::G || c.f->kind != Kind::F)
    throw Error(fmt::format("--as '{}' must name a D, a G and an F term, in that order", as));

  std::map<std::string, std::string> given;
  for (auto& entry : map)
    for (auto& kv : split(entry, ',')) {
      auto eq = kv.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == kv.size())
        throw Error(
            fmt::format("--map wants NAME=EXPR (EXPR a parameter of {}, PARAM^2 or a number), got '{}'", u.path, kv));
      given[kv.substr(0, eq)] = kv.substr(eq + 1);
    }
  auto slots = slots_of(c);
  std::string names;
  for (auto& [k, sl] : slots)
    if (names.find(sl.name()) == std::string::npos) names += (names.empty() ? "" : ", ") + sl.name();
  for (auto& [name, expr] : given) {
    bool known = false;
    for (auto& [k, sl] : slots) known = known || sl.name() == name;
    if (!known)
      throw Error(fmt::format("--map {}: {} has no parameter {} (its parameters: {})", name, as, name, names));
  }
  auto user_index = [&](const std::string& n) {
    for (size_t i = 0; i < u.params.size(); ++i)
      if (u.params[i].name == n) return int(i);
    return -1;
  };
  for (auto& [k, sl] : slots) {
    Claim::Source& s = c.slot[k];
    auto it = given.find(sl.name());
    if (it == given.end()) {
      s.param = user_index(sl.name());
      if (s.param < 0 && sl.term)
        throw Error(
            fmt::format("--as {}: no value for {}.{}; give --map {}=NAME (a parameter of {}), NAME^2 or a number", as,
                        sl.term->id, sl.name(), sl.name(), u.name));
      continue;  // kd without a user parameter: 0
    }
    std::string expr = it->second;
    if (expr.size() > 2 && expr.compare(expr.size() - 2, 2, "^2") == 0) s.squared = true, expr.resize(expr.size() - 2);
    s.param = user_index(expr);
    if (s.param >= 0) continue;
    if (s.squared) throw Error(fmt::format("--map {}={}^2: {} has no parameter {}", sl.name(), expr, u.name, expr));
    s.constant =
        parse_number(fmt::format("--map {} (neither a parameter of {} nor a number)", sl.name(), u.name), expr);
  }
  return c;
}

}  // namespace mfv
