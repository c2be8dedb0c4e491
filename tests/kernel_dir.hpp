// A temporary copy of kernels/ that a test may plant a defect in.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace mfv::test {

class PlantedKernelDir {
 public:
  PlantedKernelDir() {
    namespace fs = std::filesystem;
    dir_ = fs::temp_directory_path() /
           fs::path("mfv_kernels_" + std::to_string(::getpid()) + "_" + std::to_string(counter()++));
    fs::remove_all(dir_);
    fs::copy(MFV_KERNEL_SOURCE_DIR, dir_, fs::copy_options::recursive);
  }
  ~PlantedKernelDir() { std::filesystem::remove_all(dir_); }
  std::string path() const { return dir_.string(); }

  // Replaces the first occurrence of `from` in `file`; false if absent.
  bool replace(const std::string& file, const std::string& from, const std::string& to) {
    auto p = dir_ / file;
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    auto pos = text.find(from);
    if (pos == std::string::npos) return false;
    text.replace(pos, from.size(), to);
    std::ofstream(p) << text;
    return true;
  }

 private:
  static int& counter() {
    static int c = 0;
    return c;
  }
  std::filesystem::path dir_;
};

}  // namespace mfv::test
