// Files for the scene tests: a GLB container around a JSON chunk (and an
// optional BIN chunk), and a scene's material by name. Their temporary folder
// is test_files.hpp's Scratch.
#pragma once

#include "scene/scene.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>

namespace mfv::test {

// A GLB container (glTF 2.0 §4.4) holding `json` as its JSON chunk and `bin`, if any, as its BIN chunk.
inline std::string glb_of(std::string json, std::string bin = "") {
  while (json.size() % 4) json += ' ';
  while (bin.size() % 4) bin += '\0';
  std::string out = "glTF";
  auto u32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  u32(2);
  u32(uint32_t(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size())));
  u32(uint32_t(json.size()));
  u32(0x4E4F534Au);  // "JSON"
  out += json;
  if (!bin.empty()) {
    u32(uint32_t(bin.size()));
    u32(0x004E4942u);  // "BIN\0"
    out += bin;
  }
  return out;
}

inline const SceneMaterial& named(const Scene& s, const std::string& name) {
  for (auto& m : s.materials)
    if (m.name == name) return m;
  FAIL("no material " << name);
  return s.materials.front();
}

}  // namespace mfv::test
