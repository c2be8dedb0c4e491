#include "device_fixture.hpp"
#include "rng/philox.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <regex>
#include <string>

using namespace mfv;

// Known answers from Random123's kat_vectors (Salmon et al. 2011) for
// Philox4x32-10: counter, key -> output.
struct Kat {
  std::array<uint32_t, 4> ctr;
  std::array<uint32_t, 2> key;
  std::array<uint32_t, 4> out;
};
static const Kat kKats[] = {
    {{0, 0, 0, 0}, {0, 0}, {0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}},
    {{0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff},
     {0xffffffff, 0xffffffff},
     {0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}},
    {{0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344},
     {0xa4093822, 0x299f31d0},
     {0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}},
};

TEST_CASE("Philox4x32-10 on the host matches the published known answers", "[rng][kat]") {
  for (auto& k : kKats) {
    uint64_t seed = k.key[0] | (uint64_t(k.key[1]) << 32);
    uint64_t sample = k.ctr[0] | (uint64_t(k.ctr[1]) << 32);
    auto r = philox(seed, k.ctr[2], k.ctr[3], sample);
    CHECK(r == k.out);
  }
}

TEST_CASE("u01_open maps every 32-bit word strictly inside (0,1), exactly in float", "[rng]") {
  for (uint32_t x : {0u, 1u, 511u, 512u, 0x80000000u, 0xfffffe00u, 0xffffffffu}) {
    CAPTURE(x);
    double u = u01_open(x);
    CHECK(u > 0.0);
    CHECK(u < 1.0);
    CHECK(static_cast<double>(static_cast<float>(u)) == u);
  }
}

TEST_CASE("Philox on the OpenCL device gives the host's bits and uniforms", "[device][rng][kat]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  cl::Program prog = rt->build({"common.cl", "rng.cl"}, {});
  // mfv_philox and mfv_philox_split (kernels/rng.cl), each
  const std::string kernel = GENERATE(as<std::string>{}, "philox_kat", "philox_split_kat");
  CAPTURE(kernel);
  cl::Kernel k(prog, kernel.c_str());
  const size_t n = 4096;
  const uint64_t seed = 0x0123456789abcdefull, first = 0xfffffff0ull;  // crosses the 32-bit boundary
  cl::Buffer out(rt->context(), CL_MEM_WRITE_ONLY, n * 4 * sizeof(cl_uint));
  cl::Buffer uni(rt->context(), CL_MEM_WRITE_ONLY, n * sizeof(float));
  k.setArg(0, static_cast<cl_ulong>(seed));
  k.setArg(1, cl_uint(7));
  k.setArg(2, cl_uint(3));
  k.setArg(3, static_cast<cl_ulong>(first));
  k.setArg(4, out);
  k.setArg(5, uni);
  rt->queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n));
  std::vector<cl_uint> bits(4 * n);
  std::vector<float> u(n);
  rt->queue().enqueueReadBuffer(out, CL_TRUE, 0, bits.size() * sizeof(cl_uint), bits.data());
  rt->queue().enqueueReadBuffer(uni, CL_TRUE, 0, u.size() * sizeof(float), u.data());
  size_t mismatches = 0;
  for (size_t i = 0; i < n; ++i) {
    auto r = philox(seed, 7, 3, first + i);
    for (int j = 0; j < 4; ++j) mismatches += bits[4 * i + j] != r[j];
    mismatches += static_cast<double>(u[i]) != u01_open(r[0]);
  }
  CHECK(mismatches == 0);

  // The published answer for counter 0, key 0 from the device itself.
  k.setArg(0, cl_ulong(0));
  k.setArg(1, cl_uint(0));
  k.setArg(2, cl_uint(0));
  k.setArg(3, cl_ulong(0));
  rt->queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(1));
  std::array<cl_uint, 4> first_out{};
  rt->queue().enqueueReadBuffer(out, CL_TRUE, 0, sizeof(first_out), first_out.data());
  CHECK(first_out == kKats[0].out);
}

// albedo_values takes the cosine lobe's branch as an integer compare of the
// Philox word (kernels/rng.cl u01_open_below_fifth) where the other
// albedo paths compare u01_open(x) < MIX_I_COS: the same truth for every x,
// in the float programs (0.2f) and the double ones (0.2). Both constants
// are read from the kernel sources, so a change to either is checked. u01_open
// depends on x >> 9 only, so the 2^23 values of k = x >> 9 cover every x.
TEST_CASE("albedo_values' integer lobe compare agrees with u01_open(x) < MIX_I_COS for every x", "[rng]") {
  const std::string rng = test::slurp(std::string(MFV_KERNEL_SOURCE_DIR) + "/rng.cl");
  const std::string est = test::slurp(std::string(MFV_KERNEL_SOURCE_DIR) + "/estimators.cl");
  std::smatch m;
  REQUIRE(std::regex_search(rng, m, std::regex(R"(#define MFV_U01_BELOW_FIFTH (\d+)u)")));
  const uint64_t threshold = std::stoull(m[1].str());
  REQUIRE(std::regex_search(est, m, std::regex(R"(#define MIX_I_COS R\(([0-9.]+)\))")));
  const double share = std::stod(m[1].str());
  const float share_f = std::stof(m[1].str());
  uint64_t below = 0, mismatches = 0;
  for (uint32_t k = 0; k < (1u << 23); ++k) {
    const uint32_t x = k << 9;
    const double u = u01_open(x);
    const bool by_int = x < threshold;
    mismatches += (u < share) != by_int;
    mismatches += (static_cast<float>(u) < share_f) != by_int;  // u is exact in float
    below += by_int;
  }
  CHECK(mismatches == 0);
  CHECK(below == threshold >> 9);  // the threshold is a multiple of 2^9: no k straddles it
  CHECK(threshold % 512 == 0);
}
