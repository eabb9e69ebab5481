// DDS reader and writer (formats/common/dds.h). Field offsets (bytes from the start of the file):
//   0 magic "DDS " | 4 size (124) | 8 flags | 12 height | 16 width | 20 pitchOrLinearSize | 24 depth |
//   28 mipMapCount | 32..75 reserved1[11] | 76 pixel format: 76 size (32), 80 flags, 84 fourCC, 88 RGBBitCount,
//   92..107 masks | 108 caps | 112 caps2 | 116 caps3 | 120 caps4 | 124 reserved2 | 128 data or DX10 header:
//   128 dxgiFormat | 132 resourceDimension | 136 miscFlag | 140 arraySize | 144 miscFlags2 | 148 data.
#include "formats/common/dds.h"

#include <fstream>
#include <iterator>

#include "core/atomic_write.h"
#include "core/blocks.h"
#include "core/error.h"
#include "formats/registry.h"

namespace blocklab {

namespace {

constexpr std::uint32_t kHeaderSize = 124;
constexpr std::uint32_t kPixelFormatSize = 32;
constexpr std::size_t kLegacyDataOffset = 4 + kHeaderSize;          // 128
constexpr std::size_t kDx10DataOffset = kLegacyDataOffset + 20;     // 148

constexpr std::uint32_t kFlagCaps = 0x1, kFlagHeight = 0x2, kFlagWidth = 0x4, kFlagPitch = 0x8,
                        kFlagPixelFormat = 0x1000, kFlagMipMapCount = 0x20000, kFlagLinearSize = 0x80000,
                        kFlagDepth = 0x800000;
constexpr std::uint32_t kPixelFormatFourCC = 0x4;
constexpr std::uint32_t kCapsTexture = 0x1000;
constexpr std::uint32_t kCaps2CubeMap = 0x200, kCaps2Volume = 0x200000;
constexpr std::uint32_t kDimensionTexture2D = 3;
constexpr std::uint32_t kMiscTextureCube = 0x4;
constexpr std::uint32_t kAlphaModeStraight = 1, kAlphaModeOpaque = 3;

constexpr std::uint32_t four_cc(const char (&text)[5]) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(text[0])) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(text[1])) << 8) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(text[2])) << 16) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(text[3])) << 24);
}

struct FormatInfo {
  const char* name;
  int block_bytes;
  int channels;
  std::uint32_t legacy_four_cc;   // 0: written with the DX10 header
  std::uint32_t dxgi_format;
};

constexpr FormatInfo kFormats[] = {
    {"bc1", 8, 3, four_cc("DXT1"), 71},
    {"bc3", 16, 4, four_cc("DXT5"), 77},
    {"bc4", 8, 1, four_cc("ATI1"), 80},
    {"bc7", 16, 4, 0, 98},
    {"bc6h", 16, 3, 0, 95},      // BC6H_UF16
    {"bc6h_sf", 16, 3, 0, 96},   // BC6H_SF16
};

const FormatInfo* info_by_name(const std::string& name) {
  for (const FormatInfo& info : kFormats)
    if (name == info.name) return &info;
  return nullptr;
}

std::string four_cc_text(std::uint32_t code) {
  std::string text;
  for (int i = 0; i < 4; ++i) {
    const char c = static_cast<char>((code >> (8 * i)) & 0xFFu);
    text += (c >= 32 && c < 127) ? std::string(1, c) : "\\x" + std::to_string(static_cast<unsigned char>(c));
  }
  return text;
}

void put_u32(std::vector<std::uint8_t>& bytes, std::size_t offset, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes[offset + i] = static_cast<std::uint8_t>((value >> (8 * i)) & 0xFFu);
}

std::uint32_t get_u32(const std::vector<std::uint8_t>& bytes, std::size_t offset) {
  return static_cast<std::uint32_t>(bytes[offset]) | (static_cast<std::uint32_t>(bytes[offset + 1]) << 8) |
         (static_cast<std::uint32_t>(bytes[offset + 2]) << 16) | (static_cast<std::uint32_t>(bytes[offset + 3]) << 24);
}

std::size_t level0_bytes(std::uint32_t width, std::uint32_t height, int block_bytes) {
  // max(1, (n + 3) / 4) blocks per side; width, height >= 1 here, so (n + 3) / 4 >= 1 already.
  return static_cast<std::size_t>((width + 3) / 4) * ((height + 3) / 4) * static_cast<std::size_t>(block_bytes);
}

}  // namespace

