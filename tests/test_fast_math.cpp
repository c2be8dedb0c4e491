// The float programs' own exp, log, log1p, erfc, pow and acos
// (kernels/common.cl mfv_exp ...), which the terms and whole models call so
// that PoCL vectorizes them: their errors against the double library, over
// dense grids of their domains, and their special values; a wrong constant
// planted in mfv_exp or mfv_acos fails the sweep.
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "runtime/opencl.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

using namespace mfv;

namespace {

const char* kKernel = R"(
__kernel void fast_math(__global const float* x, __global float* out) {
  size_t i = get_global_id(0);
  out[5 * i] = mfv_exp(x[i]);
  out[5 * i + 1] = mfv_log(x[i]);
  out[5 * i + 2] = mfv_log1p(x[i]);
  out[5 * i + 3] = mfv_erfc(x[i]);
  out[5 * i + 4] = mfv_pow(fabs(x[i]), 0.2f);  // the Charlie fit's x^c, c in (0.17, 0.2)
}
)";

std::vector<float> run_fast_math(Runtime& rt, const std::vector<float>& x) {
  cl::Program prog = rt.build({"common.cl"}, {}, kKernel);
  cl::Buffer in(rt.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, x.size() * sizeof(float),
                const_cast<float*>(x.data()));
  cl::Buffer out(rt.context(), CL_MEM_WRITE_ONLY, 5 * x.size() * sizeof(float));
  cl::Kernel k(prog, "fast_math");
  k.setArg(0, in);
  k.setArg(1, out);
  rt.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(x.size()));
  std::vector<float> r(5 * x.size());
  rt.queue().enqueueReadBuffer(out, CL_TRUE, 0, r.size() * sizeof(float), r.data());
  return r;
}

// |got - want| in units of the float spacing at want (subnormal spacing below FLT_MIN).
double ulps(float got, double want) {
  if (std::isinf(want) || std::isnan(want))
    return (got == want || (std::isnan(got) && std::isnan(want))) ? 0 : INFINITY;
  double a = std::max(std::fabs(want), double(std::numeric_limits<float>::min()));
  int e;
  std::frexp(a, &e);
  return std::fabs(double(got) - want) / std::ldexp(1.0, e - 24);
}

// n points spread evenly in [lo, hi]
std::vector<float> grid(double lo, double hi, int n) {
  std::vector<float> x;
  for (int i = 0; i <= n; ++i) x.push_back(float(lo + (hi - lo) * i / n));
  return x;
}

// The dense sweep: exp over its finite range (below -104 the result rounds
// to 0, above 88.72 it overflows) at 400001 points; log and pow over every
// binade from the subnormals (2^-149) up to 2^127, 256 points each; log1p
// near its cancellation; erfc over [-10, 10] (into its subnormal tail).
std::vector<float> sweep_points() {
  std::vector<float> x = grid(-104, 89, 400000);
  for (int e = -149; e < 128; ++e)
    for (int k = 0; k < 256; ++k) x.push_back(std::ldexp(1.0f + k / 256.0f, e));
  for (float v : grid(-0.999, 0.999, 40000)) x.push_back(v);
  for (float v : grid(-1e-6, 1e-6, 4000)) x.push_back(v);
  for (float v : grid(-10, 10, 40000)) x.push_back(v);
  return x;
}

struct Worst {
  double exp = 0, log = 0, log1p = 0, erfc = 0, pow = 0;
};

// The largest error of each function over sweep_points, in float ulps of the
// double library's value; for erfc less x², for pow less |ln x| (the parts of
// their bounds that grow with the argument).
Worst worst_ulps(Runtime& rt) {
  const std::vector<float> x = sweep_points();
  const std::vector<float> r = run_fast_math(rt, x);
  Worst w;
  for (size_t i = 0; i < x.size(); ++i) {
    const double v = x[i];
    if (v >= -104 && v <= 88.7) w.exp = std::max(w.exp, ulps(r[5 * i], std::exp(v)));
    if (v > 0) w.log = std::max(w.log, ulps(r[5 * i + 1], std::log(v)));
    if (v > -1) w.log1p = std::max(w.log1p, ulps(r[5 * i + 2], std::log1p(v)));
    // erfc and pow: the error beyond the part that grows with |x| (see the bounds)
    if (v >= -10 && v <= 10) w.erfc = std::max(w.erfc, ulps(r[5 * i + 3], std::erfc(v)) - v * v);
    if (v != 0)
      w.pow =
          std::max(w.pow, ulps(r[5 * i + 4], std::pow(std::fabs(v), double(0.2f))) - std::fabs(std::log(std::fabs(v))));
  }
  return w;
}

