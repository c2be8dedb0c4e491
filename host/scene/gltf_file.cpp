// glTF containers and images (scene/gltf_file.hpp): GLB chunks (§4.4), URIs
// (data: or a file beside the scene, §3.8.4), images from a uri or a
// bufferView (§3.8), decoded only where a texture scales a checked parameter.
#include "scene/gltf_file.hpp"

#include "scene/json_input.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <sstream>

namespace mfv {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

uint32_t u32_at(const std::string& b, size_t at) {
  uint32_t v;
  std::memcpy(&v, b.data() + at, 4);  // GLB is little-endian, as every platform mfv builds on
  return v;
}

// GLB (§4.4): magic "glTF", version 2, length; chunk 0 JSON; chunk 1 BIN (optional).
std::string glb_json(GltfFile& f, const std::string& bytes) {
  auto bad = [&](const std::string& why) {
    return Error(fmt::format("{}: not a valid glTF binary (.glb) file: {}", f.path, why));
  };
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) throw bad("no 'glTF' header");
  if (u32_at(bytes, 4) != 2) throw bad(fmt::format("container version {} (2 expected)", u32_at(bytes, 4)));
  const size_t total = std::min<size_t>(u32_at(bytes, 8), bytes.size());
  const size_t json_len = u32_at(bytes, 12);
  if (u32_at(bytes, 16) != 0x4E4F534Au || 20 + json_len > total) throw bad("the first chunk is not a whole JSON chunk");
  const size_t next = 20 + ((json_len + 3) & ~size_t(3));
  if (next + 8 <= total && u32_at(bytes, next + 4) == 0x004E4942u) {  // "BIN\0"
    const size_t bin_len = u32_at(bytes, next);
    if (next + 8 + bin_len > total) throw bad("the BIN chunk runs past the end of the file");
    f.bin = bytes.substr(next + 8, bin_len);
  }
  return bytes.substr(20, json_len);
}

// RFC 3986 percent-decoding of a relative URI (glTF §3.8.4: "images/a%20b.png").
std::string uri_to_path(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uint8_t(uri[i + 1])) &&
        std::isxdigit(uint8_t(uri[i + 2]))) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

// The bytes a uri names: a data: URI (base64), or a file beside the scene; nullopt when the file is absent.
std::optional<std::string> uri_bytes(const GltfFile& f, const std::string& uri, const std::string& who) {
  if (uri.rfind("data:", 0) == 0) {
    const size_t comma = uri.find(',');
    if (comma == std::string::npos || uri.substr(0, comma).find(";base64") == std::string::npos)
      throw Error(fmt::format("{}: {}: a data: URI without ';base64,'", f.path, who));
    return base64_decode(uri.substr(comma + 1), f.path + ": " + who);
  }
  const fs::path p = f.dir / uri_to_path(uri);
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) return std::nullopt;
  return read_bytes(p.string());
}

}  // namespace

GltfFile read_gltf_file(const std::string& path, bool binary) {
  GltfFile f;
  f.path = path;
  f.dir = fs::path(path).parent_path();
  f.binary = binary;
  const std::string bytes = read_bytes(path);
  const std::string text = binary ? glb_json(f, bytes) : bytes;
  try {
    f.j = parse_json_strict(path, text);
  } catch (const Error& e) {
    std::string what = e.what();
    if (what.rfind(path + ": ", 0) == 0) what = what.substr(path.size() + 2);
    throw Error(fmt::format("{}: not a valid glTF {} file: {}", path, binary ? "binary (.glb)" : "JSON (.gltf)", what));
  }
  if (!f.j.is_object() || !f.j.contains("asset") || !f.j["asset"].is_object() || !f.j["asset"].contains("version") ||
      !f.j["asset"]["version"].is_string())
    throw Error(
        fmt::format("{}: not a valid glTF {} file: no asset.version", path, binary ? "binary (.glb)" : "JSON (.gltf)"));
  const std::string version = f.j["asset"]["version"].get<std::string>();
  if (version.rfind("2.", 0) != 0) throw Error(fmt::format("{}: glTF version {} (mfv reads 2.x)", path, version));
  return f;
}

