// A temporary copy of kernels/ that a test may plant a defect in, and the
// Runtime that builds its programs from that copy.
#pragma once

#include "runtime/opencl.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
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
  // The copy with one defect planted: `from` replaced by `to` in `file`
  // (REQUIREd to be there, so that a moved kernel line cannot leave the
  // copy correct and the test that expects a failure meaningless).
  PlantedKernelDir(const std::string& file, const std::string& from, const std::string& to) : PlantedKernelDir() {
    INFO("planting in " << file << ": " << from);
    REQUIRE(replace(file, from, to));
  }
  ~PlantedKernelDir() { std::filesystem::remove_all(dir_); }
  PlantedKernelDir(const PlantedKernelDir&) = delete;
  PlantedKernelDir& operator=(const PlantedKernelDir&) = delete;
  std::string path() const { return dir_.string(); }

  // A Runtime on the default device that builds from this copy (it must not
  // outlive the copy).
  Runtime runtime() const { return Runtime("", path()); }

  // Replaces the first occurrence of `from` in `file`; false if absent.
  bool replace(const std::string& file, const std::string& from, const std::string& to) {
    auto p = dir_ / file;
    std::string text = slurp(p);
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
