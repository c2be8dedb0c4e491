// Philox4x32-10 on the host, same header and counter layout as kernels/rng.cl:
// key = seed, counter = (sample low, sample high, stream, draw).
#pragma once

#include <Random123/philox.h>

#include <array>
#include <cstdint>

namespace mfv {

inline std::array<uint32_t, 4> philox(uint64_t seed, uint32_t stream, uint32_t draw, uint64_t sample) {
  r123::Philox4x32 gen;
  r123::Philox4x32::ctr_type ctr = {{static_cast<uint32_t>(sample), static_cast<uint32_t>(sample >> 32), stream, draw}};
  r123::Philox4x32::key_type key = {{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32)}};
  auto r = gen(ctr, key);
  return {r[0], r[1], r[2], r[3]};
}

// (2k+1) * 2^-24 with k < 2^23: exact in float and double, never 0 or 1.
inline double u01_open(uint32_t x) { return static_cast<double>(((x >> 9) << 1) | 1u) * 0x1.0p-24; }

}  // namespace mfv
