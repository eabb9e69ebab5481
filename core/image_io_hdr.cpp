// Radiance RGBE (.hdr / .pic) reader and writer.
//
// Reference: G. Ward, "Real Pixels", Graphics Gems II (1991) and his public-domain rgbe.c/rgbe.h (1995), plus the
// Radiance file-format notes (header, resolution string, scanline encodings):
//   header      text lines, normally starting with "#?RADIANCE" (or "#?RGBE"), ended by an empty line; the
//               FORMAT= line must say 32-bit_rle_rgbe (32-bit_rle_xyze, the XYZ variant, is rejected);
//   resolution  "-Y H +X W" (standard: top row first, left to right); "+Y" (bottom row first) and "-X" (right to
//               left) are also accepted; the transposed forms ("+X W -Y H" ...) are rejected;
//   scanlines   new-style RLE (4 bytes 2 2 W_hi W_lo, then each of the 4 components run-length coded: a count byte
//               > 128 is a run of count-128 copies of the next byte, a count 1..128 is that many literal bytes),
//               flat 4-byte RGBE pixels, or old-style RLE (pixel 1 1 1 n repeats the previous pixel n << shift
//               times; consecutive repeat pixels raise the shift by 8).
// Decoding is two passes over the pixel stream: the first only validates it (no allocation), the second decodes,
// so a truncated or corrupt file is rejected before the image buffer is allocated.
// RGBE -> float follows Ward's rgbe.c: e == 0 -> 0, otherwise value = mantissa * 2^(e - 136).
// float -> RGBE follows Ward's float2rgbe: frexp of the largest channel (see encode_rgbe).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "core/atomic_write.h"
#include "core/image_io_detail.h"

