#include "scene/texture_range.hpp"

#include "util/error.hpp"

#include <fmt/format.h>
#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace mfv {

ImageRanges image_ranges(const std::string& bytes, const std::string& where) {
  ImageRanges out;
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int len = int(std::min<size_t>(bytes.size(), size_t(INT32_MAX)));
  int w = 0, h = 0, n = 0;
  const bool sixteen = stbi_is_16_bit_from_memory(data, len) != 0;
  // 4 channels requested: stb spreads grey to RGB and fills a missing alpha with the maximum
  std::unique_ptr<void, void (*)(void*)> pixels(
      sixteen ? static_cast<void*>(stbi_load_16_from_memory(data, len, &w, &h, &n, 4))
              : static_cast<void*>(stbi_load_from_memory(data, len, &w, &h, &n, 4)),
      stbi_image_free);
  if (!pixels)
    throw Error(fmt::format("{}: cannot decode the image ({}; glTF images are PNG or JPEG)", where,
                            stbi_failure_reason() ? stbi_failure_reason() : "unknown reason"));
  out.width = w, out.height = h, out.channels = n;
  const size_t texels = size_t(w) * size_t(h);
  for (int c = 0; c < 4; ++c) {
    double lo = 1, hi = 0;
    for (size_t t = 0; t < texels; ++t) {
      const double v = sixteen ? static_cast<const uint16_t*>(pixels.get())[4 * t + size_t(c)] / 65535.0
                               : static_cast<const stbi_uc*>(pixels.get())[4 * t + size_t(c)] / 255.0;
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
    out.rgba[size_t(c)] = {lo, hi};
  }
  return out;
}

std::string base64_decode(const std::string& text, const std::string& where) {
  std::string out;
  uint32_t acc = 0;
  int bits = 0;
  for (char ch : text) {
    int v;
    if (ch >= 'A' && ch <= 'Z')
      v = ch - 'A';
    else if (ch >= 'a' && ch <= 'z')
      v = ch - 'a' + 26;
    else if (ch >= '0' && ch <= '9')
      v = ch - '0' + 52;
    else if (ch == '+' || ch == '-')
      v = 62;  // '-', '_': the URL-safe alphabet (RFC 4648 §5)
    else if (ch == '/' || ch == '_')
      v = 63;
    else if (ch == '=')
      break;
    else
      throw Error(fmt::format("{}: the data URI is not base64 (character '{}')", where, ch));
    acc = (acc << 6) | uint32_t(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += char((acc >> bits) & 0xFF);
    }
  }
  return out;
}

double srgb_to_linear(double c) {
  // IEC 61966-2-1: linear segment below 0.04045, else ((c + 0.055)/1.055)^2.4
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

}  // namespace mfv
