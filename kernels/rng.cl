// Philox4x32-10 glue (Random123): key = run seed, counter = (sample index
// low, high, stream, draw). The host's host/rng/philox.hpp uses the same
// header and layout, so a counter gives the same bits on both sides.
#include <Random123/philox.h>

static inline uint4 mfv_philox(ulong seed, uint stream, uint draw, ulong sample) {
  philox4x32_ctr_t ctr = {{(uint)sample, (uint)(sample >> 32), stream, draw}};
  philox4x32_key_t key = {{(uint)seed, (uint)(seed >> 32)}};
  philox4x32_ctr_t r = philox4x32(ctr, key);
  return (uint4)(r.v[0], r.v[1], r.v[2], r.v[3]);
}

// Uniform in (0,1) by integer arithmetic: (2k+1) * 2^-24 with k < 2^23 is
// exact in float and in double, so both sides see the identical number.
static inline real u01_open(uint x) { return (real)((((x >> 9) << 1) | 1u)) * R(5.9604644775390625e-8); }

__kernel void philox_kat(ulong seed, uint stream, uint draw, ulong first, __global uint4* out,
                         __global float* uniforms) {
  size_t i = get_global_id(0);
  uint4 r = mfv_philox(seed, stream, draw, first + i);
  out[i] = r;
  uniforms[i] = (float)u01_open(r.x);
}
