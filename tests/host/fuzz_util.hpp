// A small mutation fuzzer for Catch2 (issue 17): corpus files from
// tests/fuzz/corpus/ mutated by byte edits and by splicing tokens from a
// dictionary of known-hard values, for a bounded time. MFV_FUZZ_SECONDS sets
// the time per target (default 5; the fuzz-long test gives 600) and
// MFV_FUZZ_SEED the first seed (default 1), so every run is reproducible.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace mfv::fuzz {

inline double budget_seconds() {
  const char* s = std::getenv("MFV_FUZZ_SECONDS");
  return s ? std::atof(s) : 5.0;
}

inline uint64_t first_seed() {
  const char* s = std::getenv("MFV_FUZZ_SEED");
  return s ? std::strtoull(s, nullptr, 10) : 1;
}

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Every file of a corpus folder, in name order.
inline std::vector<std::filesystem::path> corpus(const std::string& sub) {
  std::vector<std::filesystem::path> files;
  for (auto& e : std::filesystem::directory_iterator(std::filesystem::path(MFV_FUZZ_DIR) / "corpus" / sub))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  REQUIRE_FALSE(files.empty());
  return files;
}

// Values that broke parsers before, or that sit on a type's edge.
inline const std::vector<std::string>& dictionary() {
  static const std::vector<std::string> d = {"1e400",
                                             "-1e400",
                                             "1e-400",
                                             "NaN",
                                             "\"NaN\"",
                                             "null",
                                             "true",
                                             "false",
                                             "\"0.2\"",
                                             "\"red\"",
                                             "[]",
                                             "{}",
                                             "[1,2,3]",
                                             "[1,2,3,4,5]",
                                             "[0.5,0.5,0.5,1]",
                                             "-1",
                                             "0",
                                             "-0",
                                             "1e30",
                                             "1e-9",
                                             "18446744073709551616",
                                             "9223372036854775808",
                                             "-9223372036854775809",
                                             "2e19",
                                             "1.7976931348623157e308",
                                             "4.9e-324",
                                             "\"\"",
                                             "\"ggx\"",
                                             "\"smith_ggx\"",
                                             "\"schlick\"",
                                             "\"gltf\"",
                                             "\"dgf\"",
                                             "\"roughness\"",
                                             "\"alpha\"",
                                             "\"params\"",
                                             "\"KHR_materials_ior\"",
                                             "\"KHR_materials_specular\"",
                                             "\"KHR_materials_anisotropy\"",
                                             "\"materials\"",
                                             ",",
                                             ":",
                                             "\"",
                                             "\\u0000",
                                             "{\"ior\": 0}",
                                             "{\"ior\": -1}",
                                             "{\"ior\": \"1.5\"}",
                                             "\xff\xfe",
                                             "glTF"};
  return d;
}

// One random edit: flip a byte, insert or delete a run, duplicate a span,
// or put a dictionary token at a random place (often replacing a number).
inline std::string mutate(std::string s, std::mt19937_64& rng) {
  auto pick = [&](size_t n) { return n == 0 ? size_t(0) : size_t(rng() % n); };
  int edits = 1 + int(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    size_t at = pick(s.size() + 1);
    switch (rng() % 6) {
      case 0:
        if (!s.empty()) s[pick(s.size())] ^= char(1u << (rng() % 8));
        break;
      case 1: s.insert(at, std::string(1 + pick(8), char(rng() % 256))); break;
      case 2: s.erase(at, pick(16)); break;
      case 3: {
        size_t from = pick(s.size()), len = pick(64);
        s.insert(at, s.substr(from, len));
        break;
      }
      default: {
        const std::string& tok = dictionary()[pick(dictionary().size())];
        // replace the number (or literal) at a random place, if any
        size_t n = s.find_first_of("-0123456789tfn", at);
        if (n != std::string::npos && rng() % 2) {
          size_t end = s.find_first_of(",]} \n", n);
          s.replace(n, (end == std::string::npos ? s.size() : end) - n, tok);
        } else {
          s.insert(at, tok);
        }
      }
    }
  }
  return s;
}

// Runs `one(input, seed)` on mutated corpus inputs until the budget is spent.
template <class F>
uint64_t run(const std::vector<std::filesystem::path>& files, F one) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(budget_seconds());
  uint64_t n = 0;
  for (uint64_t seed = first_seed(); std::chrono::steady_clock::now() < end; ++seed, ++n) {
    std::mt19937_64 rng(seed);
    const auto& file = files[size_t(rng() % files.size())];
    std::string input = read_file(file);
    int rounds = 1 + int(rng() % 3);
    for (int r = 0; r < rounds; ++r) input = mutate(input, rng);
    one(file, input, seed);
  }
  return n;
}

}  // namespace mfv::fuzz
