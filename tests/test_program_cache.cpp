// The on-disk program binary cache (host/runtime/program_cache.hpp): a hit
// builds from the binary and runs the same kernels; a truncated, corrupt or
// foreign entry is ignored and rewritten; a changed source is a new entry;
// it is off unless MFV_PROGRAM_CACHE=1, and a bad value is a one-line error.
#include "device_fixture.hpp"
#include "run_mfv.hpp"
#include "runtime/opencl.hpp"
#include "runtime/program_cache.hpp"
#include "scoped_env.hpp"
#include "test_files.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

using namespace mfv;
namespace fs = std::filesystem;

namespace {

std::vector<fs::path> entries(const std::string& dir) {
  std::vector<fs::path> out;
  if (fs::exists(dir))
    for (auto& e : fs::directory_iterator(dir)) out.push_back(e.path());
  return out;
}

// Philox words from kernels/rng.cl's philox_kat kernel of `prog`.
std::vector<cl_uint> philox_words(Runtime& rt, const cl::Program& prog) {
  const size_t n = 64;
  cl::Buffer out(rt.context(), CL_MEM_WRITE_ONLY, n * 4 * sizeof(cl_uint));
  cl::Buffer uni(rt.context(), CL_MEM_WRITE_ONLY, n * sizeof(float));
  cl::Kernel k(prog, "philox_kat");
  k.setArg(0, cl_ulong(7));
  k.setArg(1, cl_uint(3));
  k.setArg(2, cl_uint(0));
  k.setArg(3, cl_ulong(0));
  k.setArg(4, out);
  k.setArg(5, uni);
  rt.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n));
  std::vector<cl_uint> w(n * 4);
  rt.queue().enqueueReadBuffer(out, CL_TRUE, 0, w.size() * sizeof(cl_uint), w.data());
  return w;
}

const std::vector<std::string> kFiles = {"common.cl", "rng.cl"};

// Philox words from `rt`'s build of kFiles.
std::vector<cl_uint> built_words(Runtime& rt) { return philox_words(rt, rt.build(kFiles, {})); }

// The program cache on (MFV_PROGRAM_CACHE=1) in a scratch folder, for one test.
struct CacheOn {
  test::Scratch dir;
  test::ScopedEnv on, where;
  explicit CacheOn(const std::string& name)
      : dir(name), on("MFV_PROGRAM_CACHE", "1"), where("MFV_CACHE_DIR", dir.dir.c_str()) {}
  std::vector<fs::path> entries() const { return ::entries(dir.dir.string()); }
};

}  // namespace

TEST_CASE("A program comes from the cache on the second build and runs the same", "[device][program_cache]") {
  if (!test::device_runtime()) return;
  const CacheOn cache("mfv_program_cache_hit");
  Runtime rt("");
  const std::vector<cl_uint> fresh = built_words(rt);
  CHECK(rt.build_stats().cached == 0);
  REQUIRE(cache.entries().size() == 1);
  Runtime again("");  // another process would see the same: a new context
  const std::vector<cl_uint> cached = built_words(again);
  CHECK(again.build_stats().cached == 1);
  CHECK(cached == fresh);
}

TEST_CASE("A truncated, corrupt or foreign cache entry is rebuilt, never trusted", "[device][program_cache]") {
  if (!test::device_runtime()) return;
  const CacheOn cache("mfv_program_cache_bad");
  Runtime rt("");
  const std::vector<cl_uint> fresh = built_words(rt);
  REQUIRE(cache.entries().size() == 1);
  const fs::path entry = cache.entries()[0];
  const std::string good = test::slurp(entry);
  const size_t header = good.find('\n') + 1;
  REQUIRE(good.size() > header + 64);

  std::string flipped = good;
  flipped[header + (good.size() - header) / 2] ^= 0x5a;  // one payload byte
  std::string other_key = good;
  other_key[std::string("mfv-program-cache-1 ").size()] ^= 1;  // the first hex digit of the key
  const std::vector<std::pair<std::string, std::string>> damaged = {
      {"truncated", good.substr(0, header + (good.size() - header) / 2)},
      {"header only", good.substr(0, header)},
      {"empty", ""},
      {"corrupt payload", flipped},
      {"another key", other_key},
      {"garbage", std::string(1000, '\x7f')},
      {"grown", good + "extra"}};
  for (auto& [what, text] : damaged) {
    INFO(what);
    std::ofstream(entry, std::ios::binary | std::ios::trunc) << text;
    Runtime r("");
    const std::vector<cl_uint> words = built_words(r);
    CHECK(r.build_stats().cached == 0);  // built from source
    CHECK(words == fresh);
    // and the entry rewritten whole: the next build takes it. (Not compared
    // byte for byte with `good`: PoCL's binaries of one program need not be
    // identical; a ctest -j2 run saw two differ.)
    Runtime next("");
    CHECK(built_words(next) == fresh);
    CHECK(next.build_stats().cached == 1);
  }
}

TEST_CASE("A changed source or option is a new cache entry", "[device][program_cache]") {
  if (!test::device_runtime()) return;
  const CacheOn cache("mfv_program_cache_new");
  Runtime rt("");
  rt.build(kFiles, {});
  rt.build(kFiles, {}, "// one more line\n");
  CHECK(rt.build_stats().cached == 0);
  CHECK(cache.entries().size() == 2);
  rt.build(kFiles, {"MFV_SOMETHING"});
  CHECK(rt.build_stats().cached == 0);
  CHECK(cache.entries().size() == 3);
  rt.build(kFiles, {}, "// one more line\n");
  CHECK(rt.build_stats().cached == 1);
}

TEST_CASE("MFV_PROGRAM_CACHE=0 or unset writes nothing, and a bad value is an error",
          "[device][program_cache][bad_input]") {
  if (!test::device_runtime()) return;
  test::Scratch dir("mfv_program_cache_off");
  for (const char* value : {"0", static_cast<const char*>(nullptr)}) {
    const test::ScopedEnv off("MFV_PROGRAM_CACHE", value), where("MFV_CACHE_DIR", dir.dir.c_str());
    Runtime rt("");
    rt.build(kFiles, {});
    rt.build(kFiles, {});
    CHECK(rt.build_stats().cached == 0);
    CHECK(entries(dir.dir.string()).empty());
  }
  {
    const test::ScopedEnv bad("MFV_PROGRAM_CACHE", "yes");
    CHECK_THROWS_WITH(Runtime(""), Catch::Contains("MFV_PROGRAM_CACHE=yes"));
  }
  const test::Run r = test::run_mfv("eval ggx", "MFV_PROGRAM_CACHE=2");
  CHECK(r.code == 2);
  CHECK(r.out.find("mfv: error: MFV_PROGRAM_CACHE=2: expected 0 (off) or 1 (on)") != std::string::npos);
}
