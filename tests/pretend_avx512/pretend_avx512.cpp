// LD_PRELOAD shim for scripts/pocl-vectorization.sh --targets on a CPU
// without AVX-512: PoCL (3.1, Debian's distro build) picks its kernel library
// and LLVM target CPU among those whose features the *host* has
// (pocl_get_distro_kernellib_name over llvm::sys::getHostCPUFeatures), so
// POCL_KERNELLIB_NAME=avx512 on an AVX2 host silently compiles for haswell.
// This shim answers getHostCPUFeatures with the host's features plus
// AVX-512 (F, CD, BW, DQ, VL: skylake-avx512's), so PoCL selects its avx512
// library and compiles for `skylake-avx512`, as on an AVX-512 host. The
// compile depends only on that target (PoCL passes `-target-cpu` and no host
// feature list), so its vectorizer remarks are the AVX-512 host's. Running
// such a kernel on an AVX2 CPU dies (SIGILL): the script only compiles.
// Test and tooling use only; never loaded by mfv itself.
#include <dlfcn.h>

#include <cstddef>
#include <cstring>

namespace {

// llvm::StringRef's layout (a pointer and a length, trivially copyable, so
// passed by value in two registers as this struct is).
struct StringRefAbi {
  const char* data;
  std::size_t size;
};

using HostFeaturesFn = bool (*)(void* features);
using UpdateImpliedFn = void (*)(StringRefAbi feature, bool enabled, void* features);

// From the libLLVM that PoCL loaded: the ICD loader opens PoCL (and so
// LLVM) locally, out of RTLD_NEXT's reach.
template <typename Fn>
Fn llvm15_symbol(const char* mangled) {
  void* llvm = dlopen("libLLVM-15.so.1", RTLD_LAZY | RTLD_NOLOAD);
  return llvm == nullptr ? nullptr : reinterpret_cast<Fn>(dlvsym(llvm, mangled, "LLVM_15"));
}

}  // namespace

// bool llvm::sys::getHostCPUFeatures(llvm::StringMap<bool>&), LLVM 15.
extern "C" bool _ZN4llvm3sys18getHostCPUFeaturesERNS_9StringMapIbNS_15MallocAllocatorEEE(void* features) {
  static const auto real =
      llvm15_symbol<HostFeaturesFn>("_ZN4llvm3sys18getHostCPUFeaturesERNS_9StringMapIbNS_15MallocAllocatorEEE");
  // llvm::X86::updateImpliedFeatures(StringRef, bool, StringMap<bool>&):
  // sets a feature and every feature it implies (avx512f -> avx2, fma, ...).
  static const auto imply =
      llvm15_symbol<UpdateImpliedFn>("_ZN4llvm3X8621updateImpliedFeaturesENS_9StringRefEbRNS_9StringMapIbNS_15MallocAllocatorEEE");
  if (real == nullptr || imply == nullptr || !real(features)) return false;
  static const char* const kAvx512[] = {"avx512f", "avx512cd", "avx512bw", "avx512dq", "avx512vl"};
  for (const char* f : kAvx512) imply(StringRefAbi{f, std::strlen(f)}, true, features);
  return true;
}
