// The float RGBA image every part of blocklab works on.
//
// Storage is always four floats per texel (R, G, B, A), row-major, top row first. `channels` says how many of
// them the source really had: 1 (luminance files are expanded to R = G = B), 3 (RGB, alpha stored as 1) or
// 4 (RGBA). Values are linear for HDR sources; for 8/16-bit PNG they are the stored code values scaled to [0, 1]
// (no sRGB decoding: LDR PSNR is computed on code values, SPECS.md section 1d).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace blocklab {

struct ImageMetadata {
  std::string source_path;        // file the image was read from ("" when made in memory)
  std::string container;          // "exr", "hdr", "pfm", "png"
  std::string pixel_type;         // "half", "float", "rgbe", "uint8", "uint16"
  bool is_hdr = false;            // true for float sources (EXR, .hdr, PFM), false for PNG
  // OpenEXR `chromaticities` attribute (red xy, green xy, blue xy, white xy) when the file carries one. blocklab
  // does not convert primaries; the attribute is kept so luminance-based metrics can say what they assumed.
  std::optional<std::array<float, 8>> chromaticities;
};

struct Image {
  int width = 0;
  int height = 0;
  int channels = 3;               // 1, 3 or 4 (see above); storage is RGBA regardless
  std::vector<float> pixels;      // width * height * 4
  ImageMetadata metadata;

  Image() = default;
  Image(int w, int h, int source_channels = 3) : width(w), height(h), channels(source_channels),
      pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4, 0.0f) {
    for (std::size_t i = 3; i < pixels.size(); i += 4) pixels[i] = 1.0f;
  }

  std::size_t texel_count() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  bool has_alpha() const { return channels == 4; }
  float* texel(int x, int y) { return &pixels[(static_cast<std::size_t>(y) * width + x) * 4]; }
  const float* texel(int x, int y) const { return &pixels[(static_cast<std::size_t>(y) * width + x) * 4]; }
};

// The width x height rectangle of `image` whose top-left texel is (x, y), with the same channels and metadata.
// The caller guarantees the rectangle lies inside the image (0 <= x, x + width <= image.width, same for y).
inline Image crop_image(const Image& image, int x, int y, int width, int height) {
  Image cropped(width, height, image.channels);
  cropped.metadata = image.metadata;
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col)
      for (int c = 0; c < 4; ++c) cropped.texel(col, row)[c] = image.texel(x + col, y + row)[c];
  return cropped;
}

}  // namespace blocklab
