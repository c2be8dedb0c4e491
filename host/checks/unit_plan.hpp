// What every sharded command's plan shares (docs/scale.md): its digest and,
// where a shard runs whole units, each unit's estimated cost
// (checks/shard.hpp cut_by_cost cuts them).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mfv {

// FNV-1a, 64-bit: the digest of a plan (plan_hash, energy's, agree's and
// stability's), for equality of plans, not for security.
struct PlanDigest {
  uint64_t h = 14695981039346656037ull;
  void bytes(const void* p, size_t n) {
    auto* c = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
  }
  void text(const std::string& s) { bytes(s.c_str(), s.size() + 1); }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
  void doubles(const std::vector<double>& v) {
    value(uint64_t(v.size()));
    if (!v.empty()) bytes(v.data(), v.size() * sizeof(double));
  }
  std::string hex() const;  // 16 hex digits
};

// A plan cut into units that a shard runs whole (mfv energy's cells, mfv
// agree's and mfv stability's cases): each unit's estimated cost, in plan
// order, and the plan's digest (16 hex digits) over everything that fixes
// the units' values but the seed.
struct UnitPlan {
  std::vector<uint64_t> cost;
  std::string hash;
};

}  // namespace mfv
