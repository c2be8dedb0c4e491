#include "util/files.hpp"

#include "util/error.hpp"
#include "util/temp_files.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace mfv {

std::string read_text_file(const std::string& path, const std::string& option) {
  std::ifstream in(path);
  std::stringstream ss;
  if (!in || !(ss << in.rdbuf())) throw Error(fmt::format("{} {}: cannot read the file", option, path));
  return ss.str();
}

void prepare_output_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw Error(fmt::format("--out {}: exists and is not a folder", dir));
  if (dir.empty()) throw Error("--out: the folder name is empty");
  fs::create_directories(dir, ec);
  if (ec) throw Error(fmt::format("--out {}: cannot create that folder ({})", dir, ec.message()));
  // Writable? A probe file now, not a failed rename after the whole run.
  std::string probe = (fs::path(dir) / fmt::format(".mfv-write-probe-{}", ::getpid())).string();
  bool ok = static_cast<bool>(std::ofstream(probe, std::ios::binary | std::ios::trunc));
  fs::remove(probe, ec);
  if (!ok) throw Error(fmt::format("--out {}: cannot write files in that folder ({})", dir, std::strerror(errno)));
}

void write_files_atomically(const std::vector<std::pair<std::string, std::string>>& files) {
  namespace fs = std::filesystem;
  std::vector<std::string> temps;
  std::vector<TempFile> registered;  // removed by a signal handler until renamed (util/temp_files.hpp)
  auto cleanup = [&] {
    std::error_code ec;
    for (auto& t : temps) fs::remove(t, ec);
  };
  for (auto& [path, text] : files) {
    std::error_code ec;
    fs::path parent = fs::path(path).parent_path();
    if (!parent.empty()) fs::create_directories(parent, ec);
    std::string tmp = path + ".tmp-mfv";
    registered.emplace_back(tmp);
    temps.push_back(tmp);
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (out) out << text;
    out.flush();
    if (!out) {
      cleanup();
      throw Error(fmt::format("cannot write {}; earlier results are untouched", path));
    }
  }
  for (size_t i = 0; i < files.size(); ++i) {
    std::error_code ec;
    fs::rename(temps[i], files[i].first, ec);
    if (ec) {
      cleanup();
      throw Error(fmt::format("cannot move {} into place: {}", files[i].first, ec.message()));
    }
  }
}

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string utc_timestamp() {
  std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

}  // namespace mfv