const json& top_array(const GltfFile& f, const char* key) {
  static const json empty = json::array();
  if (!f.j.contains(key)) return empty;
  if (!f.j[key].is_array()) throw Error(fmt::format("{}: {} is not an array", f.path, key));
  return f.j[key];
}

const json& element(const GltfFile& f, const char* array, size_t i, const std::string& who) {
  const json& a = top_array(f, array);
  if (i >= a.size())
    throw Error(fmt::format("{}: {} names {}[{}], but the file has {}", f.path, who, array, i, a.size()));
  if (!a[i].is_object()) throw Error(fmt::format("{}: {}[{}] is not an object", f.path, array, i));
  return a[i];
}

namespace {

ImageInfo read_image(const GltfFile& f, size_t index) {
  const json& im = element(f, "images", index, "a texture");
  ImageInfo info;
  const std::string name = im.contains("name") && im["name"].is_string() ? im["name"].get<std::string>() : "";
  const std::string uri = im.contains("uri") && im["uri"].is_string() ? im["uri"].get<std::string>() : "";
  const std::string shown = !uri.empty() && uri.rfind("data:", 0) != 0 ? uri : !name.empty() ? name : "embedded";
  info.label = fmt::format("image {} '{}'", index, shown);
  const std::string mime =
      im.contains("mimeType") && im["mimeType"].is_string() ? im["mimeType"].get<std::string>() : "";
  if (!mime.empty() && mime != "image/png" && mime != "image/jpeg") {
    info.missing = fmt::format("{} is {}, which mfv does not decode", info.label, mime);
    return info;
  }
  std::optional<std::string> bytes;
  if (!uri.empty()) {
    bytes = uri_bytes(f, uri, info.label);
    if (!bytes)
      info.missing = fmt::format("{} is not beside the scene ({})", info.label, (f.dir / uri_to_path(uri)).string());
  } else if (im.contains("bufferView")) {
    const size_t bv_i = json_index(im["bufferView"], fmt::format("{}: images[{}].bufferView", f.path, index));
    const json& bv = element(f, "bufferViews", bv_i, info.label);
    const size_t buf_i =
        json_index(bv.value("buffer", json()), fmt::format("{}: bufferViews[{}].buffer", f.path, bv_i));
    const size_t off = bv.contains("byteOffset") ? json_index(bv["byteOffset"], f.path + ": byteOffset") : 0;
    const size_t len =
        json_index(bv.value("byteLength", json()), fmt::format("{}: bufferViews[{}].byteLength", f.path, bv_i));
    const json& buf = element(f, "buffers", buf_i, info.label);
    std::optional<std::string> data;
    if (!buf.contains("uri") && buf_i == 0 && f.bin)
      data = f.bin;  // GLB: buffer 0 without uri is the BIN chunk
    else if (buf.contains("uri") && buf["uri"].is_string())
      data = uri_bytes(f, buf["uri"].get<std::string>(), info.label);
    if (!data) {
      info.missing = fmt::format("{} sits in buffer {}, which is absent", info.label, buf_i);
    } else {
      if (off + len > data->size())
        throw Error(fmt::format("{}: {}: bufferView {} runs past its buffer", f.path, info.label, bv_i));
      bytes = data->substr(off, len);
    }
  } else {
    throw Error(fmt::format("{}: images[{}] has neither uri nor bufferView", f.path, index));
  }
  if (bytes) info.ranges = image_ranges(*bytes, f.path + ": " + info.label);
  return info;
}

}  // namespace

const ImageInfo& Images::get(size_t i) {
  auto it = cache.find(i);
  return it != cache.end() ? it->second : cache.emplace(i, read_image(f, i)).first->second;
}

}  // namespace mfv
