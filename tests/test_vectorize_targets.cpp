// The fast-path kernels vectorize on an AVX2 target as on an AVX-512 one,
// whichever x86-64 CPU runs the test: scripts/pocl-vectorization.sh
// --targets compiles the bench program for PoCL's avx2 (haswell) and avx512
// (skylake-avx512) kernel libraries, every kernel at build time (mfv's
// program cache asks for the binary), and reports each kernel's width per
// target. A kernel that vectorizes on one and stays scalar on the other
// fails the test, unless it is a documented exception below.
#include "kernel_dir.hpp"
#include "run_mfv.hpp"
#include "skip.hpp"

#include <catch2/catch.hpp>

#include <map>
#include <set>
#include <sstream>
#include <string>

namespace {

struct Widths {
  std::string avx2, avx512;
};

// The script's table (kernel, then one column per target) -> widths by kernel.
std::map<std::string, Widths> vectorization(const std::string& kernel_dir) {
  const std::string script = std::string(MFV_KERNEL_SOURCE_DIR) + "/../scripts/pocl-vectorization.sh";
  // the bench program holds every fast-path kernel of the isotropic
  // microfacet integrals; one tiny launch of each integrand
  const auto r = mfv::test::run_mfv_shell("bash " + script + " --targets avx2,avx512 " + MFV_BINARY +
                                          " --kernel-dir " + kernel_dir +
                                          " bench --integrand d_norm --repeats 1 --integrals 1 --samples 64"
                                          " --ref-samples 1 --threads 1 --out " + kernel_dir + "/bench-out");
  INFO(r.out);
  REQUIRE(r.code == 0);
  std::map<std::string, Widths> w;
  std::istringstream in(r.out);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string kernel;
    Widths x;
    if (row >> kernel >> x.avx2 >> x.avx512) w[kernel] = x;
  }
  return w;
}

// Kernels known to differ, each with its reason: the test fails when one of
// them stops differing, so the list cannot go stale. None now: the last two
// (reciprocity_values_microfacet, albedo_rqmc_values, scalar on avx2) were
// fixed by the select-form horizon test (brdf_above_c) and a |f1 - f2| that
// SLP does not pair (docs/performance.md, "AVX2").
const std::map<std::string, std::string> kKnownDifferent = {};

// PoCL prints no remarks (another driver, or no device): nothing to compare.
bool have_remarks(const std::map<std::string, Widths>& w) {
  for (const auto& [k, x] : w)
    if (x.avx2 != "-" && x.avx512 != "-") return true;
  return false;
}

}  // namespace

TEST_CASE("Every fast-path kernel that vectorizes for AVX-512 also vectorizes for AVX2, and the reverse",
          "[vectorize][device]") {
  const mfv::test::PlantedKernelDir kernels;  // an unchanged copy (the out folder goes there too)
  const auto w = vectorization(kernels.path());
  if (!have_remarks(w)) {
    mfv::test::skip("no PoCL vectorizer remarks (not PoCL, or no device)");
    return;
  }
  for (const char* k : {"d_norm_values", "albedo_values", "masking_values", "albedo_mis_values", "albedo_rqmc_values",
                        "reciprocity_values_microfacet"}) {
    INFO(k);
    REQUIRE(w.count(k));
    CHECK(w.at(k).avx2 != "scalar");
  }
  for (const auto& [k, x] : w) {
    INFO(k << ": avx2 " << x.avx2 << ", avx512 " << x.avx512);
    const bool differ = (x.avx2 == "scalar") != (x.avx512 == "scalar");
    CHECK(differ == (kKnownDifferent.count(k) > 0));
  }
}

TEST_CASE("The two-target vectorization test fails on a kernel that vectorizes only with AVX-512",
          "[vectorize][device]") {
  // plant: D_ggx with its early return before alpha is read, the form that
  // kept d_norm_values scalar on AVX2 (the load of alpha left conditional)
  mfv::test::PlantedKernelDir kernels("terms_d.cl", "  real c = min(NoH, R(1.0));\n  // divide by α² first",
                                      "  if (NoH <= R(0.0)) return R(0.0);\n  real c = min(NoH, R(1.0));\n"
                                      "  // divide by α² first");
  const auto w = vectorization(kernels.path());
  if (!have_remarks(w)) {
    mfv::test::skip("no PoCL vectorizer remarks (not PoCL, or no device)");
    return;
  }
  REQUIRE(w.count("d_norm_values"));
  CHECK(w.at("d_norm_values").avx2 == "scalar");
  CHECK(w.at("d_norm_values").avx512 != "scalar");
}
