#include "util/exr.hpp"

#include "util/error.hpp"

#include <fmt/format.h>
#include <tinyexr.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>

namespace mfv {

const ExrChannel* ExrImage::find(const std::string& name) const {
  for (auto& c : channels)
    if (c.name == name) return &c;
  return nullptr;
}

std::string exr_encode(const ExrImage& img) {
  const size_t n = img.channels.size();
  if (n == 0 || img.width <= 0 || img.height <= 0) throw Error("OpenEXR: an image needs a channel and a size");
  std::vector<EXRChannelInfo> info(n);
  std::vector<int> types(n, TINYEXR_PIXELTYPE_FLOAT), stored(n, TINYEXR_PIXELTYPE_FLOAT);
  std::vector<unsigned char*> planes(n);
  for (size_t c = 0; c < n; ++c) {
    const ExrChannel& ch = img.channels[c];
    if (ch.pixel.size() != size_t(img.width) * size_t(img.height) || ch.name.empty() || ch.name.size() > 255)
      throw Error(fmt::format("OpenEXR: channel '{}' does not fit the image", ch.name));
    std::memset(&info[c], 0, sizeof(EXRChannelInfo));
    std::strncpy(info[c].name, ch.name.c_str(), 255);
    if (ch.half) stored[c] = TINYEXR_PIXELTYPE_HALF;
    info[c].pixel_type = stored[c];
    planes[c] = reinterpret_cast<unsigned char*>(const_cast<float*>(ch.pixel.data()));
  }
  EXRHeader header;
  InitEXRHeader(&header);
  header.num_channels = int(n);
  header.channels = info.data();
  header.pixel_types = types.data();
  header.requested_pixel_types = stored.data();  // saving: the type in the file
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
  EXRImage image;
  InitEXRImage(&image);
  image.num_channels = int(n);
  image.images = planes.data();
  image.width = img.width;
  image.height = img.height;
  unsigned char* mem = nullptr;
  const char* err = nullptr;
  const size_t size = SaveEXRImageToMemory(&image, &header, &mem, &err);
  if (size == 0) {
    const std::string why = err ? err : "unknown";
    if (err) FreeEXRErrorMessage(err);
    throw Error("OpenEXR: could not encode the image (" + why + ")");
  }
  std::string out(reinterpret_cast<const char*>(mem), size);
  std::free(mem);
  return out;
}

ExrImage exr_decode(const std::string& bytes, const std::string& what) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const char* err = nullptr;
  auto fail = [&](const std::string& why) {
    const std::string reason = err ? err : why;
    if (err) FreeEXRErrorMessage(err);
    err = nullptr;
    return Error(fmt::format("{}: not a readable OpenEXR image ({})", what, reason));
  };
  EXRVersion version;
  if (ParseEXRVersionFromMemory(&version, data, bytes.size()) != TINYEXR_SUCCESS) throw fail("no EXR signature");
  if (version.tiled || version.multipart || version.non_image) throw fail("tiled, multipart or deep; want a scanline image");
  EXRHeader header;
  InitEXRHeader(&header);
  if (ParseEXRHeaderFromMemory(&header, &version, data, bytes.size(), &err) != TINYEXR_SUCCESS) throw fail("bad header");
  std::unique_ptr<EXRHeader, void (*)(EXRHeader*)> hold_header(&header, [](EXRHeader* h) { FreeEXRHeader(h); });
  std::vector<bool> half(size_t(std::max(0, header.num_channels)));
  for (int c = 0; c < header.num_channels; ++c) {
    half[size_t(c)] = header.pixel_types[c] == TINYEXR_PIXELTYPE_HALF;  // as stored (loading may rewrite it)
    if (header.pixel_types[c] == TINYEXR_PIXELTYPE_UINT)
      throw fail(fmt::format("channel '{}' holds integers; want half or float", header.channels[c].name));
    header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;  // half read as float (exactly)
  }
  EXRImage image;
  InitEXRImage(&image);
  if (LoadEXRImageFromMemory(&image, &header, data, bytes.size(), &err) != TINYEXR_SUCCESS) throw fail("bad pixels");
  std::unique_ptr<EXRImage, void (*)(EXRImage*)> hold_image(&image, [](EXRImage* i) { FreeEXRImage(i); });
  if (!image.images) throw fail("no scanline pixels");
  ExrImage out;
  out.width = image.width;
  out.height = image.height;
  const size_t px = size_t(image.width) * size_t(image.height);
  for (int c = 0; c < header.num_channels; ++c) {
    const float* p = reinterpret_cast<const float*>(image.images[c]);
    out.channels.push_back({header.channels[c].name, std::vector<float>(p, p + px), half[size_t(c)]});
  }
  return out;
}

}  // namespace mfv
