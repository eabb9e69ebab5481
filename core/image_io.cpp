// Image I/O dispatcher: reads the whole file, picks the reader from the magic bytes (never the extension) and
// the writer from the output extension. Every writer encodes the whole file in memory and stores it with
// write_file_atomically (core/atomic_write.h): a failed write (disk full, ...) throws and leaves no partial file. The formats themselves live in image_io_exr.cpp (OpenEXR),
// image_io_hdr.cpp (Radiance RGBE), image_io_pfm.cpp (PFM) and image_io_png.cpp (PNG).
//
// Magic bytes recognised:
//   OpenEXR   76 2f 31 01                    (OpenEXR file layout, "magic number")
//   PNG       89 50 4e 47 0d 0a 1a 0a        (PNG specification, section 5.2 "PNG signature")
//   Radiance  "#?"                           (Radiance file header: "#?RADIANCE", "#?RGBE", ...), or leading text
//                                            lines containing a "#?" or FORMAT=32-bit_rle_ line (memorial.hdr)
//   PFM       "PF" or "Pf" + whitespace      (Portable Float Map header)
#include "core/image_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <sys/stat.h>

#include "core/error.h"
#include "core/image_io_detail.h"

namespace blocklab {
namespace {

using image_io_detail::Bytes;

// Reads the whole file with stdio so that errno explains a failure (missing file, permission, directory...).
Bytes read_file_bytes(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) fail(path, std::string("cannot open file (") + std::strerror(errno) + ")");
  if (S_ISDIR(status.st_mode)) fail(path, "is a directory, not an image file");

  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) fail(path, std::string("cannot open file (") + std::strerror(errno) + ")");

  Bytes bytes;
  // Grows in chunks instead of trusting st_size, so special files (pipes, /proc) and files that change size while
  // being read still give exactly the bytes that were there.
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  for (;;) {
    const std::size_t old_size = bytes.size();
    bytes.resize(old_size + kChunk);
    const std::size_t got = std::fread(bytes.data() + old_size, 1, kChunk, file.get());
    bytes.resize(old_size + got);
    if (got < kChunk) break;
  }
  if (std::ferror(file.get())) fail(path, std::string("read error (") + std::strerror(errno) + ")");
  return bytes;
}

bool starts_with(const Bytes& bytes, std::initializer_list<std::uint8_t> magic) {
  return bytes.size() >= magic.size() && std::equal(magic.begin(), magic.end(), bytes.begin());
}

std::string hex_prefix(const Bytes& bytes) {
  std::string text;
  char digits[4];
  for (std::size_t i = 0; i < std::min<std::size_t>(bytes.size(), 8); ++i) {
    std::snprintf(digits, sizeof digits, "%02x", bytes[i]);
    if (!text.empty()) text += ' ';
    text += digits;
  }
  return text;
}

std::string lower_extension(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string extension = path.substr(dot);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

void check_writable_image(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0) {
    fail(path, "cannot write an empty image (" + std::to_string(image.width) + " x " + std::to_string(image.height) + ")");
  }
  if (image.pixels.size() != image.texel_count() * 4) {
    fail(path, "image has " + std::to_string(image.pixels.size()) + " floats, expected width * height * 4 = " +
                   std::to_string(image.texel_count() * 4));
  }
  if (image.channels != 1 && image.channels != 3 && image.channels != 4) {
    fail(path, "image has channels = " + std::to_string(image.channels) + " (must be 1, 3 or 4)");
  }
}

}  // namespace

Image read_image(const std::string& path) {
  const Bytes bytes = read_file_bytes(path);
  if (bytes.empty()) fail(path, "empty file");

  Image image;
  if (starts_with(bytes, {0x76, 0x2f, 0x31, 0x01})) {
    image = image_io_detail::read_exr(path, bytes);
  } else if (starts_with(bytes, {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a})) {
    image = image_io_detail::read_png(path, bytes);
  } else if (starts_with(bytes, {'#', '?'})) {
    image = image_io_detail::read_radiance_hdr(path, bytes);
  } else if (bytes.size() >= 3 && bytes[0] == 'P' && (bytes[1] == 'F' || bytes[1] == 'f') &&
             std::isspace(bytes[2])) {
    image = image_io_detail::read_pfm(path, bytes);
  } else if (image_io_detail::has_radiance_signature(bytes)) {  // checked last: it scans text lines
    image = image_io_detail::read_radiance_hdr(path, bytes);
  } else {
    fail(path, "unsupported file type (first bytes " + hex_prefix(bytes) +
                   "; expected OpenEXR, PNG, Radiance .hdr or PFM)");
  }
  image.metadata.source_path = path;
  return image;
}

void write_image(const std::string& path, const Image& image, const WriteOptions& options) {
  const std::string extension = lower_extension(path);
  if (extension != ".exr" && extension != ".hdr" && extension != ".pfm" && extension != ".png") {
    fail(path, "unsupported output extension \"" + extension + "\" (supported: .exr .hdr .pfm .png)");
  }
  check_writable_image(path, image);
  if (extension == ".exr") {
    image_io_detail::write_exr(path, image, options.exr_pixel_type);
  } else if (extension == ".hdr") {
    image_io_detail::write_radiance_hdr(path, image);
  } else if (extension == ".pfm") {
    image_io_detail::write_pfm(path, image);
  } else {
    if (options.png_bits != 8 && options.png_bits != 16) {
      fail(path, "png_bits must be 8 or 16, got " + std::to_string(options.png_bits));
    }
    image_io_detail::write_png(path, image, options.png_bits);
  }
}

}  // namespace blocklab
