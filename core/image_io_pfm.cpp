// Portable Float Map (PFM) reader and writer.
//
// Format (Paul Debevec's PFM description, the de-facto spec; also netpbm's "pfm"):
//   "PF" (3 channels, RGB) or "Pf" (1 channel, grey), whitespace,
//   width, whitespace, height, whitespace,
//   scale: a non-zero decimal number whose sign gives the byte order (negative: little-endian, positive:
//   big-endian); its magnitude is informational and is ignored here,
//   exactly one whitespace byte (normally '\n'), then width * height * channels IEEE-754 binary32 values,
//   rows stored BOTTOM-TO-TOP, each row left to right, and nothing after them. The reader rejects any file whose
//   size after the header differs from that (an extra header token or blank line would shift the raster).
// Writer: always colour ("PF"), little-endian (scale -1.0), alpha is dropped (PFM has no alpha channel).
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/atomic_write.h"
#include "core/image_io_detail.h"

namespace blocklab::image_io_detail {
namespace {

bool is_pfm_space(std::uint8_t c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

// Returns the next whitespace-delimited token of the header, starting at `pos` (leading whitespace skipped).
std::string next_token(const std::string& path, const Bytes& bytes, std::size_t& pos, const char* what) {
  while (pos < bytes.size() && is_pfm_space(bytes[pos])) ++pos;
  const std::size_t start = pos;
  // A header token longer than 64 characters is garbage, not a number: stop there instead of scanning the file.
  while (pos < bytes.size() && !is_pfm_space(bytes[pos]) && pos - start <= 64) ++pos;
  if (pos == start) fail(path, std::string("truncated PFM header (missing ") + what + ")");
  if (pos - start > 64) fail(path, std::string("invalid PFM header (") + what + " is not a number)");
  return std::string(bytes.begin() + static_cast<std::ptrdiff_t>(start), bytes.begin() + static_cast<std::ptrdiff_t>(pos));
}

std::int64_t parse_dimension(const std::string& path, const std::string& token, const char* what) {
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(token.c_str(), &end, 10);
  if (end != token.c_str() + token.size() || errno != 0 || value <= 0) {
    fail(path, std::string("invalid PFM ") + what + " \"" + token + "\"");
  }
  return value;
}

float load_float(const std::uint8_t* p, bool little_endian) {
  std::uint32_t bits = little_endian
      ? (std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 | std::uint32_t{p[3]} << 24)
      : (std::uint32_t{p[3]} | std::uint32_t{p[2]} << 8 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[0]} << 24);
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

void store_float_little_endian(float value, std::uint8_t* p) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(bits >> (8 * i));
}

}  // namespace

Image read_pfm(const std::string& path, const Bytes& bytes) {
  std::size_t pos = 0;
  const std::string magic = next_token(path, bytes, pos, "type");
  if (magic != "PF" && magic != "Pf") fail(path, "invalid PFM type \"" + magic + "\" (expected PF or Pf)");
  const int file_channels = magic == "PF" ? 3 : 1;
  const std::int64_t width = parse_dimension(path, next_token(path, bytes, pos, "width"), "width");
  const std::int64_t height = parse_dimension(path, next_token(path, bytes, pos, "height"), "height");
  const std::string scale_token = next_token(path, bytes, pos, "scale");
  char* end = nullptr;
  const double scale = std::strtod(scale_token.c_str(), &end);
  // Zero or non-finite scale carries no byte order: reject rather than guess.
  if (end != scale_token.c_str() + scale_token.size() || !std::isfinite(scale) || scale == 0.0) {
    fail(path, "invalid PFM scale \"" + scale_token + "\" (must be a non-zero number)");
  }
  const bool little_endian = scale < 0.0;
  // Exactly one whitespace byte separates the scale from the raster (the raster may start with a byte that
  // looks like whitespace, so no further skipping).
  if (pos >= bytes.size() || !is_pfm_space(bytes[pos])) fail(path, "truncated PFM header (no raster)");
  ++pos;

  check_image_size(path, width, height);
  const std::uint64_t needed = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) *
                               static_cast<std::uint64_t>(file_channels) * 4;
  const std::uint64_t available = bytes.size() - pos;
  // Checked before allocating: a truncated file or a lying header never causes a large allocation. Extra bytes are
  // an error too: a stray header token or a second line break after the scale shifts the whole raster, which
  // would otherwise decode to plausible-looking garbage.
  if (available != needed) {
    fail(path, std::string(available < needed ? "truncated PFM raster: " : "PFM raster size mismatch: ") +
                   std::to_string(available) + " bytes after the header, " + std::to_string(needed) +
                   " expected for " + std::to_string(width) + " x " + std::to_string(height) + " x " +
                   std::to_string(file_channels) + " floats (the scale line must be followed by exactly one "
                   "whitespace byte, then the raster and nothing else)");
  }

  Image image(static_cast<int>(width), static_cast<int>(height), file_channels);
  const std::uint8_t* raster = bytes.data() + pos;
  for (std::int64_t file_row = 0; file_row < height; ++file_row) {
    // File rows run bottom-to-top; Image rows top-to-bottom.
    const int y = static_cast<int>(height - 1 - file_row);
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = raster + (static_cast<std::uint64_t>(file_row) * static_cast<std::uint64_t>(width) +
                                        static_cast<std::uint64_t>(x)) * static_cast<std::uint64_t>(file_channels) * 4;
      float* texel = image.texel(x, y);
      if (file_channels == 3) {
        texel[0] = load_float(p, little_endian);
        texel[1] = load_float(p + 4, little_endian);
        texel[2] = load_float(p + 8, little_endian);
      } else {
        texel[0] = texel[1] = texel[2] = load_float(p, little_endian);
      }
    }
  }
  image.metadata.container = "pfm";
  image.metadata.pixel_type = "float";
  image.metadata.is_hdr = true;
  return image;
}

void write_pfm(const std::string& path, const Image& image) {
  const std::string header = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
  Bytes bytes(header.begin(), header.end());
  const std::size_t raster_start = bytes.size();
  bytes.resize(raster_start + image.texel_count() * 12);
  std::uint8_t* out = bytes.data() + raster_start;
  for (int y = image.height - 1; y >= 0; --y) {  // bottom row first
    for (int x = 0; x < image.width; ++x) {
      const float* texel = image.texel(x, y);
      for (int c = 0; c < 3; ++c, out += 4) store_float_little_endian(texel[c], out);
    }
  }
  write_file_atomically(path, bytes);
}

}  // namespace blocklab::image_io_detail