std::vector<std::uint8_t> dds_bytes(const EncodedTexture& texture, const std::string& where) {
  const FormatInfo* info = info_by_name(texture.format);
  if (info == nullptr)
    fail(where, "DDS output supports the formats bc1, bc3, bc4, bc7, bc6h, bc6h_sf, not '" + texture.format + "'");
  if (texture.width < 1 || texture.height < 1 || texture.width > kMaxTextureDimension ||
      texture.height > kMaxTextureDimension)
    fail(where, "texture size " + std::to_string(texture.width) + "x" + std::to_string(texture.height) +
                    " is outside 1.." + std::to_string(kMaxTextureDimension));
  if (texture.block_bytes != info->block_bytes)
    fail(where, texture.format + " blocks are " + std::to_string(info->block_bytes) + " bytes, the texture says " +
                    std::to_string(texture.block_bytes));
  const std::size_t data_size = level0_bytes(static_cast<std::uint32_t>(texture.width),
                                             static_cast<std::uint32_t>(texture.height), info->block_bytes);
  if (texture.blocks.size() != data_size)
    fail(where, "texture holds " + std::to_string(texture.blocks.size()) + " bytes of blocks, a " +
                    std::to_string(texture.width) + "x" + std::to_string(texture.height) + " " + texture.format +
                    " texture needs " + std::to_string(data_size));
  const bool dx10 = info->legacy_four_cc == 0;
  const std::size_t data_offset = dx10 ? kDx10DataOffset : kLegacyDataOffset;
  std::vector<std::uint8_t> bytes(data_offset + data_size, 0);
  put_u32(bytes, 0, four_cc("DDS "));
  put_u32(bytes, 4, kHeaderSize);
  put_u32(bytes, 8, kFlagCaps | kFlagHeight | kFlagWidth | kFlagPixelFormat | kFlagLinearSize);
  put_u32(bytes, 12, static_cast<std::uint32_t>(texture.height));
  put_u32(bytes, 16, static_cast<std::uint32_t>(texture.width));
  put_u32(bytes, 20, static_cast<std::uint32_t>(data_size));   // pitchOrLinearSize of the top level
  put_u32(bytes, 76, kPixelFormatSize);
  put_u32(bytes, 80, kPixelFormatFourCC);
  put_u32(bytes, 84, dx10 ? four_cc("DX10") : info->legacy_four_cc);
  put_u32(bytes, 108, kCapsTexture);
  if (dx10) {
    put_u32(bytes, 128, info->dxgi_format);
    put_u32(bytes, 132, kDimensionTexture2D);
    put_u32(bytes, 136, 0);   // miscFlag: not a cube map
    put_u32(bytes, 140, 1);   // arraySize
    put_u32(bytes, 144, texture.channels == 4 && info->channels == 4 ? kAlphaModeStraight : kAlphaModeOpaque);
  }
  std::copy(texture.blocks.begin(), texture.blocks.end(), bytes.begin() + static_cast<std::ptrdiff_t>(data_offset));
  return bytes;
}

