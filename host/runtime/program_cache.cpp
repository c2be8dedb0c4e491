#include "runtime/program_cache.hpp"

#include "runtime/opencl.hpp"
#include "runtime/provenance.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <unistd.h>

namespace mfv {
namespace {

constexpr const char* kMagic = "mfv-program-cache-1";
constexpr size_t kMaxHeader = 256;  // magic, two digests, a size: well under this

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "";
}

}  // namespace

std::string ProgramCache::default_dir() {
  const std::string on = env("MFV_PROGRAM_CACHE");
  if (!on.empty() && on != "0" && on != "1")
    throw Error(fmt::format("MFV_PROGRAM_CACHE={}: expected 0 (off) or 1 (on)", on));
  if (on != "1") return "";  // off unless asked for (see program_cache.hpp)
  return cache_folder();
}

std::string ProgramCache::cache_folder() {
  if (std::string d = env("MFV_CACHE_DIR"); !d.empty()) return d;
  if (std::string x = env("XDG_CACHE_HOME"); !x.empty()) return x + "/mfv";
  if (std::string h = env("HOME"); !h.empty()) return h + "/.cache/mfv";
  return "";
}

std::string ProgramCache::key(const DeviceInfo& device, const std::string& options, const std::string& source) {
  // Length-prefixed fields, so no two different keys concatenate alike.
  std::string k;
  for (const std::string* f : {&device.platform, &device.name, &device.version, &device.driver, &options, &source})
    k += std::to_string(f->size()) + ":" + *f + ";";
  return sha256_hex(k);
}

std::string ProgramCache::path(const std::string& key) const { return dir_ + "/" + key + ".bin"; }

std::optional<std::vector<unsigned char>> ProgramCache::load(const std::string& key) const {
  if (!enabled()) return std::nullopt;
  std::ifstream in(path(key), std::ios::binary);
  if (!in) return std::nullopt;
  std::string header;
  for (char c; header.size() < kMaxHeader && in.get(c) && c != '\n';) header += c;
  std::istringstream h(header);
  std::string magic, file_key, digest;
  uint64_t size = 0;
  if (!(h >> magic >> file_key >> size >> digest) || magic != kMagic || file_key != key) return std::nullopt;
  std::vector<unsigned char> payload((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (payload.size() != size || size == 0) return std::nullopt;                                // truncated, or grown
  if (sha256_hex(std::string(payload.begin(), payload.end())) != digest) return std::nullopt;  // corrupt
  return payload;
}

void ProgramCache::store(const std::string& key, const std::vector<unsigned char>& binary) const {
  if (!enabled() || binary.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) return;
  // A name no other process writes (pid), renamed over the entry at the end.
  const std::string tmp = fmt::format("{}.{}.tmp", path(key), ::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return;
    out << kMagic << ' ' << key << ' ' << binary.size() << ' ' << sha256_hex(std::string(binary.begin(), binary.end()))
        << '\n';
    out.write(reinterpret_cast<const char*>(binary.data()), std::streamsize(binary.size()));
    if (!out.flush()) {
      out.close();
      std::filesystem::remove(tmp, ec);
      return;
    }
  }
  std::filesystem::rename(tmp, path(key), ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

}  // namespace mfv
