// Philox4x32-10 (Salmon et al. 2011, "Parallel random numbers: as easy as
// 1, 2, 3"): key = run seed, counter = (sample index low, high, stream,
// draw | stream_hi << 8): an integral's 56-bit stream (IntegralSpec::stream,
// stream_hi: a hash of its identity, host/checks/streams.hpp) and the draw
// (0..255) that says what the uniforms are for. The host's host/rng/philox.hpp runs Random123's own code with the
// same layout, so a counter gives the same bits on both sides;
// tests/test_philox.cpp checks this kernel against Random123's published
// known answers. The rounds are written out on uint values (Random123's
// multipliers and Weyl constants) rather than through Random123's OpenCL
// path, which passes the four counter words as two 64-bit words: PoCL then
// vectorizes every xor and shift of the generator in 64-bit lanes, four
// work-items to an AVX2 register instead of eight (albedo_values ran 1.2x
// slower with it).
#define PHILOX_M0 0xD2511F53u
#define PHILOX_M1 0xCD9E8D57u
#define PHILOX_W0 0x9E3779B9u
#define PHILOX_W1 0xBB67AE85u

static inline uint4 mfv_philox(ulong seed, uint stream, uint draw, ulong sample) {
  uint c0 = (uint)sample, c1 = (uint)(sample >> 32), c2 = stream, c3 = draw;
  uint k0 = (uint)seed, k1 = (uint)(seed >> 32);
#pragma unroll
  for (int round = 0; round < 10; ++round) {
    ulong p0 = (ulong)PHILOX_M0 * c0, p1 = (ulong)PHILOX_M1 * c2;  // 32 x 32 -> 64-bit products
    uint n0 = (uint)(p1 >> 32) ^ c1 ^ k0, n2 = (uint)(p0 >> 32) ^ c3 ^ k1;
    c1 = (uint)p1;
    c3 = (uint)p0;
    c0 = n0;
    c2 = n2;
    k0 += PHILOX_W0;  // the key's Weyl sequence (bumped before every round but the first)
    k1 += PHILOX_W1;
  }
  return (uint4)(c0, c1, c2, c3);
}

// mfv_philox's bits, each 32 x 32-bit product's high word from its own
// expression (the 64-bit product shifted) and its low word as a 32-bit
// product: LLVM then forms a vector high multiply and a vpmulld in 32-bit
// lanes, where mfv_philox's 64-bit products take eight lanes as two AVX2
// registers and cross-lane shuffles to split them. albedo_values, the
// whole models' kernels (kernels/model_values.cl, reciprocity.cl: with it SLP
// does not pair the two products into a 2-lane multiply, which kept them
// scalar on skylake-avx512) and the reciprocity pairs draw with it (issue
// 31, docs/performance.md); reciprocity_values_microfacet (mfv bench on
// AVX2, 5 alternated rounds: 20.2 % of the peak row against 19.4 %,
// medians; llvm-mca on the kernel's loop of 32 pairs, znver3 1060 -> 1021
// cycles, skylake-avx512 1022 -> 1007); d_norm keeps
// mfv_philox, whose loop on skylake-avx512 grew from 109 to 142 instructions
// with it (docs/performance.md, issue 31). tests/test_philox.cpp checks both.
static inline uint4 mfv_philox_split(ulong seed, uint stream, uint draw, ulong sample) {
  uint c0 = (uint)sample, c1 = (uint)(sample >> 32), c2 = stream, c3 = draw;
  uint k0 = (uint)seed, k1 = (uint)(seed >> 32);
#pragma unroll
  for (int round = 0; round < 10; ++round) {
    uint h0 = (uint)(((ulong)PHILOX_M0 * c0) >> 32), h1 = (uint)(((ulong)PHILOX_M1 * c2) >> 32);
    uint n0 = h1 ^ c1 ^ k0, n2 = h0 ^ c3 ^ k1;
    c1 = PHILOX_M1 * c2;  // the products' low words, mod 2^32
    c3 = PHILOX_M0 * c0;
    c0 = n0;
    c2 = n2;
    k0 += PHILOX_W0;
    k1 += PHILOX_W1;
  }
  return (uint4)(c0, c1, c2, c3);
}

// Uniform in (0,1) by integer arithmetic: (2k+1) * 2^-24 with k < 2^23 is
// exact in float and in double, so both sides see the identical number.
static inline real u01_open(uint x) { return (real)((((x >> 9) << 1) | 1u)) * R(5.9604644775390625e-8); }

// u01_open(x) < MIX_I_COS (0.2, albedo's cosine-lobe share) as an integer
// compare, the same truth for every x: u01_open(x) = (2k + 1) 2^-24 with
// k = x >> 9, below 0.2 exactly when 2k + 1 <= 3355443 (0.2 * 2^24 =
// 3355443.2 in double, 3355443.25 with float's 0.2f), that is when k <=
// 1677721, x < 1677722 * 2^9. albedo_values takes it so that LLVM's SLP pass
// finds no two float compares of one sample's words (r.x here, r.y's
// u_pick < MIX_COS) to pair into a 2-lane vector, which PoCL's work-item
// vectorizer refuses (kernels/albedo.cl). tests/test_philox.cpp checks it
// against both compares for every x.
#define MFV_U01_BELOW_FIFTH 858993664u
static inline bool u01_open_below_fifth(uint x) { return x < MFV_U01_BELOW_FIFTH; }

// Known-answer kernels (tests/test_philox.cpp): each generator's words and
// first uniform at counters first + i.
#define MFV_PHILOX_KAT(NAME, GENERATOR)                                                                          \
  __kernel void NAME(ulong seed, uint stream, uint draw, ulong first, __global uint4* out,                       \
                     __global float* uniforms) {                                                                 \
    size_t i = get_global_id(0);                                                                                 \
    uint4 r = GENERATOR(seed, stream, draw, first + i);                                                          \
    out[i] = r;                                                                                                  \
    uniforms[i] = (float)u01_open(r.x);                                                                          \
  }
MFV_PHILOX_KAT(philox_kat, mfv_philox)
MFV_PHILOX_KAT(philox_split_kat, mfv_philox_split)