EncodedTexture parse_dds(const std::vector<std::uint8_t>& bytes, const std::string& where) {
  // Each read below is preceded by a length check, so no truncation can read past the buffer.
  if (bytes.size() < kLegacyDataOffset)
    fail(where, "file is " + std::to_string(bytes.size()) + " bytes, shorter than the 128-byte DDS header");
  if (get_u32(bytes, 0) != four_cc("DDS "))
    fail(where, "not a DDS file (magic is '" + four_cc_text(get_u32(bytes, 0)) + "', expected 'DDS ')");
  if (get_u32(bytes, 4) != kHeaderSize)
    fail(where, "DDS header size is " + std::to_string(get_u32(bytes, 4)) + ", expected 124");
  const std::uint32_t flags = get_u32(bytes, 8);
  if ((flags & (kFlagHeight | kFlagWidth)) != (kFlagHeight | kFlagWidth))
    fail(where, "DDS header flags " + std::to_string(flags) + " lack DDSD_HEIGHT | DDSD_WIDTH");
  if ((flags & kFlagDepth) != 0) fail(where, "volume textures (DDSD_DEPTH) are not supported");
  if ((flags & kFlagPitch) != 0 && (flags & kFlagLinearSize) != 0)
    fail(where, "DDS header sets both DDSD_PITCH and DDSD_LINEARSIZE");
  const std::uint32_t height = get_u32(bytes, 12), width = get_u32(bytes, 16);
  if (width < 1 || height < 1 || width > static_cast<std::uint32_t>(kMaxTextureDimension) ||
      height > static_cast<std::uint32_t>(kMaxTextureDimension))
    fail(where, "texture size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1.." +
                    std::to_string(kMaxTextureDimension));
  const std::uint32_t depth = get_u32(bytes, 24);
  if (depth > 1) fail(where, "depth " + std::to_string(depth) + ": volume textures are not supported");
  if (get_u32(bytes, 76) != kPixelFormatSize)
    fail(where, "DDS pixel format size is " + std::to_string(get_u32(bytes, 76)) + ", expected 32");
  if ((get_u32(bytes, 80) & kPixelFormatFourCC) == 0)
    fail(where, "pixel format is not a FourCC (block-compressed) format; only BC1, BC3, BC4, BC6H and BC7 are read");
  const std::uint32_t caps2 = get_u32(bytes, 112);
  if ((caps2 & kCaps2CubeMap) != 0) fail(where, "cube maps are not supported");
  if ((caps2 & kCaps2Volume) != 0) fail(where, "volume textures are not supported");

  const std::uint32_t code = get_u32(bytes, 84);
  const FormatInfo* info = nullptr;
  std::size_t data_offset = kLegacyDataOffset;
  int channels = 0;
  if (code == four_cc("DX10")) {
    if (bytes.size() < kDx10DataOffset)
      fail(where, "file is " + std::to_string(bytes.size()) + " bytes, shorter than the 148-byte DX10 header");
    const std::uint32_t dxgi_format = get_u32(bytes, 128);
    for (const FormatInfo& candidate : kFormats)
      if (candidate.dxgi_format == dxgi_format) info = &candidate;
    if (info == nullptr)
      fail(where, "DX10 dxgiFormat " + std::to_string(dxgi_format) +
                      " is not supported (supported: 71 BC1_UNORM, 77 BC3_UNORM, 80 BC4_UNORM, 95 BC6H_UF16, 96 BC6H_SF16, "
                      "98 BC7_UNORM)");
    if (get_u32(bytes, 132) != kDimensionTexture2D)
      fail(where, "DX10 resourceDimension " + std::to_string(get_u32(bytes, 132)) + " is not 3 (TEXTURE2D)");
    if ((get_u32(bytes, 136) & kMiscTextureCube) != 0) fail(where, "cube maps are not supported");
    if (get_u32(bytes, 140) != 1)
      fail(where, "DX10 arraySize " + std::to_string(get_u32(bytes, 140)) + ": texture arrays are not supported");
    const std::uint32_t alpha_mode = get_u32(bytes, 144) & 7u;   // miscFlags2 low 3 bits: DDS_ALPHA_MODE
    if (alpha_mode > 4) fail(where, "DX10 alpha mode " + std::to_string(alpha_mode) + " is not 0..4");
    data_offset = kDx10DataOffset;
    // An opaque alpha mode on a format with alpha means the source had none.
    channels = (alpha_mode == kAlphaModeOpaque && info->channels == 4) ? 3 : info->channels;
  } else {
    if (code == four_cc("BC4U")) info = info_by_name("bc4");
    for (const FormatInfo& candidate : kFormats)
      if (candidate.legacy_four_cc != 0 && candidate.legacy_four_cc == code) info = &candidate;
    if (info == nullptr)
      fail(where, "FourCC '" + four_cc_text(code) + "' is not supported (supported: DXT1, DXT5, ATI1, BC4U, DX10)");
    channels = info->channels;
  }
  const std::size_t data_size = level0_bytes(width, height, info->block_bytes);
  // pitchOrLinearSize is only meaningful with DDSD_LINEARSIZE; then it must be the size of the top level.
  if ((flags & kFlagLinearSize) != 0 && get_u32(bytes, 20) != data_size)
    fail(where, "pitchOrLinearSize is " + std::to_string(get_u32(bytes, 20)) + ", a " + std::to_string(width) + "x" +
                    std::to_string(height) + " " + info->name + " level needs " + std::to_string(data_size));
  if (bytes.size() - data_offset < data_size)
    fail(where, "file is truncated: the " + std::to_string(width) + "x" + std::to_string(height) + " " + info->name +
                    " level needs " + std::to_string(data_size) + " bytes of blocks, the file has " +
                    std::to_string(bytes.size() - data_offset));

  EncodedTexture texture;
  texture.format = info->name;
  texture.width = static_cast<int>(width);
  texture.height = static_cast<int>(height);
  texture.channels = channels;
  texture.block_bytes = info->block_bytes;
  texture.blocks.assign(bytes.begin() + static_cast<std::ptrdiff_t>(data_offset),
                        bytes.begin() + static_cast<std::ptrdiff_t>(data_offset + data_size));
  // DDS records no encoder options; give the registered format's defaults so the texture validates and decodes.
  for (const Format* format : all_formats())
    if (format->name() == texture.format) texture.options = resolve_format_options(*format, {});
  return texture;
}

void write_dds(const std::string& path, const EncodedTexture& texture) {
  const std::vector<std::uint8_t> bytes = dds_bytes(texture, path);
  write_file_atomically(path, bytes);
}

EncodedTexture read_dds(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) fail(path, "cannot open for reading");
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (file.bad()) fail(path, "read failed");
  return parse_dds(bytes, path);
}

}  // namespace blocklab
