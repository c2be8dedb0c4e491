#include "checks/streams.hpp"

#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "checks/registry.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

#include <cstring>
#include <unordered_map>

namespace mfv {

namespace {

// A float's exact value (hex float), so that keys differ where values do.
std::string exact(float v) { return fmt::format("{:a}", double(v)); }

std::string term_id(int32_t index) {
  if (index < 0 || size_t(index) >= catalog().size()) return fmt::format("#{}", index);
  return catalog()[size_t(index)].id;
}

}  // namespace

std::string integral_key(const std::string& check, const IntegralSpec& s) {
  static const IntegralSpec def;
  std::string k = fmt::format("check={} kind={}", check, s.check);
  auto add_float = [&](const char* name, float v, float d) {
    if (std::memcmp(&v, &d, sizeof v) != 0) k += fmt::format(" {}={}", name, exact(v));
  };
  auto add_int = [&](const char* name, int64_t v, int64_t d) {
    if (v != d) k += fmt::format(" {}={}", name, v);
  };
  if (s.model == MFV_MODEL_MICROFACET) {
    // the terms the kind's integrand reads (checks/registry.hpp; a check of
    // no kind, as a test's, keys every term it carries)
    const CheckKind* kind = find_check_kind(check);
    const int n = kind ? kind->terms_read : 3;
    k += " d=" + term_id(s.d);
    if (n > 1) k += " g=" + term_id(s.g);
    if (n > 2) k += " f=" + term_id(s.f);
  } else if (const Model* m = model_by_number(s.model)) {
    k += " model=" + m->id;
  } else {
    k += fmt::format(" model=#{}", s.model);  // user code (mfv check)
  }
  add_int("estimator", s.estimator, def.estimator);
  add_int("channel", s.channel, def.channel);
  add_float("pd", s.pd, def.pd);
  add_float("pg", s.pg, def.pg);
  add_float("pd2", s.pd2, def.pd2);
  add_float("pg2", s.pg2, def.pg2);
  add_float("f0", s.f0, def.f0);
  add_float("f1", s.f1, def.f1);
  add_float("kd", s.kd, def.kd);
  for (int i = 0; i < 7; ++i) add_float(fmt::format("p{}", i).c_str(), s.p[i], def.p[i]);
  add_float("eta", s.eta, def.eta);
  add_int("side", s.side, def.side);
  add_int("bsdf", s.bsdf, def.bsdf);
  add_int("lobe", s.lobe, def.lobe);
  add_float("cos_o", s.cos_o, def.cos_o);
  add_float("phi_o", s.phi_o, def.phi_o);
  add_float("width", s.width, def.width);
  add_float("width_y", s.width_y, def.width_y);
  return k;
}

uint64_t stream_of_key(const std::string& key) {
  uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a 64 (Fowler, Noll, Vo)
  for (unsigned char c : key) h = (h ^ c) * 0x100000001b3ull;
  h ^= h >> 30;  // splitmix64's finalizer (Steele, Lea, Flood 2014): every key bit reaches every stream bit
  h *= 0xbf58476d1ce4e5b9ull;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebull;
  h ^= h >> 31;
  return h >> 8;  // 56 bits: 32 in counter word 2, 24 above the draw in word 3
}

void assign_streams(const std::string& check, std::vector<IntegralSpec>& specs) {
  std::unordered_map<uint64_t, size_t> seen;
  seen.reserve(specs.size());
  for (size_t i = 0; i < specs.size(); ++i) {
    const std::string key = integral_key(check, specs[i]);
    const uint64_t st = stream_of_key(key);
    auto [it, fresh] = seen.emplace(st, i);
    if (!fresh) {
      const std::string other = integral_key(check, specs[it->second]);
      throw Error(other == key ? fmt::format("internal: check {} holds the same integral twice ({})", check, key)
                               : fmt::format("internal: integrals '{}' and '{}' hash to one stream ({:#x}); "
                                             "checks/streams.hpp",
                                             other, key, st));
    }
    specs[i].stream = uint32_t(st);
    specs[i].stream_hi = uint32_t(st >> 32);
  }
}

}  // namespace mfv
