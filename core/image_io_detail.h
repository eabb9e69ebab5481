// Internal interface between the image I/O dispatcher (core/image_io.cpp) and the per-format readers/writers
// (core/image_io_exr.cpp, image_io_hdr.cpp, image_io_pfm.cpp, image_io_png.cpp). Not part of the public API.
//
// Every reader gets the whole file already in memory, so it always knows how many bytes really exist and can
// check every size the file claims against that before allocating anything. Every reader and writer reports a
// failure by throwing blocklab::Error("<path>: <reason>") (core/error.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "core/image_io.h"

namespace blocklab::image_io_detail {

using Bytes = std::vector<std::uint8_t>;

// Largest image any reader accepts: 2^27 texels (e.g. 16384 x 8192, a 16k lat-long map), i.e. 2 GiB of RGBA
// float. A corrupt header that claims more is rejected before anything is allocated.
constexpr std::uint64_t kMaxTexels = std::uint64_t{1} << 27;

// Throws "<path>: image size W x H ..." unless 0 < width, 0 < height and width * height <= kMaxTexels.
inline void check_image_size(const std::string& path, std::int64_t width, std::int64_t height) {
  if (width <= 0 || height <= 0) {
    fail(path, "invalid image size " + std::to_string(width) + " x " + std::to_string(height));
  }
  // Each side is checked alone first: the 64-bit product of two sides of 2^32 or more wraps (2^32 * 2^32 = 0).
  if (static_cast<std::uint64_t>(width) > kMaxTexels || static_cast<std::uint64_t>(height) > kMaxTexels ||
      static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) > kMaxTexels) {
    fail(path, "image size " + std::to_string(width) + " x " + std::to_string(height) +
                   " exceeds the limit of " + std::to_string(kMaxTexels) + " texels");
  }
}

// True when `bytes` starts with a Radiance header whose "#?" program line or FORMAT= line is not first (some
// writers put VIEW= or other lines before it). Files starting with "#?" are recognised without this.
bool has_radiance_signature(const Bytes& bytes);

// Readers: `bytes` is the complete file content (its magic bytes already identified the format).
Image read_exr(const std::string& path, const Bytes& bytes);
Image read_radiance_hdr(const std::string& path, const Bytes& bytes);
Image read_pfm(const std::string& path, const Bytes& bytes);
Image read_png(const std::string& path, const Bytes& bytes);

// Writers: `image` has already been validated (positive size, pixels.size() == w * h * 4, channels 1/3/4).
void write_exr(const std::string& path, const Image& image, ExrPixelType pixel_type);
void write_radiance_hdr(const std::string& path, const Image& image);
void write_pfm(const std::string& path, const Image& image);
void write_png(const std::string& path, const Image& image, int bits);
// Each writer encodes the whole file in memory and stores it with write_file_atomically (core/atomic_write.h), so
// a failed write is reported and never leaves a partial file at `path`.

}  // namespace blocklab::image_io_detail