// The bounds (docs/performance.md "In-house float math"), derived a priori
// and checked against the measured worst on PoCL 3.1 (in brackets):
// - exp: the Taylor truncation at r^7 is below 0.347^8/8! = 5e-9 relative
//   (0.08 ulp); Cody-Waite's n ln2_hi is exact, so r carries one rounding
//   (|r| <= 0.35: 0.35 ulp of the result), and the Horner steps add about one
//   rounding each, damped by r^k: under 1.5 ulp in all; 2^n is exact. Bound 2 [1.4].
// - log: series truncation 7e-10; f = m - 1 exact (Sterbenz); s = f/(2+f)
//   one rounding, the polynomial and e ln2 add about one ulp. Bound 2 [1.2].
// - log1p: log(u) (2) times x/(u-1): one division, one product. Bound 3 [2.1].
// - erfc: the Numerical Recipes fit has fractional error below 1.2e-7 (2
//   ulps); exp(-z² + p) as two mfv_exp results (2 + 2), z² rounded (half an
//   ulp of z², i.e. z²·2^-24 relative after exp: up to 100·2^-24 = 100 ulps at
//   z = 10, 8 ulps at z = 2.8 where erfc is 7e-5; a relative error e is at
//   most 2^24 e ulps). Bound: 8 + z² ulps.
// - pow(x, y = 0.2) = exp(y log x): log's 2 ulps and the product's half ulp
//   are an absolute error of 2.5·2^-23·y|ln x| = 2^-24 |ln x| in the
//   exponent, |ln x| ulps of the result (43 at x = 2^-149), plus exp's 2.
//   Bound: 2 + |ln x| ulps.
const double kExpUlps = 2, kLogUlps = 2, kLog1pUlps = 3, kErfcUlps = 8, kPowUlps = 2;

}  // namespace

TEST_CASE("mfv_exp, mfv_log, mfv_log1p, mfv_erfc and mfv_pow are within their derived bounds of the double library",
          "[device][fast_math]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  const Worst w = worst_ulps(*rt);
  CAPTURE(w.exp, w.log, w.log1p, w.erfc, w.pow);
  CHECK(w.exp <= kExpUlps);
  CHECK(w.log <= kLogUlps);
  CHECK(w.log1p <= kLog1pUlps);
  CHECK(w.erfc <= kErfcUlps);
  CHECK(w.pow <= kPowUlps);

  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> sx = {0.0f, -0.0f, inf, -inf, nan, -1.0f, -2.0f, 200.0f, -200.0f};
  const std::vector<float> s = run_fast_math(*rt, sx);
  auto at = [&](size_t i, int fn) { return s[5 * i + fn]; };
  CHECK(at(0, 0) == 1.0f);
  CHECK(at(2, 0) == inf);
  CHECK(at(3, 0) == 0.0f);
  CHECK(std::isnan(at(4, 0)));
  CHECK(at(7, 0) == inf);
  CHECK(at(8, 0) == 0.0f);
  CHECK(at(0, 1) == -inf);
  CHECK(at(2, 1) == inf);
  CHECK(std::isnan(at(4, 1)));
  CHECK(std::isnan(at(5, 1)));
  CHECK(at(0, 2) == 0.0f);
  CHECK(at(5, 2) == -inf);
  CHECK(std::isnan(at(6, 2)));
  CHECK(at(0, 3) == 1.0f);
  CHECK(at(2, 3) == 0.0f);
  CHECK(at(3, 3) == 2.0f);
  CHECK(std::isnan(at(4, 3)));
  CHECK(at(0, 4) == 0.0f);  // 0^0.2
  CHECK(at(2, 4) == inf);
  CHECK(at(5, 4) == 1.0f);  // |-1|^0.2
}

TEST_CASE("A wrong constant planted in mfv_exp fails the fast-math sweep", "[device][fast_math][planted]") {
  if (!test::device_runtime()) return;
  const std::pair<const char*, const char*> plants[] = {
      {"r * (1.6666667e-1f", "r * (1.6666e-1f"},            // the 1/3! Taylor coefficient cut to 5 digits
      {"xc - n * 0.693145751953125f", "xc - n * 0.6931f"},  // ln2_hi of Cody-Waite's reduction
  };
  for (const auto& [from, to] : plants) {
    test::PlantedKernelDir dir;
    REQUIRE(dir.replace("common.cl", from, to));
    Runtime planted("", dir.path());
    const Worst w = worst_ulps(planted);
    CAPTURE(from, to, w.exp);
    CHECK(w.exp > kExpUlps);
  }
}

namespace {

const char* kAcosKernel = R"(
__kernel void fast_acos(__global const float* x, __global float* out) {
  size_t i = get_global_id(0);
  out[i] = mfv_acos(x[i]);
}
)";

