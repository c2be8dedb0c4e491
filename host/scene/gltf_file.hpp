// A glTF 2.0 file as mfv reads it (issue 21): its JSON (from a .gltf, or a
// .glb's JSON chunk), the GLB BIN chunk, and the channel ranges of the images
// a checked parameter's texture names, each read once. Spec references:
// glTF 2.0 §3.8 (images: uri or bufferView, PNG/JPEG), §4.4 (GLB).
#pragma once

#include "scene/texture_range.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mfv {

struct GltfFile {
  std::string path;
  std::filesystem::path dir;
  bool binary = false;
  nlohmann::json j;
  std::optional<std::string> bin;  // the GLB BIN chunk, where there is one
};

// Reads and checks the container (GLB header and chunks, asset.version 2.x).
GltfFile read_gltf_file(const std::string& path, bool binary);
// The top-level array `key` (empty where absent); not an array is an error.
const nlohmann::json& top_array(const GltfFile& f, const char* key);
// Element i of the top-level array, an object; `who` names the referrer in messages.
const nlohmann::json& element(const GltfFile& f, const char* array, size_t i, const std::string& who);

// One image's channel ranges, or why there are none (missing file, an encoding stb does not read).
struct ImageInfo {
  std::string label;  // "image 1 'mr.png'"
  std::optional<ImageRanges> ranges;
  std::string missing;  // non-empty when ranges is empty
};

// Reads the scene's images once each, on demand.
struct Images {
  const GltfFile& f;
  std::map<size_t, ImageInfo> cache;
  std::map<size_t, std::vector<std::string>> missing_users;  // image -> "material 'x' baseColorTexture"
  const ImageInfo& get(size_t i);                            // read on first use
};

}  // namespace mfv
