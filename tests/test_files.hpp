// Files for tests: reading one whole, and a scratch folder that is removed
// at the end of the test (every test's temporary files go there).
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace mfv::test {

// The example user BRDFs of mfv check (examples/brdf/), with a trailing '/'.
inline const std::string kBrdfExamples = std::string(MFV_KERNEL_SOURCE_DIR) + "/../examples/brdf/";

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// temp/NAME_PID_N (N counts this process's folders), empty at the start,
// removed at the end.
struct Scratch {
  std::filesystem::path dir;
  explicit Scratch(const std::string& name = "mfv_test")
      : dir(std::filesystem::temp_directory_path() /
            (name + "_" + std::to_string(::getpid()) + "_" + std::to_string(count()++))) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  ~Scratch() { std::filesystem::remove_all(dir); }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  std::string operator/(const std::string& f) const { return (dir / f).string(); }
  // writes `text` to dir/NAME and returns its path
  std::string file(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name, std::ios::binary) << text;
    return (dir / name).string();
  }
  // a copy of `src` here, alone (e.g. a scene with no .bin, no images beside it)
  std::string copy(const std::string& src) const {
    return file(std::filesystem::path(src).filename().string(), slurp(src));
  }

 private:
  static int& count() {
    static int n = 0;
    return n;
  }
};

}  // namespace mfv::test
