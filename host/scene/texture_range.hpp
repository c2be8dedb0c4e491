// The range of each channel of a glTF image (issue 21): where a texture is
// present mfv checks a textured parameter over the values its texels reach,
// not over [0, factor]. Images are decoded with stb_image (Debian libstb-dev):
// PNG and JPEG, the two image formats glTF 2.0 core allows (spec 3.8.2).
#pragma once

#include <array>
#include <string>

namespace mfv {

struct ChannelRange {
  double lo = 0, hi = 1;  // stored value / 255 (or / 65535), as written in the file
};

struct ImageRanges {
  int width = 0, height = 0, channels = 0;  // channels in the file (1..4)
  std::array<ChannelRange, 4> rgba;         // R, G, B, A; grey images spread to R = G = B; no alpha: A = 1
};

// Decodes PNG or JPEG bytes; throws mfv::Error "<where>: cannot decode ..." otherwise.
ImageRanges image_ranges(const std::string& bytes, const std::string& where);

// RFC 4648 base64 (data: URIs); throws mfv::Error on a character outside the alphabet.
std::string base64_decode(const std::string& text, const std::string& where);

// The sRGB transfer function, encoded value to linear (IEC 61966-2-1): glTF's
// colour textures (baseColorTexture, specularColorTexture, sheenColorTexture)
// are sRGB-encoded, their factors linear.
double srgb_to_linear(double encoded);

}  // namespace mfv
