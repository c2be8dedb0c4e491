#include "util/temp_files.hpp"

#include "util/error.hpp"

#include <fmt/format.h>

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <mutex>

namespace mfv {
namespace {

constexpr int kSlots = 1024;
constexpr size_t kPathMax = 1024;
// A slot is written while unused, then published by `used` (a lock-free
// atomic: safe to read in a handler); the handler reads only published slots.
char g_paths[kSlots][kPathMax];
std::atomic<bool> g_used[kSlots];
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler reads these");
std::mutex g_claim;  // slots are claimed and released outside the handler only

extern "C" void remove_temps_and_reraise(int sig) {
  for (int i = 0; i < kSlots; ++i)
    if (g_used[i].load()) ::unlink(g_paths[i]);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      ::sigaction(sig, nullptr, &old);
      if (old.sa_handler == SIG_IGN) continue;  // e.g. nohup: keep ignoring it
      struct sigaction sa {};
      sa.sa_handler = remove_temps_and_reraise;
      sigemptyset(&sa.sa_mask);
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

}  // namespace

TempFile::TempFile(const std::string& path) {
  if (path.size() >= kPathMax) throw Error(fmt::format("path too long for a temporary file: {}", path));
  install_handlers();
  std::lock_guard<std::mutex> g(g_claim);
  for (int i = 0; i < kSlots; ++i)
    if (!g_used[i].load()) {
      std::memcpy(g_paths[i], path.c_str(), path.size() + 1);
      g_used[i].store(true);
      slot_ = i;
      return;
    }
  throw Error(fmt::format("more than {} temporary files at once", kSlots));
}

TempFile::~TempFile() {
  if (slot_ < 0) return;
  std::lock_guard<std::mutex> g(g_claim);
  g_used[slot_].store(false);
}

}  // namespace mfv
