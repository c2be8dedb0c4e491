#include "runtime/provenance.hpp"

#include "mfv_git_commit.h"
#include "runtime/opencl.hpp"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <map>
#include <mutex>

namespace mfv {
namespace {

struct Record {
  std::mutex lock;
  std::string command, kernel_dir;
  bool has_device = false;
  std::string device, platform, driver, device_version;
  std::map<std::string, std::string> sources;  // name -> SHA-256 of the text built
};

Record& record() {
  static Record r;
  return r;
}

// A word of the command line as a POSIX shell would need it quoted.
std::string shell_word(const std::string& w) {
  if (!w.empty() && w.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=.,/:@%^") ==
                        std::string::npos)
    return w;
  std::string q = "'";
  for (char c : w) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

std::string sha256_hex(const std::string& data) {
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int n = 0;
  EVP_Digest(data.data(), data.size(), md, &n, EVP_sha256(), nullptr);
  std::string hex;
  for (unsigned int i = 0; i < n; ++i) hex += fmt::format("{:02x}", md[i]);
  return hex;
}

void record_command_line(int argc, const char* const* argv) {
  std::lock_guard<std::mutex> g(record().lock);
  std::string cmd;
  for (int i = 0; i < argc; ++i) cmd += (i ? " " : "") + shell_word(argv[i]);
  record().command = cmd;
}

void record_runtime(const DeviceInfo& d, const std::string& kernel_dir) {
  std::lock_guard<std::mutex> g(record().lock);
  Record& r = record();
  r.has_device = true;
  r.device = d.name;
  r.platform = d.platform;
  r.driver = d.driver;
  r.device_version = d.version;
  r.kernel_dir = kernel_dir;
}

void record_kernel_source(const std::string& name, const std::string& text) {
  std::string digest = sha256_hex(text);
  std::lock_guard<std::mutex> g(record().lock);
  record().sources[name] = digest;
}

nlohmann::json provenance_json() {
  std::lock_guard<std::mutex> g(record().lock);
  const Record& r = record();
  nlohmann::json j;
  j["command"] = r.command;
  j["version"] = MFV_VERSION;
  j["commit"] = MFV_GIT_COMMIT;
  j["kernel_dir"] = r.kernel_dir.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.kernel_dir);
  j["kernel_sources"] = nlohmann::json::object();
  std::string all;
  for (auto& [name, digest] : r.sources) {
    j["kernel_sources"][name] = digest;
    all += name + " " + digest + "\n";
  }
  j["kernel_sha256"] = r.sources.empty() ? nlohmann::json(nullptr) : nlohmann::json(sha256_hex(all));
  if (r.has_device) {
    j["device"] = r.device;
    j["platform"] = r.platform;
    j["driver"] = r.driver;
    j["device_version"] = r.device_version;
  }
  return j;
}

}  // namespace mfv