std::vector<float> run_acos(Runtime& rt, const std::vector<float>& x) {
  cl::Program prog = rt.build({"common.cl"}, {}, kAcosKernel);
  cl::Buffer in(rt.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, x.size() * sizeof(float),
                const_cast<float*>(x.data()));
  cl::Buffer out(rt.context(), CL_MEM_WRITE_ONLY, x.size() * sizeof(float));
  cl::Kernel k(prog, "fast_acos");
  k.setArg(0, in);
  k.setArg(1, out);
  rt.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(x.size()));
  std::vector<float> r(x.size());
  rt.queue().enqueueReadBuffer(out, CL_TRUE, 0, r.size() * sizeof(float), r.data());
  return r;
}

// acos's domain [-1, 1]: 400001 points evenly, the 4096 floats next to each
// end (1 - k 2^-24, where acos ~ sqrt(2 (1 - x)) is steepest), the floats
// around the ±1/2 switch of the two forms, and the tiny arguments down to
// the subnormals.
std::vector<float> acos_points() {
  std::vector<float> x = grid(-1, 1, 400000);
  for (int k = 0; k < 4096; ++k)
    for (float sign : {1.0f, -1.0f}) {
      x.push_back(sign * float(1.0 - k * 0x1p-24));
      x.push_back(sign * float(0.5 + (k - 2048) * 0x1p-25));
      x.push_back(sign * std::ldexp(1.0f + k / 4096.0f, -1 - k % 149));
    }
  return x;
}

// The largest error of mfv_acos over acos_points, in float ulps of the double acos.
double worst_acos_ulps(Runtime& rt) {
  const std::vector<float> x = acos_points();
  const std::vector<float> r = run_acos(rt, x);
  double w = 0;
  for (size_t i = 0; i < x.size(); ++i) w = std::max(w, ulps(r[i], std::acos(double(x[i]))));
  return w;
}

// The bound, derived a priori and checked against the measured worst on
// PoCL 3.1 (1.24 ulps, docs/performance.md): the fit's own error, computed
// in double over t in [0, 1/2] with the float coefficients, is below 5.5e-9
// of asin (0.09 ulp); a² and P's steps add about 0.05 ulp (t z P is under
// 5 % of asin(t)) and the last sum half an ulp: asin within 0.65 ulp of its
// own. |x| <= 1/2: asin <= 0.524 against a result >= π/3 (twice the ulp),
// so 0.33 ulp, plus π/2's float (0.37) and the subtraction (0.5): 1.2 ulps.
// Above 1/2: 1 - a and the halving are exact, the square root rounds once
// (half an ulp through asin ~ t), the doubling is exact: 1.2 ulps. x < 0:
// π - r adds π's float (0.36 ulp) and a rounding (0.5), r's error counting
// at most once (the result is at least r): 2.1 ulps. Bound 3.
const double kAcosUlps = 3;

}  // namespace

TEST_CASE("mfv_acos is within its derived bound of the double library, exact at the ends", "[device][fast_math]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  const double w = worst_acos_ulps(*rt);
  CAPTURE(w);
  CHECK(w <= kAcosUlps);

  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> sx = {1.0f, -1.0f, 0.0f, -0.0f, nan, 1.0f + 0x1p-23f, -1.0f - 0x1p-23f, 0.5f, -0.5f};
  const std::vector<float> s = run_acos(*rt, sx);
  CHECK(s[0] == 0.0f);                        // acos(1), exactly
  CHECK(s[1] == float(M_PI));                 // acos(-1): π rounded
  CHECK(s[2] == float(M_PI / 2));             // acos(0)
  CHECK(s[3] == float(M_PI / 2));             // acos(-0)
  CHECK(std::isnan(s[4]));                    // NaN stays NaN
  CHECK(s[5] == 0.0f);                        // a cosine rounded above 1: acos(1), not NaN
  CHECK(s[6] == float(M_PI));                 // ... below -1: acos(-1)
  CHECK(ulps(s[7], std::acos(0.5)) <= kAcosUlps);   // π/3 at the switch of the two forms
  CHECK(ulps(s[8], std::acos(-0.5)) <= kAcosUlps);  // 2π/3
}

TEST_CASE("A wrong constant planted in mfv_acos fails its sweep", "[device][fast_math][planted]") {
  if (!test::device_runtime()) return;
  const std::pair<const char*, const char*> plants[] = {
      {"(1.6666752422e-1f", "(1.6666e-1f"},   // asin's leading coefficient cut to 5 digits
      {"hi = a > 0.5f", "hi = a > 0.75f"},    // the switch moved: asin's fit (made for z <= 1/4) used to z = 9/16
  };
  for (const auto& [from, to] : plants) {
    test::PlantedKernelDir dir;
    REQUIRE(dir.replace("common.cl", from, to));
    Runtime planted("", dir.path());
    const double w = worst_acos_ulps(planted);
    CAPTURE(from, to, w);
    CHECK(w > kAcosUlps);
  }
}
