// Float OpenEXR images in memory through tinyexr (Debian libtinyexr-dev):
// mfv energy --layout's float tables and --compare's reader of them
// (docs/energy-layouts.md). Scanline images, one plane per channel.
#pragma once

#include <string>
#include <vector>

namespace mfv {

struct ExrChannel {
  std::string name;          // "Y", "R", "G", "B", ...
  std::vector<float> pixel;  // w x h, row 0 (the top row in a viewer) first
  bool half = false;         // stored as 16-bit half floats (mfv's tables are 32-bit floats)
};

struct ExrImage {
  int width = 0, height = 0;
  std::vector<ExrChannel> channels;  // in the file's order (EXR sorts channel names)
  const ExrChannel* find(const std::string& name) const;
};

// An EXR (ZIP compressed) of `img`'s channels, each stored as 32-bit float
// or, where `half`, as 16-bit half float; throws mfv::Error.
std::string exr_encode(const ExrImage& img);

// Decodes a scanline EXR of half or float channels; throws mfv::Error
// "<what>: not a readable OpenEXR image (<tinyexr's reason>)" otherwise
// (tiled, deep, multipart or 32-bit integer channels included).
ExrImage exr_decode(const std::string& bytes, const std::string& what);

}  // namespace mfv
