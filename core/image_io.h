// Image readers and writers. The reader is chosen by the file's magic bytes (not its extension); the writer by
// the output extension (.exr, .hdr, .png, .pfm). Every failure throws blocklab::Error("<path>: <reason>").
//
// Readers: OpenEXR (scanline, tiled, first level of mip-mapped files, luminance-only Y, luminance/chroma Y/RY/BY,
// offset data windows, half and float), Radiance .hdr (RLE and flat), PFM (colour and grey, either endianness),
// PNG 8/16-bit (grey, grey+alpha, RGB, RGBA, palette).
// Writers: EXR (half or float), Radiance .hdr (new-style RLE), PNG (8 or 16 bit, values clamped to [0,1] and
// rounded), PFM (float, colour, little-endian).
#pragma once

#include <cstddef>
#include <string>

#include "core/image.h"

namespace blocklab {

Image read_image(const std::string& path);

enum class ExrPixelType { half, float32 };
struct WriteOptions {
  ExrPixelType exr_pixel_type = ExrPixelType::half;
  int png_bits = 8;               // 8 or 16
};
void write_image(const std::string& path, const Image& image, const WriteOptions& options = {});

// What writing `image` as half-float EXR would do to its values (the channels an EXR holds: RGB, and A when
// channels == 4): finite values beyond +-65504 that round to +-Inf, and non-zero values that round to 0.
struct HalfConversionLoss {
  std::size_t overflowed = 0;
  std::size_t flushed_to_zero = 0;
  bool any() const { return overflowed != 0 || flushed_to_zero != 0; }
};
HalfConversionLoss half_conversion_loss(const Image& image);

}  // namespace blocklab
