// mfv bench's peak row: the device's attainable single-precision rate in
// the same run as the integrands. Each work-item runs MFV_PEAK_CHAINS
// independent chains of fused multiply-adds x <- fma(x, a, b) on float8
// (2 flops per lane), MFV_PEAK_STEPS steps long. float8 is the width PoCL
// vectorizes the integrands' work-item loops to on both of its x86 targets
// (haswell and skylake-avx512: 8 lanes, one ymm register); written as a
// vector because scalar chains in one work-item would be packed by LLVM's
// SLP vectorizer into one long dependent chain. Eight independent chains
// cover the FMA latency on both pipes of a core (2 pipes x 4 cycles). No
// memory traffic but one store per work-item. The chains converge to
// b / (1 - a) for 0 < a < 1: no overflow, no subnormals.
#define MFV_PEAK_CHAINS 8  // the flop count per work-item: 2 * 8 lanes * CHAINS * STEPS
#define MFV_PEAK_STEPS 64

__kernel void fma_peak(float a, float b, __global float* restrict out) {
  size_t i = get_global_id(0);
  float8 va = (float8)(a), vb = (float8)(b);
  float8 x0 = (float8)((float)(i & 255u) * 1e-3f) + (float8)(0.0f, 0.01f, 0.02f, 0.03f, 0.04f, 0.05f, 0.06f, 0.07f);
  float8 x1 = x0 + 0.1f, x2 = x0 + 0.2f, x3 = x0 + 0.3f, x4 = x0 + 0.4f, x5 = x0 + 0.5f, x6 = x0 + 0.6f,
         x7 = x0 + 0.7f;
  for (int k = 0; k < MFV_PEAK_STEPS; ++k) {
    x0 = fma(x0, va, vb);
    x1 = fma(x1, va, vb);
    x2 = fma(x2, va, vb);
    x3 = fma(x3, va, vb);
    x4 = fma(x4, va, vb);
    x5 = fma(x5, va, vb);
    x6 = fma(x6, va, vb);
    x7 = fma(x7, va, vb);
  }
  float8 s = ((x0 + x1) + (x2 + x3)) + ((x4 + x5) + (x6 + x7));
  out[i] = ((s.s0 + s.s1) + (s.s2 + s.s3)) + ((s.s4 + s.s5) + (s.s6 + s.s7));
}
