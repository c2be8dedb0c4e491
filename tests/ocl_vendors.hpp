// The extra OpenCL implementations that scripts/install-ocl-extras.sh
// installs under $MFV_OCL_CACHE (default ~/.cache/mfv/ocl), each with its own
// ICD folder, for the `portability` tests.
#pragma once

#include "skip.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace mfv::test {

// The ICD folder of `name` (intel, oclgrind, rusticl), or "" (with a
// message) when it or the library it names is missing.
inline std::string vendor_dir(const std::string& name) {
  namespace fs = std::filesystem;
  const char* cache = std::getenv("MFV_OCL_CACHE");
  const char* home = std::getenv("HOME");
  fs::path root = cache ? fs::path(cache) : fs::path(home ? home : "/root") / ".cache/mfv/ocl";
  fs::path dir = root / "vendors" / name, icd = dir / (name + ".icd");
  std::string lib;
  if (std::ifstream in(icd); in) std::getline(in, lib);
  if (lib.empty() || !fs::exists(lib)) {
    skip(name + " OpenCL implementation not installed (" + icd.string() +
         "); run scripts/install-ocl-extras.sh to run its portability tests");
    return "";
  }
  return dir.string();
}

// The environment that selects `name` from its ICD folder `dir`.
inline std::string vendor_env(const std::string& name, const std::string& dir) {
  std::string env = "OCL_ICD_VENDORS=" + dir;
  if (name == "rusticl") env += " RUSTICL_ENABLE=llvmpipe";
  return env;
}

}  // namespace mfv::test
