// On-disk cache of built OpenCL program binaries (CL_PROGRAM_BINARIES), so
// that a later mfv process skips the compiler's front end. One file per
// program, named by the SHA-256 of its key: the device's name, OpenCL
// version and driver version, the build options and the whole source text.
// A file holds a header line with the full key's digest, the payload's size
// and the payload's SHA-256; a file that is truncated, corrupt or written for
// another key is ignored (and replaced by the next build), never trusted.
//
// Where: $MFV_CACHE_DIR, else $XDG_CACHE_HOME/mfv, else $HOME/.cache/mfv.
// On with MFV_PROGRAM_CACHE=1; off where it is 0 or unset (any other value
// is an error). Off by default because on PoCL, asking a program for its
// binary compiles every kernel in it (PoCL's binary holds the compiled
// work-group functions): measured on `mfv run --check d_norm --model ggx`
// with PoCL's own cache off, the first run took 20.6 s of CPU against 5.8 s
// without mfv's cache, the next 4.5 s with builds down from 26.5 s to 0.7 s
// (wall, load 15; docs/performance.md). PoCL's own kernel cache
// (POCL_KERNEL_CACHE, on by default) already makes its second runs warm; this
// cache is for drivers and set-ups without one.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace mfv {

struct DeviceInfo;

class ProgramCache {
 public:
  // The folder from the environment (see above); "" where the cache is off or
  // no folder can be named (no HOME).
  static std::string default_dir();
  // mfv's cache folder whether or not this cache is on (see above; "" where
  // none can be named): checks/furnace_truth.cpp keeps its truths under it.
  static std::string cache_folder();

  explicit ProgramCache(std::string dir) : dir_(std::move(dir)) {}
  bool enabled() const { return !dir_.empty(); }
  const std::string& dir() const { return dir_; }

  // The key's digest: what names the file and is checked inside it.
  static std::string key(const DeviceInfo& device, const std::string& options, const std::string& source);
  std::string path(const std::string& key) const;

  // The binary stored for `key`; nothing where there is none or the file does
  // not check out (wrong magic or key, short, payload digest mismatch).
  std::optional<std::vector<unsigned char>> load(const std::string& key) const;
  // Writes through a temporary file and a rename, so a reader never sees a
  // half-written entry. Failures (read-only folder, full disk) are ignored:
  // the cache only saves time.
  void store(const std::string& key, const std::vector<unsigned char>& binary) const;

 private:
  std::string dir_;
};

}  // namespace mfv
