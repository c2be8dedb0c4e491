// The fast-path kernels vectorize on an AVX2 target as on an AVX-512 one,
// whichever x86-64 CPU runs the test: scripts/pocl-vectorization.sh
// --targets compiles the bench program for PoCL's avx2 (haswell) and avx512
// (skylake-avx512) kernel libraries, every kernel at build time (mfv's
// program cache asks for the binary), and reports each kernel's width per
// target. A kernel that vectorizes on one and stays scalar on the other
// fails the test, unless it is a documented exception below.
#include "kernel_dir.hpp"
#include "plants.hpp"
#include "run_mfv.hpp"
#include "skip.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <initializer_list>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>

namespace {

struct Widths {
  std::string avx2, avx512;
};

// The script's table (kernel, then one column per target) -> widths by kernel.
// The bench program holds every fast-path kernel of the isotropic microfacet
// integrals; one tiny launch of each integrand.
const char* const kBench =
    "bench --integrand d_norm --repeats 1 --integrals 1 --samples 64 --ref-samples 1 --threads 1";
// The energy program of every D with smith_ggx_correlated (G id 12): its
// kernels specialized per pair, albedo_rqmc_values__dN_g12 for the five
// isotropic Ds, and per G, albedo_mis_values__g12 and masking_values__g12
// (with albedo_mis_df__dN and masking_d__dN per D); a 2x2 table.
const char* const kEnergyG12 =
    "energy --models /smith_ggx_correlated --grid 2x2 --max-points 1024 --replicates 2";
// The program of ggx/smith_ggx_correlated alone (d2_g12), where the paired
// horizon selects kept the albedo kernels scalar (in kEnergyG12's program
// they happened to vectorize on haswell even so: docs/performance.md).
const char* const kEnergyGgxG12 =
    "energy --models ggx/smith_ggx_correlated --grid 2x2 --max-points 1024 --replicates 2";
// The energy program of every D with kelemen (G id 6): its pairs'
// kernels `__dN_g6`, and the generic albedo kernels, whose G is kelemen
// alone; all of them stayed scalar on haswell while G_kelemen's two
// quotients were a pair SLP packed into one <2 x float> division there.
const char* const kEnergyG6 = "energy --models /kelemen --grid 2x2 --max-points 1024 --replicates 2";
// The program of ggx with every isotropic G, kelemen among them: its generic
// kernels evaluate every G in a select chain (the multi-G programs of the
// default mfv run), and the same pair kept masking_values and
// reciprocity_values_microfacet scalar on haswell.
const char* const kEnergyGgxAllG = "energy --models ggx/ --grid 2x2 --max-points 1024 --replicates 2";

// The energy program of charlie with charlie_sheen (G id 23): its masking and
// AlbedoMis kernels per G (`__g23`), per D (`__d22`) and per pair.
const char* const kEnergyCharlie = "energy --models charlie/charlie_sheen --grid 2x2 --max-points 1024 --replicates 2";

// The run's program of charlie with neubelt_sheen: its generic
// kernels (albedo_values, albedo_mis_values, reciprocity_values_microfacet:
// the program's one G in their select chains), built with the reciprocity
// check's.
const char* const kRunNeubelt = "run --check reciprocity --model charlie/neubelt_sheen";

// Whole models (kernels/model_values.cl, kernels/reciprocity.cl): Lambert
// (m1) and radiance_002_fixed (m14), whose model_albedo_values__mN and
// model_reciprocity_values__mN are 8-wide on both targets since the models'
// select form (models.cl above_horizons) and mfv_philox_split in these
// kernels (docs/performance.md, "Whole models on both targets"). The per-model
// reciprocity kernels are built where the pairs reach 1e7 a model
// (model_reciprocity_per_model_pays): 4 integrals x 64 x 64 x 1250 pairs.
const char* const kWholeModels = "run --check reciprocity --scale 1250 --model lambert radiance_002_fixed";
const char* const kWholeModelKernels[] = {"model_albedo_values__m1", "model_reciprocity_values__m1",
                                          "model_albedo_values__m14", "model_reciprocity_values__m14"};

// The rest of the catalog (issue 31): eon (m3), phong_004 (m6),
// phong_normalized (m7), ward_004 (m9) and ward_dur (m10), 8-wide on both
// targets since mfv_acos, mfv_exp/mfv_log1p in Phong, EON's E_FON at l in a
// block of its own and Ward's exponent as one fused sum (docs/performance.md,
// "The rest of the catalog"). The same scale as kWholeModels: two
// reciprocity integrals a model reach 1e7 pairs.
const char* const kCatalogModels = "run --check reciprocity --scale 1250 --model eon phong ward";
const char* const kCatalogModelKernels[] = {
    "model_albedo_values__m3",  "model_reciprocity_values__m3",  "model_albedo_values__m6",
    "model_reciprocity_values__m6", "model_albedo_values__m7",  "model_reciprocity_values__m7",
    "model_albedo_values__m9",  "model_reciprocity_values__m9",  "model_albedo_values__m10",
    "model_reciprocity_values__m10"};

// oren_nayar (m2), toon_diffuse (m4) and cook_torrance_004 (m11), 8-wide on
// both targets since oren_nayar's one clamp and the whole-model reciprocity
// kernel's f(b, a) + 0 (docs/performance.md, "oren_nayar, toon_diffuse and
// cook_torrance_004"). Three models' reciprocity integrals reach 3e7 pairs at
// this scale.
const char* const kOrenToonCook =
    "run --check reciprocity --scale 1250 --model oren_nayar toon_diffuse cook_torrance_004";
const char* const kOrenToonCookKernels[] = {"model_albedo_values__m2",  "model_reciprocity_values__m2",
                                            "model_albedo_values__m4",  "model_reciprocity_values__m4",
                                            "model_albedo_values__m11", "model_reciprocity_values__m11"};

// The glTF models (15-19): 8-wide on both targets since the select form,
// Lambda_ggx_aniso's fused α²sin² and gltf_sheen's log10 and lookups
// (docs/performance.md, "The glTF models"), their reciprocity kernels since
// model_gltf is forced inline and gltf_transmission evaluates its two halves
// once ("The glTF models' reciprocity kernels"). The scale is the least at
// which the run compiles the per-model reciprocity kernels
// (model_reciprocity_per_model_pays: 1e7 pairs a model).
const char* const kGltfModels = "run --check reciprocity --scale 1250 --model gltf";
const char* const kGltfModelKernels[] = {"model_albedo_values__m15", "model_reciprocity_values__m15",
                                         "model_albedo_values__m16", "model_reciprocity_values__m16",
                                         "model_albedo_values__m17", "model_reciprocity_values__m17",
                                         "model_albedo_values__m18", "model_reciprocity_values__m18",
                                         "model_albedo_values__m19", "model_reciprocity_values__m19"};

std::map<std::string, Widths> vectorization(const std::string& kernel_dir, const std::string& command = kBench) {
  const std::string script = std::string(MFV_KERNEL_SOURCE_DIR) + "/../scripts/pocl-vectorization.sh";
  const auto r = mfv::test::run_mfv_shell("bash " + script + " --targets avx2,avx512 " + MFV_BINARY +
                                          " --kernel-dir " + kernel_dir + " " + command + " --out " + kernel_dir +
                                          "/cmd-out");
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
  for (const char* k : {"d_norm_values", "albedo_values", "masking_geometry", "masking_d", "masking_values",
                        "albedo_mis_values", "albedo_rqmc_values", "reciprocity_values_microfacet"}) {
    INFO(k);
    REQUIRE(w.count(k));
    CHECK(w.at(k).avx2 != "scalar");
    CHECK(w.at(k).avx512 != "-");
  }
  for (const auto& [k, x] : w) {
    INFO(k << ": avx2 " << x.avx2 << ", avx512 " << x.avx512);
    // "-": not compiled for that target. On a CPU without AVX-512 the avx512
    // command dies at its first launch (SIGILL), before bench builds its peak
    // program; the fast-path kernels above are all compiled by then.
    if (x.avx2 == "-" || x.avx512 == "-") continue;
    const bool differ = (x.avx2 == "scalar") != (x.avx512 == "scalar");
    CHECK(differ == (kKnownDifferent.count(k) > 0));
  }
}

TEST_CASE("The two-target vectorization test fails on a kernel that vectorizes only with AVX-512",
          "[vectorize][device]") {
  // plant: D_ggx with its early return before alpha is read, the form that
  // kept d_norm_values scalar on AVX2 (the load of alpha left conditional).
  // masking_d (one D a work-item) still shows it; d_norm_values, two samples
  // in two blocks since (kernels/estimators.cl MFV_SAMPLE_VALUES_2), is
  // 8-wide on both targets with it.
  mfv::test::PlantedKernelDir kernels("terms_d.cl", "  real c = min(NoH, R(1.0));\n  // divide by α² first",
                                      "  if (NoH <= R(0.0)) return R(0.0);\n  real c = min(NoH, R(1.0));\n"
                                      "  // divide by α² first");
  const auto w = vectorization(kernels.path());
  if (!have_remarks(w)) {
    mfv::test::skip("no PoCL vectorizer remarks (not PoCL, or no device)");
    return;
  }
  REQUIRE(w.count("masking_d"));
  CHECK(w.at("masking_d").avx2 == "scalar");
  CHECK(w.at("masking_d").avx512 != "scalar");
  CHECK(w.at("masking_d").avx512 != "-");
}

// PoCL picks its kernel library among those the host CPU can run, so on a CPU
// without AVX-512, POCL_KERNELLIB_NAME=avx512 alone compiles for haswell, and
// the two columns above would both be AVX2 (the plant test failed on such a
// CPU, 5 December 2026). The script then preloads tests/pretend_avx512 (the
// plant test above passing there shows the avx512 column is AVX-512's), and
// without that preload it refuses rather than print a false column.
TEST_CASE("On a CPU without AVX-512 the two-target script refuses an avx512 column it cannot compile",
          "[vectorize][device]") {
  std::ifstream cpuinfo("/proc/cpuinfo");
  const std::string flags((std::istreambuf_iterator<char>(cpuinfo)), std::istreambuf_iterator<char>());
  if (flags.find(" avx512f") != std::string::npos) {
    mfv::test::skip("this CPU has AVX-512: PoCL compiles for skylake-avx512 without the preload");
    return;
  }
  if (mfv::test::run_mfv("devices").out.find("pthread-") == std::string::npos) {
    mfv::test::skip("no PoCL CPU device: no target to check");
    return;
  }
  // the preload named but absent: the script must refuse before it runs
  // anything (the command would otherwise fail on its /dev/null output)
  const std::string script = std::string(MFV_KERNEL_SOURCE_DIR) + "/../scripts/pocl-vectorization.sh";
  const auto r = mfv::test::run_mfv_shell("MFV_PRETEND_AVX512=/nonexistent bash " + script + " --targets avx2,avx512 " +
                                          MFV_BINARY + " " + kBench + " --out /dev/null");
  INFO(r.out);
  CHECK(r.code == 2);
  // PoCL's best CPU here (haswell on an AVX2 CPU), whichever it is, named against the one asked for
  CHECK(r.out.find("target avx512: PoCL compiles for '") != std::string::npos);
  CHECK(r.out.find("' here, not 'skylake-avx512'") != std::string::npos);
}

namespace {

// The kernels of a program specialized for G `suffix` ("_g12": named
// `__dN_g12`), with their widths.
std::map<std::string, Widths> pair_kernels(const std::map<std::string, Widths>& w, const std::string& suffix) {
  std::map<std::string, Widths> g;
  for (const auto& [k, x] : w)
    if (k.size() > suffix.size() && k.compare(k.size() - suffix.size(), suffix.size(), suffix) == 0) g[k] = x;
  return g;
}

// `plant` makes each named kernel of `command`'s programs scalar on avx2
// and wide on avx512 (measured 5 December 2026, PoCL 3.1): a test that asks
// for them wide on both, or for no kernel to differ, fails on it.
void require_avx2_only_scalar(const mfv::test::Plant& plant, const char* command,
                              std::initializer_list<const char*> names) {
  const mfv::test::PlantedKernelDir kernels(plant.file, plant.from, plant.to);
  const auto w = vectorization(kernels.path(), command);
  if (!have_remarks(w)) {
    mfv::test::skip("no PoCL vectorizer remarks (not PoCL, or no device)");
    return;
  }
  for (const char* k : names) {
    INFO(k);
    REQUIRE(w.count(k));
    CHECK(w.at(k).avx2 == "scalar");
    CHECK(w.at(k).avx512 != "scalar");
    CHECK(w.at(k).avx512 != "-");
  }
}

// No kernel compiled for both targets is scalar on one and wide on the other.
void require_no_difference(const std::map<std::string, Widths>& w) {
  for (const auto& [k, x] : w) {
    INFO(k << ": avx2 " << x.avx2 << ", avx512 " << x.avx512);
    if (x.avx2 == "-" || x.avx512 == "-") continue;  // not compiled for one target (see the first test)
    CHECK((x.avx2 == "scalar") == (x.avx512 == "scalar"));
  }
}

}  // namespace

TEST_CASE("The energy kernels of every D with smith_ggx_correlated vectorize on AVX2 and on AVX-512",
          "[vectorize][device]") {
  const mfv::test::PlantedKernelDir kernels;
  // albedo_rqmc: for d0..d4, and for d2 alone; albedo_mis_values__g12 and masking_values__g12 once;
  // and for d2 alone, a program of one pair, AlbedoMis in one kernel, albedo_mis_pair__d2_g12
  for (const auto& [command, n] : {std::pair<const char*, size_t>{kEnergyG12, 7}, {kEnergyGgxG12, 4}}) {
    INFO(command);
    const auto w = vectorization(kernels.path(), command);
    if (!have_remarks(w)) {
      mfv::test::skip("no PoCL vectorizer remarks (not PoCL, or no device)");
      return;
    }
    const auto g = pair_kernels(w, "_g12");
    CHECK(g.size() == n);
    for (const auto& [k, x] : g) {
      INFO(k << ": avx2 " << x.avx2 << ", avx512 " << x.avx512);
      CHECK(x.avx2 != "scalar");
      CHECK(x.avx512 != "scalar");
    }
  }
}

TEST_CASE("The smith_ggx_correlated vectorization test fails on a horizon select that SLP pairs with D's",
          "[vectorize][device]") {
  const auto& p = mfv::test::kGgxCorrelatedHorizonPaired;
  const mfv::test::PlantedKernelDir kernels(p.file, p.from, p.to);
  const auto w = vectorization(kernels.path(), kEnergyGgxG12);
  if (!have_remarks(w)) {
    mfv::test::skip("no PoCL vectorizer remarks (not PoCL, or no device)");
    return;
  }
  // planted: the albedo kernel with D beside G goes scalar on both targets
  // (the masking one, with no D select beside G's, stays wide, and so does
  // AlbedoMis's albedo_mis_values__g12, which evaluates no D, and its
  // one-pair albedo_mis_pair__d2_g12, measured 8-wide on both), so the test
  // above fails
  for (const char* k : {"albedo_rqmc_values__d2_g12"}) {
    INFO(k);
    REQUIRE(w.count(k));
    CHECK(w.at(k).avx2 == "scalar");
    CHECK(w.at(k).avx512 == "scalar");
  }
}

TEST_CASE("The kernels of every D with kelemen, and of ggx with every G, vectorize on AVX2 as on AVX-512: no kernel "
          "of those programs differs between them",
          "[vectorize][device]") {
  const mfv::test::PlantedKernelDir kernels;
  // albedo_rqmc for d0..d4, and for d2 beside every other G; albedo_mis_values__g6 and
  // masking_values__g6 once
  for (const auto& [command, n] : {std::pair<const char*, size_t>{kEnergyG6, 7}, {kEnergyGgxAllG, 3}}) {
    INFO(command);
    const auto w = vectorization(kernels.path(), command);
    if (!have_remarks(w)) {
      mfv::test::skip("no PoCL vectorizer remarks (not PoCL, or no device)");
      return;
    }
    const auto g = pair_kernels(w, "_g6");
    CHECK(g.size() == n);
    for (const auto& [k, x] : g) {
      INFO(k << ": avx2 " << x.avx2 << ", avx512 " << x.avx512);
      CHECK(x.avx2 != "scalar");
      CHECK(x.avx512 != "scalar");
    }
    // the generic kernels too (in kEnergyG6's program albedo_values,
    // albedo_mis_values, albedo_rqmc_values and albedo_aniso_values, whose
    // only G is kelemen; in kEnergyGgxAllG's the multi-G masking_values and
    // reciprocity_values_microfacet, which must be wide)
    if (command == kEnergyGgxAllG)
      for (const char* k : {"masking_values", "reciprocity_values_microfacet"}) {
        INFO(k);
        REQUIRE(w.count(k));
        CHECK(w.at(k).avx2 != "scalar");
        CHECK(w.at(k).avx512 != "scalar");
      }
    for (const auto& [k, x] : w) {
      INFO(k << ": avx2 " << x.avx2 << ", avx512 " << x.avx512);
      CHECK((x.avx2 == "scalar") == (x.avx512 == "scalar"));
    }
  }
}

TEST_CASE("The kelemen vectorization test fails on G_kelemen's two quotients that SLP pairs on AVX2",
          "[vectorize][device]") {
  // planted: the pair's RQMC albedo kernel and the multi-G generic masking
  // and reciprocity kernels go scalar on avx2 only, so the test above fails
  // (AlbedoMis's albedo_mis_values__g6, G without D, stays 8-wide on both)
  require_avx2_only_scalar(mfv::test::kKelemenQuotientsPaired, kEnergyGgxAllG,
                           {"albedo_rqmc_values__d2_g6", "masking_values", "reciprocity_values_microfacet"});
}

namespace {

// The named kernels of `command`'s programs, each wide on both targets.
template <size_t N>
void require_wide(const char* command, const char* const (&names)[N]) {
  const mfv::test::PlantedKernelDir kernels;
  const auto w = vectorization(kernels.path(), command);
  if (!have_remarks(w)) {
    mfv::test::skip("no PoCL vectorizer remarks (not PoCL, or no device)");
    return;
  }
  for (const char* k : names) {
    INFO(k);
    REQUIRE(w.count(k));
    CHECK(w.at(k).avx2 != "scalar");
    CHECK(w.at(k).avx512 != "scalar");
  }
}

// One plant a case, each alone: its kernel scalar or not on each target, as
// measured (5 December 2026, PoCL 3.1), so that require_wide fails on it.
struct PlantCase {
  const mfv::test::Plant* plant;
  const char* kernel;
  bool avx2_scalar, avx512_scalar;
};

void require_planted_widths(const char* command, std::initializer_list<PlantCase> cases) {
  for (const PlantCase& c : cases) {
    INFO(c.plant->name << ": " << c.kernel);
    const mfv::test::PlantedKernelDir kernels(c.plant->file, c.plant->from, c.plant->to);
    const auto w = vectorization(kernels.path(), command);
    if (!have_remarks(w)) {
      mfv::test::skip("no PoCL vectorizer remarks (not PoCL, or no device)");
      return;
    }
    REQUIRE(w.count(c.kernel));
    CHECK((w.at(c.kernel).avx2 == "scalar") == c.avx2_scalar);
    CHECK((w.at(c.kernel).avx512 == "scalar") == c.avx512_scalar);
    CHECK(w.at(c.kernel).avx512 != "-");
  }
}

}  // namespace

TEST_CASE("Whole models' albedo and reciprocity kernels vectorize on AVX2 and on AVX-512", "[vectorize][device]") {
  require_wide(kWholeModels, kWholeModelKernels);
}

TEST_CASE("The whole-model vectorization test fails on an early horizon return, on Philox's products SLP pairs and "
          "on a horizon test SLP pairs",
          "[vectorize][device]") {
  // planted, each alone: the test above fails on a Lambert kernel
  require_planted_widths(kWholeModels,
                         {{&mfv::test::kModelAlbedoEarlyReturn, "model_albedo_values__m1", true, false},
                          {&mfv::test::kModelAlbedoPhiloxPaired, "model_albedo_values__m1", false, true},
                          {&mfv::test::kHorizonsFmin, "model_reciprocity_values__m1", true, true}});
}

TEST_CASE("The kernels of charlie with charlie_sheen vectorize on AVX2 and on AVX-512: no kernel of its program "
          "differs between them",
          "[vectorize][device]") {
  const mfv::test::PlantedKernelDir kernels;
  const auto w = vectorization(kernels.path(), kEnergyCharlie);
  if (!have_remarks(w)) {
    mfv::test::skip("no PoCL vectorizer remarks (not PoCL, or no device)");
    return;
  }
  // masking_values__g23, albedo_mis_values__g23, albedo_rqmc_values__d22_g23, albedo_mis_pair__d22_g23
  const auto g = pair_kernels(w, "_g23");
  CHECK(g.size() == 4);
  for (const auto& [k, x] : g) {
    INFO(k << ": avx2 " << x.avx2 << ", avx512 " << x.avx512);
    CHECK(x.avx2 != "scalar");
    CHECK(x.avx512 != "scalar");
  }
  require_no_difference(w);
}

TEST_CASE("The charlie_sheen vectorization test fails on Charlie's G as before: two L's in its Lambda, early "
          "horizon returns",
          "[vectorize][device]") {
  require_avx2_only_scalar(mfv::test::kCharlieEarlyReturns, kEnergyCharlie,
                           {"masking_values__g23", "albedo_mis_values__g23"});
}

TEST_CASE("The generic kernels of a program with neubelt_sheen vectorize on AVX2 and on AVX-512: no kernel of it "
          "differs between them",
          "[vectorize][device]") {
  const mfv::test::PlantedKernelDir kernels;
  const auto w = vectorization(kernels.path(), kRunNeubelt);
  if (!have_remarks(w)) {
    mfv::test::skip("no PoCL vectorizer remarks (not PoCL, or no device)");
    return;
  }
  for (const char* k : {"albedo_values", "albedo_mis_values", "reciprocity_values_microfacet"}) {
    INFO(k);
    REQUIRE(w.count(k));
    CHECK(w.at(k).avx2 != "scalar");
    CHECK(w.at(k).avx512 != "scalar");
  }
  require_no_difference(w);
}

TEST_CASE("The neubelt_sheen vectorization test fails on G_neubelt_sheen's two clamps side by side",
          "[vectorize][device]") {
  require_avx2_only_scalar(mfv::test::kNeubeltClampsPaired, kRunNeubelt,
                           {"albedo_values", "albedo_mis_values", "reciprocity_values_microfacet"});
}

TEST_CASE("The rest of the catalog's whole models (eon, Phong, Ward) vectorize on AVX2 and on AVX-512",
          "[vectorize][device]") {
  require_wide(kCatalogModels, kCatalogModelKernels);
}

TEST_CASE("The catalog vectorization test fails on the library's log1p in Phong, on EON's E_FON paired and on "
          "Ward's squares paired",
          "[vectorize][device]") {
  // planted, each alone: the test above fails on these kernels
  require_planted_widths(kCatalogModels, {{&mfv::test::kPhongLibraryLog1p, "model_albedo_values__m6", true, true},
                                          {&mfv::test::kEonFonPaired, "model_albedo_values__m3", true, true},
                                          {&mfv::test::kWardSquaresPaired, "model_albedo_values__m9", true, false}});
}

TEST_CASE("oren_nayar's, toon_diffuse's and cook_torrance_004's whole-model kernels vectorize on AVX2 and on AVX-512",
          "[vectorize][device]") {
  require_wide(kOrenToonCook, kOrenToonCookKernels);
}

TEST_CASE("The oren_nayar/toon_diffuse/cook_torrance_004 vectorization test fails on oren_nayar's clamps paired and on "
          "the reciprocity kernel's two evaluations paired",
          "[vectorize][device]") {
  // planted, each alone: the test above fails on these kernels
  require_planted_widths(kOrenToonCook,
                         {{&mfv::test::kOrenNayarClampsPaired, "model_albedo_values__m2", true, false},
                          {&mfv::test::kModelReciprocityPaired, "model_reciprocity_values__m4", true, false},
                          {&mfv::test::kModelReciprocityPaired, "model_reciprocity_values__m11", true, true}});
}

TEST_CASE("The glTF whole models' albedo and reciprocity kernels vectorize on AVX2 and on AVX-512",
          "[vectorize][device]") {
  require_wide(kGltfModels, kGltfModelKernels);
}

TEST_CASE("The glTF vectorization test fails on gltf_sheen's lookups paired, on model_gltf out of line, on "
          "gltf_transmission's halves as two calls and on Lambda_ggx_aniso's squares paired",
          "[vectorize][device]") {
  // planted, each alone: the test above fails on these kernels
  require_planted_widths(kGltfModels,
                         {{&mfv::test::kSheenLookupsPaired, "model_albedo_values__m18", true, true},
                          {&mfv::test::kGltfOutOfLine, "model_reciprocity_values__m15", true, true},
                          {&mfv::test::kTransmissionHalvesPaired, "model_reciprocity_values__m19", true, false},
                          {&mfv::test::kLambdaAnisoSquaresPaired, "model_albedo_values__m15", true, false}});
}