namespace blocklab::image_io_detail {
namespace {

// A header longer than this is not a Radiance header (real ones are a few hundred bytes).
constexpr std::size_t kMaxHeaderBytes = 64 * 1024;
// New-style RLE can only describe scanline widths 8..0x7fff (the width is stored in 15 bits; Ward's encoder
// writes narrower lines flat).
constexpr int kMinRleWidth = 8;
constexpr int kMaxRleWidth = 0x7fff;

struct Cursor {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t pos;
  std::size_t remaining() const { return size - pos; }
};

[[noreturn]] void fail_scanline(const std::string& path, int scanline, const std::string& why) {
  fail(path, "scanline " + std::to_string(scanline) + ": " + why);
}

// New-style RLE scanline (the 4-byte marker already consumed): four component planes, each run-length coded.
// Writes component c of pixel x to out[4 * x + c] unless `out` is null (validation pass).
void decode_rle_scanline(const std::string& path, Cursor& in, int width, int scanline, std::uint8_t* out) {
  for (int component = 0; component < 4; ++component) {
    int x = 0;
    while (x < width) {
      if (in.remaining() < 2) fail_scanline(path, scanline, "truncated RLE data");
      int count = in.data[in.pos++];
      if (count > 128) {  // a run: count - 128 copies of the next byte
        count -= 128;
        if (count > width - x) fail_scanline(path, scanline, "RLE run overruns the scanline");
        const std::uint8_t value = in.data[in.pos++];
        if (out) for (int i = 0; i < count; ++i) out[4 * (x + i) + component] = value;
      } else {
        // Count 0 would be a dump of nothing: Ward's reader rejects it as bad scanline data (it also cannot loop).
        if (count == 0) fail_scanline(path, scanline, "zero-length RLE literal run");
        if (count > width - x) fail_scanline(path, scanline, "RLE literal run overruns the scanline");
        if (in.remaining() < static_cast<std::size_t>(count)) fail_scanline(path, scanline, "truncated RLE data");
        if (out) for (int i = 0; i < count; ++i) out[4 * (x + i) + component] = in.data[in.pos + i];
        in.pos += static_cast<std::size_t>(count);
      }
      x += count;
    }
  }
}

// Flat 4-byte pixels, with old-style run-length pixels (1, 1, 1, n) allowed. A well-formed RGBE pixel never has
// mantissas 1 1 1 (the largest mantissa is always >= 128), so the marker is unambiguous.
void decode_flat_scanline(const std::string& path, Cursor& in, int width, int scanline, std::uint8_t* out) {
  int x = 0;
  int shift = 0;
  while (x < width) {
    if (in.remaining() < 4) fail_scanline(path, scanline, "truncated pixel data");
    const std::uint8_t* pixel = in.data + in.pos;
    in.pos += 4;
    if (pixel[0] == 1 && pixel[1] == 1 && pixel[2] == 1) {
      // Old-style run: repeat the previous pixel of this scanline. At the start of a scanline there is none
      // (Radiance would read before its buffer): reject.
      if (x == 0) fail_scanline(path, scanline, "old-style RLE run with no preceding pixel");
      // shift grows by 8 per consecutive run marker; beyond 16 the count cannot fit any legal scanline.
      if (shift > 16) fail_scanline(path, scanline, "old-style RLE run count overflows");
      const std::int64_t count = static_cast<std::int64_t>(pixel[3]) << shift;
      if (count > width - x) fail_scanline(path, scanline, "old-style RLE run overruns the scanline");
      if (out) {
        for (std::int64_t i = 0; i < count; ++i) std::memcpy(out + 4 * (x + i), out + 4 * (x - 1), 4);
      }
      x += static_cast<int>(count);
      shift += 8;
    } else {
      if (out) std::memcpy(out + 4 * x, pixel, 4);
      ++x;
      shift = 0;
    }
  }
}

void decode_scanline(const std::string& path, Cursor& in, int width, int scanline, std::uint8_t* out) {
  const bool rle_width = width >= kMinRleWidth && width <= kMaxRleWidth;
  // The new-style marker is 2 2 followed by the width with its top bit clear; anything else is a flat pixel.
  // A flat pixel (2, 2, <128, e) would be unnormalised (largest mantissa < 128), which no RGBE encoder writes, so
  // the marker is unambiguous (the same rule rgbe.c and Radiance apply).
  if (rle_width && in.remaining() >= 4 && in.data[in.pos] == 2 && in.data[in.pos + 1] == 2 &&
      (in.data[in.pos + 2] & 0x80) == 0) {
    const int encoded_width = (in.data[in.pos + 2] << 8) | in.data[in.pos + 3];
    if (encoded_width != width) {
      fail_scanline(path, scanline, "RLE scanline width " + std::to_string(encoded_width) + " does not match image width " +
                                        std::to_string(width));
    }
    in.pos += 4;
    decode_rle_scanline(path, in, width, scanline, out);
  } else {
    decode_flat_scanline(path, in, width, scanline, out);
  }
}

// Ward's rgbe2float (rgbe.c): e == 0 is exact zero; otherwise f = 2^(e - 128 - 8) and each channel is mantissa * f.
// Note: no +0.5 is added to the mantissa (Radiance's own colr_color adds 0.5; rgbe.c, stb_image and most
// texture tools do not). This is the convention SPECS.md uses for RGBE.
void decode_rgbe(const std::uint8_t* rgbe, float* rgb) {
  if (rgbe[3] == 0) {  // exponent byte 0 encodes black regardless of the mantissas
    rgb[0] = rgb[1] = rgb[2] = 0.0f;
    return;
  }
  const float f = std::ldexp(1.0f, static_cast<int>(rgbe[3]) - (128 + 8));
  rgb[0] = static_cast<float>(rgbe[0]) * f;
  rgb[1] = static_cast<float>(rgbe[1]) * f;
  rgb[2] = static_cast<float>(rgbe[2]) * f;
}

// Largest value RGBE can hold: mantissa 255 with exponent byte 255, i.e. 255 * 2^(255 - 136).
const float kMaxRgbeValue = std::ldexp(255.0f, 255 - 136);

// Ward's float2rgbe: v = max channel; v < 1e-32 -> (0,0,0,0); else m = frexp(v, &e), scale = m * 256 / v,
// each mantissa = (unsigned char)(channel * scale) (truncation), exponent byte = e + 128.
void encode_rgbe(const float* rgb, std::uint8_t* rgbe) {
  float channel[3];
  for (int c = 0; c < 3; ++c) {
    const float value = rgb[c];
    // RGBE has no sign and no NaN: negative and NaN become 0 (the input policy normally removed them already);
    // +Inf and anything above the largest encodable value saturate to it so the exponent byte cannot overflow.
    channel[c] = std::isnan(value) || value <= 0.0f ? 0.0f : std::min(value, kMaxRgbeValue);
  }
  const float v = std::max(channel[0], std::max(channel[1], channel[2]));
  if (v < 1e-32f) {  // Ward's threshold: too small to matter, stored as exact black
    rgbe[0] = rgbe[1] = rgbe[2] = rgbe[3] = 0;
    return;
  }
  int exponent = 0;
  const float scale = static_cast<float>(std::frexp(v, &exponent) * 256.0 / v);
  for (int c = 0; c < 3; ++c) {
    // channel * scale < 256 mathematically; float rounding could reach 256.0, which would wrap: clamp to 255.
    rgbe[c] = static_cast<std::uint8_t>(std::min(channel[c] * scale, 255.0f));
  }
  rgbe[3] = static_cast<std::uint8_t>(exponent + 128);
}

// New-style RLE encoding of one component plane (`stride`-spaced bytes): runs of >= 4 equal bytes become
// (128 + n, value) with n <= 127; everything else goes out as literal blocks (n, bytes...) with n <= 128.
void encode_rle_plane(const std::uint8_t* plane, int width, int stride, Bytes& out) {
  auto at = [&](int i) { return plane[static_cast<std::size_t>(i) * stride]; };
  constexpr int kMinRun = 4;  // shorter runs cost no less as literals
  int x = 0;
  while (x < width) {
    int run_start = x;
    int run_length = 0;
    while (run_start < width) {
      run_length = 1;
      while (run_start + run_length < width && run_length < 127 && at(run_start + run_length) == at(run_start)) {
        ++run_length;
      }
      if (run_length >= kMinRun) break;
      run_start += run_length;
    }
    while (x < run_start) {  // literals before the run (or up to the end of the line)
      const int count = std::min(128, run_start - x);
      out.push_back(static_cast<std::uint8_t>(count));
      for (int i = 0; i < count; ++i) out.push_back(at(x + i));
      x += count;
    }
    if (run_start < width) {
      out.push_back(static_cast<std::uint8_t>(128 + run_length));
      out.push_back(at(run_start));
      x = run_start + run_length;
    }
  }
}

struct Header {
  int width = 0;
  int height = 0;
  bool bottom_to_top = false;  // "+Y": first scanline is the bottom row
  bool right_to_left = false;  // "-X": first pixel is the rightmost
};

bool line_starts_with(const std::string& line, const char* prefix) {
  return line.compare(0, std::strlen(prefix), prefix) == 0;
}

// Reads one '\n'-terminated line starting at in.pos (without the '\n'); a missing '\n' is a truncated header.
std::string read_header_line(const std::string& path, Cursor& in) {
  const std::size_t limit = std::min(in.size, kMaxHeaderBytes);
  std::size_t end = in.pos;
  while (end < limit && in.data[end] != '\n') ++end;
  if (end >= limit) {
    fail(path, in.size > kMaxHeaderBytes ? "Radiance header longer than 64 KiB" : "truncated Radiance header");
  }
  std::string line(reinterpret_cast<const char*>(in.data + in.pos), end - in.pos);
  in.pos = end + 1;
  if (!line.empty() && line.back() == '\r') line.pop_back();  // tolerate CRLF-edited headers
  return line;
}

int parse_resolution_number(const std::string& path, const std::string& token, const std::string& line) {
  if (token.empty() || token.size() > 9 || token.find_first_not_of("0123456789") != std::string::npos) {
    fail(path, "invalid Radiance resolution line \"" + line + "\"");
  }
  return std::stoi(token);
}

Header parse_header(const std::string& path, Cursor& in) {
  Header header;
  // Information lines up to the empty line. The "#?" program line is normally first but some writers put other
  // lines first (memorial.hdr starts with VIEW=), so it is not required to be.
  for (;;) {
    const std::string line = read_header_line(path, in);
    if (line.empty()) break;
    if (line_starts_with(line, "FORMAT=")) {
      std::string format = line.substr(7);
      format.erase(0, format.find_first_not_of(" \t"));
      format.erase(format.find_last_not_of(" \t") + 1);
      if (format == "32-bit_rle_xyze") {
        fail(path, "Radiance XYZE files (FORMAT=32-bit_rle_xyze) are not supported; convert to RGBE");
      }
      if (format != "32-bit_rle_rgbe") fail(path, "unsupported Radiance FORMAT \"" + format + "\" (expected 32-bit_rle_rgbe)");
    }
    // EXPOSURE=, PRIMARIES=, VIEW=, comments and command lines are informational: pixel values are returned as
    // stored, like rgbe.c and stb_image (no exposure division, no primaries conversion).
  }
  // A missing FORMAT line means the default, RGBE (Radiance's convention): accepted.

  const std::string line = read_header_line(path, in);
  char tokens[4][16] = {};
  int consumed = 0;
  if (line.size() > 60 ||
      std::sscanf(line.c_str(), "%15s %15s %15s %15s%n", tokens[0], tokens[1], tokens[2], tokens[3], &consumed) != 4 ||
      static_cast<std::size_t>(consumed) != line.size()) {
    fail(path, "invalid Radiance resolution line \"" + line.substr(0, 60) + "\"");
  }
  const std::string first(tokens[0]);
  const std::string second(tokens[2]);
  if ((first == "-Y" || first == "+Y") && (second == "+X" || second == "-X")) {
    header.height = parse_resolution_number(path, tokens[1], line);
    header.width = parse_resolution_number(path, tokens[3], line);
    header.bottom_to_top = first == "+Y";
    header.right_to_left = second == "-X";
  } else if ((first == "+X" || first == "-X") && (second == "+Y" || second == "-Y")) {
    fail(path, "unsupported Radiance orientation \"" + line + "\" (column-major images are not supported; expected -Y H +X W)");
  } else {
    fail(path, "invalid Radiance resolution line \"" + line + "\"");
  }
  check_image_size(path, header.width, header.height);
  return header;
}

}  // namespace

Image read_radiance_hdr(const std::string& path, const Bytes& bytes) {
  Cursor in{bytes.data(), bytes.size(), 0};
  const Header header = parse_header(path, in);
  const std::size_t pixels_start = in.pos;

  // Pass 1: walk the whole pixel stream without storing anything.
  for (int scanline = 0; scanline < header.height; ++scanline) decode_scanline(path, in, header.width, scanline, nullptr);

  // Pass 2: the stream is known to be complete, so allocating is safe. Decode one scanline at a time.
  Image image(header.width, header.height, 3);
  Bytes rgbe_line(static_cast<std::size_t>(header.width) * 4);
  in.pos = pixels_start;
  for (int scanline = 0; scanline < header.height; ++scanline) {
    decode_scanline(path, in, header.width, scanline, rgbe_line.data());
    const int y = header.bottom_to_top ? header.height - 1 - scanline : scanline;
    for (int i = 0; i < header.width; ++i) {
      const int x = header.right_to_left ? header.width - 1 - i : i;
      decode_rgbe(&rgbe_line[static_cast<std::size_t>(i) * 4], image.texel(x, y));
    }
  }
  image.metadata.container = "hdr";
  image.metadata.pixel_type = "rgbe";
  image.metadata.is_hdr = true;
  return image;
}

void write_radiance_hdr(const std::string& path, const Image& image) {
  const std::string header = "#?RADIANCE\n# Written by blocklab\nFORMAT=32-bit_rle_rgbe\n\n-Y " +
                             std::to_string(image.height) + " +X " + std::to_string(image.width) + "\n";
  Bytes bytes(header.begin(), header.end());
  Bytes rgbe_line(static_cast<std::size_t>(image.width) * 4);
  const bool use_rle = image.width >= kMinRleWidth && image.width <= kMaxRleWidth;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) encode_rgbe(image.texel(x, y), &rgbe_line[static_cast<std::size_t>(x) * 4]);
    if (!use_rle) {  // widths RLE cannot describe are written flat, as rgbe.c does
      bytes.insert(bytes.end(), rgbe_line.begin(), rgbe_line.end());
      continue;
    }
    bytes.push_back(2);
    bytes.push_back(2);
    bytes.push_back(static_cast<std::uint8_t>(image.width >> 8));
    bytes.push_back(static_cast<std::uint8_t>(image.width & 0xff));
    for (int component = 0; component < 4; ++component) encode_rle_plane(&rgbe_line[component], image.width, 4, bytes);
  }
  write_file_atomically(path, bytes);
}

bool has_radiance_signature(const Bytes& bytes) {
  // Walk the leading text lines (up to the blank line that ends a Radiance header): a "#?" program line or a
  // FORMAT=32-bit_rle_ line identifies the file even when it is not the first line.
  std::size_t pos = 0;
  const std::size_t limit = std::min(bytes.size(), kMaxHeaderBytes);
  while (pos < limit) {
    std::size_t end = pos;
    while (end < limit && bytes[end] != '\n') {
      if (bytes[end] == 0) return false;  // binary data: not a text header
      ++end;
    }
    const std::string line(reinterpret_cast<const char*>(bytes.data() + pos), end - pos);
    if (line.empty() || line == "\r") return false;
    if (line_starts_with(line, "#?") || line_starts_with(line, "FORMAT=32-bit_rle_")) return true;
    pos = end + 1;
  }
  return false;
}

}  // namespace blocklab::image_io_detail
