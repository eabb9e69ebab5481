// DDS reader and writer (formats/common/dds.h): round trips for bc1/bc3/bc4/bc7 with true sizes, the header fields
// ECOSYSTEM.md section 2 prescribes, NVTT-style files with mip levels, and an Error (never a crash) for every
// truncation and for corrupt fields.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "core/error.h"
#include "formats/common/dds.h"
#include "formats/registry.h"
#include "test_s3tc_helpers.h"

namespace blocklab {
namespace {

std::uint32_t u32_at(const std::vector<std::uint8_t>& bytes, std::size_t offset) {
  return bytes[offset] | (bytes[offset + 1] << 8) | (bytes[offset + 2] << 16) | (static_cast<std::uint32_t>(bytes[offset + 3]) << 24);
}
void set_u32(std::vector<std::uint8_t>& bytes, std::size_t offset, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes[offset + i] = static_cast<std::uint8_t>(value >> (8 * i));
}

EncodedTexture texture_of(const std::string& format, int width, int height, int channels, std::uint64_t seed) {
  EncodedTexture texture;
  texture.format = format;
  texture.width = width;
  texture.height = height;
  texture.channels = channels;
  texture.block_bytes = (format == "bc1" || format == "bc4") ? 8 : 16;
  texture.blocks = s3tc_test::random_blocks(static_cast<std::size_t>((width + 3) / 4) * ((height + 3) / 4),
                                            texture.block_bytes, seed);
  return texture;
}

TEST(Dds, RoundTripsEveryFormatWithTrueSizes) {
  const struct { const char* format; int channels; const char* four_cc; } cases[] = {
      {"bc1", 3, "DXT1"}, {"bc3", 4, "DXT5"}, {"bc4", 1, "ATI1"}, {"bc7", 4, "DX10"}};
  for (const auto& c : cases) {
    for (const auto& size : {std::pair<int, int>{1, 1}, {5, 3}, {64, 8}, {767, 1023}}) {
      const EncodedTexture texture = texture_of(c.format, size.first, size.second, c.channels, 41);
      const std::vector<std::uint8_t> bytes = dds_bytes(texture, "memory");
      EXPECT_EQ(std::string(bytes.begin() + 84, bytes.begin() + 88), c.four_cc);
      EXPECT_EQ(u32_at(bytes, 8), 0x81007u);   // CAPS | HEIGHT | WIDTH | PIXELFORMAT | LINEARSIZE
      EXPECT_EQ(u32_at(bytes, 12), static_cast<std::uint32_t>(size.second));
      EXPECT_EQ(u32_at(bytes, 16), static_cast<std::uint32_t>(size.first));
      EXPECT_EQ(u32_at(bytes, 20), texture.blocks.size());   // pitchOrLinearSize
      EXPECT_EQ(u32_at(bytes, 108), 0x1000u);
      const EncodedTexture read = parse_dds(bytes, "memory");
      EXPECT_EQ(read.format, c.format);
      EXPECT_EQ(read.width, size.first);
      EXPECT_EQ(read.height, size.second);
      EXPECT_EQ(read.channels, c.channels);
      EXPECT_EQ(read.blocks, texture.blocks);
    }
  }
}

TEST(Dds, Bc7OpaqueSourceIsRecordedAsOpaqueAlphaMode) {
  const std::vector<std::uint8_t> bytes = dds_bytes(texture_of("bc7", 8, 8, 3, 42), "memory");
  EXPECT_EQ(u32_at(bytes, 128), 98u);
  EXPECT_EQ(u32_at(bytes, 144), 3u);
  EXPECT_EQ(parse_dds(bytes, "memory").channels, 3);
}

TEST(Dds, FilesOnDiskRoundTripAndDecode) {
  const std::string path = (std::filesystem::temp_directory_path() / ("blocklab_test_dds_" + std::to_string(::getpid()) + ".dds")).string();
  Image image(13, 7);
  for (std::size_t i = 0; i < image.texel_count(); ++i) image.pixels[i * 4 + 1] = (i % 17) / 16.0f;
  const Format& bc1 = find_format("bc1");
  const EncodedTexture texture = bc1.encode(image, resolve_format_options(bc1, {}), CodecContext{1, 1});
  write_dds(path, texture);
  const EncodedTexture read = read_dds(path);
  std::filesystem::remove(path);
  EXPECT_EQ(read.blocks, texture.blocks);
  const Image a = bc1.decode(texture, CodecContext{1, 1}), b = bc1.decode(read, CodecContext{1, 1});
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_THROW(read_dds(path), Error);   // missing file
}

TEST(Dds, ReadsLegacyVariantsWithMipLevelsAndBc4uAndDx10Codes) {
  EncodedTexture texture = texture_of("bc1", 8, 8, 3, 43);
  std::vector<std::uint8_t> bytes = dds_bytes(texture, "memory");
  // Mip levels after the top level (4x4 and 2x2 and 1x1: 3 more blocks), as nvcompress writes without -nomips.
  set_u32(bytes, 28, 4);
  set_u32(bytes, 8, u32_at(bytes, 8) | 0x20000u);
  bytes.resize(bytes.size() + 3 * 8, 0xAB);
  EXPECT_EQ(parse_dds(bytes, "memory").blocks, texture.blocks);
  // pitchOrLinearSize 0 without the LINEARSIZE flag is accepted (some writers leave it).
  set_u32(bytes, 8, 0x1007u);
  set_u32(bytes, 20, 0);
  EXPECT_NO_THROW(parse_dds(bytes, "memory"));
  // BC4U FourCC -> bc4.
  std::vector<std::uint8_t> bc4 = dds_bytes(texture_of("bc4", 4, 4, 1, 44), "memory");
  bc4[84] = 'B', bc4[85] = 'C', bc4[86] = '4', bc4[87] = 'U';
  EXPECT_EQ(parse_dds(bc4, "memory").format, "bc4");
}

TEST(Dds, EveryTruncationOfARealFileIsAnError) {
  for (const char* format : {"bc1", "bc7"}) {
    const std::vector<std::uint8_t> bytes = dds_bytes(texture_of(format, 9, 6, 4, 45), "memory");
    for (std::size_t length = 0; length < bytes.size(); ++length) {
      const std::vector<std::uint8_t> truncated(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(length));
      EXPECT_THROW(parse_dds(truncated, "cut.dds"), Error) << format << " length " << length;
    }
  }
}

TEST(Dds, CorruptFieldsAreErrorsNamingTheFileAndReason) {
  const std::vector<std::uint8_t> good = dds_bytes(texture_of("bc3", 8, 8, 4, 46), "memory");
  const struct { std::size_t offset; std::uint32_t value; const char* reason; } cases[] = {
      {0, 0x20534444u + 1, "magic"},      {4, 120, "header size"},     {8, 0x1001u, "DDSD_HEIGHT"},
      {12, 0, "outside"},                 {16, 70000, "outside"},      {20, 17, "pitchOrLinearSize"},
      {24, 4, "volume"},                  {76, 24, "pixel format size"}, {80, 0x40, "FourCC"},
      {84, 0x33545844u, "not supported"}, {112, 0x200, "cube"},
  };
  for (const auto& c : cases) {
    std::vector<std::uint8_t> bytes = good;
    set_u32(bytes, c.offset, c.value);
    try {
      parse_dds(bytes, "bad.dds");
      FAIL() << "accepted corrupt field at " << c.offset;
    } catch (const Error& error) {
      const std::string message = error.what();
      EXPECT_EQ(message.rfind("bad.dds: ", 0), 0u) << message;
      EXPECT_NE(message.find(c.reason), std::string::npos) << message;
    }
  }
  std::vector<std::uint8_t> dx10 = dds_bytes(texture_of("bc7", 8, 8, 4, 47), "memory");
  for (const auto& field : {std::pair<std::size_t, std::uint32_t>{128, 94}, {132, 2}, {136, 4}, {140, 6}, {144, 7}}) {
    std::vector<std::uint8_t> bytes = dx10;
    set_u32(bytes, field.first, field.second);
    EXPECT_THROW(parse_dds(bytes, "bad.dds"), Error) << field.first;
  }
}

TEST(Dds, WriterRejectsUnsupportedOrInconsistentTextures) {
  EncodedTexture texture = texture_of("bc1", 8, 8, 3, 48);
  texture.format = "fp16";
  EXPECT_THROW(dds_bytes(texture, "out.dds"), Error);
  texture = texture_of("bc1", 8, 8, 3, 48);
  texture.blocks.pop_back();
  EXPECT_THROW(dds_bytes(texture, "out.dds"), Error);
  texture = texture_of("bc1", 8, 8, 3, 48);
  texture.block_bytes = 16;
  EXPECT_THROW(dds_bytes(texture, "out.dds"), Error);
}

}  // namespace
}  // namespace blocklab
