// Hand-built files exercising each reader's format rules and its error messages: dispatch by magic bytes,
// Radiance header/orientation/scanline encodings and Ward's RGBE decoding, PFM byte order / grey / row order,
// PNG palette / tRNS / low bit depth / grey+alpha / CRC damage, and writer argument checks.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image_io.h"
#include "test_image_io_common.h"

namespace blocklab {
namespace {

using test_io::Bytes;
using test_io::TempDir;

// Runs `action`, expects blocklab::Error, and returns its message ("" and a test failure otherwise).
template <typename Action>
std::string error_message(Action action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw a non-blocklab exception: " << e.what();
    return "";
  }
  ADD_FAILURE() << "did not throw";
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

Bytes text_bytes(const std::string& text) { return Bytes(text.begin(), text.end()); }
void append(Bytes& bytes, std::initializer_list<int> values) {
  for (int v : values) bytes.push_back(static_cast<std::uint8_t>(v));
}

// ---------------------------------------------------------------------------------------------------------------
// Dispatch and generic failures

TEST(ReadImage, MissingFileNamesThePath) {
  TempDir dir("io_missing");
  const std::string path = dir.file("does_not_exist.exr");
  const std::string message = error_message([&] { read_image(path); });
  EXPECT_TRUE(contains(message, path)) << message;
  EXPECT_TRUE(contains(message, "cannot open")) << message;
}

TEST(ReadImage, DirectoryAndEmptyFileAreErrors) {
  TempDir dir("io_dir");
  test_io::write_text(dir.file("empty.png"), "");
  EXPECT_TRUE(contains(error_message([&] { read_image(dir.file("")); }), "directory"));
  EXPECT_TRUE(contains(error_message([&] { read_image(dir.file("empty.png")); }), "empty file"));
}

TEST(ReadImage, UnknownMagicIsUnsupportedFileTypeRegardlessOfExtension) {
  TempDir dir("io_magic");
  const std::string path = dir.file("looks_like.exr");
  test_io::write_text(path, "GIF89a not an image blocklab reads");
  const std::string message = error_message([&] { read_image(path); });
  EXPECT_EQ(message.rfind(path + ": unsupported file type (", 0), 0u) << message;
}

TEST(ReadImage, DispatchIgnoresTheExtension) {
  TempDir dir("io_dispatch");
  const std::string pfm_named_png = dir.file("really_a_pfm.png");
  Bytes bytes = text_bytes("Pf\n1 1\n-1\n");
  const float value = 0.375f;
  append(bytes, {0, 0, 0, 0});
  std::memcpy(&bytes[bytes.size() - 4], &value, 4);
  test_io::write_bytes(pfm_named_png, bytes);
  const Image image = read_image(pfm_named_png);
  EXPECT_EQ(image.metadata.container, "pfm");
  EXPECT_EQ(image.texel(0, 0)[0], 0.375f);
}

TEST(WriteImage, UnknownExtensionListsTheSupportedOnes) {
  TempDir dir("io_write_ext");
  const std::string message = error_message([&] { write_image(dir.file("out.tiff"), Image(2, 2)); });
  EXPECT_TRUE(contains(message, ".exr .hdr .pfm .png")) << message;
  EXPECT_TRUE(contains(message, "out.tiff")) << message;
  EXPECT_TRUE(contains(error_message([&] { write_image(dir.file("no_extension"), Image(2, 2)); }), ".exr"));
}

TEST(WriteImage, InvalidImagesAndOptionsAreRejected) {
  TempDir dir("io_write_bad");
  Image broken(2, 2);
  broken.pixels.pop_back();
  EXPECT_TRUE(contains(error_message([&] { write_image(dir.file("a.exr"), broken); }), "floats"));
  EXPECT_TRUE(contains(error_message([&] { write_image(dir.file("a.png"), Image()); }), "empty image"));
  Image two_channels(2, 2);
  two_channels.channels = 2;
  EXPECT_TRUE(contains(error_message([&] { write_image(dir.file("a.pfm"), two_channels); }), "channels"));
  EXPECT_TRUE(contains(error_message([&] { write_image(dir.file("a.png"), Image(2, 2), WriteOptions{ExrPixelType::half, 12}); }),
                       "png_bits"));
  EXPECT_TRUE(contains(error_message([&] { write_image(dir.file("no_such_dir/a.exr"), Image(2, 2)); }), "no_such_dir"));
  EXPECT_TRUE(contains(error_message([&] { write_image(dir.file("no_such_dir/a.png"), Image(2, 2)); }), "no_such_dir"));
}

// ---------------------------------------------------------------------------------------------------------------
// Radiance .hdr

Bytes radiance(const std::string& header_lines, const std::string& resolution, const Bytes& pixels) {
  Bytes bytes = text_bytes(header_lines + "\n" + resolution + "\n");
  bytes.insert(bytes.end(), pixels.begin(), pixels.end());
  return bytes;
}

Image read_bytes_as(const TempDir& dir, const std::string& name, const Bytes& bytes) {
  test_io::write_bytes(dir.file(name), bytes);
  return read_image(dir.file(name));
}

TEST(RadianceReader, DecodesWithWardsConventionMantissaTimesTwoToEMinus136) {
  TempDir dir("io_hdr_ward");
  Bytes pixels;
  append(pixels, {128, 64, 255, 129});  // 2^(129-136) = 1/128: (1, 0.5, 255/128)
  append(pixels, {200, 100, 7, 0});     // exponent 0 is black whatever the mantissas
  append(pixels, {1, 2, 3, 136});       // no +0.5: exactly (1, 2, 3)
  const Image image = read_bytes_as(dir, "ward.hdr", radiance("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", "-Y 1 +X 3", pixels));
  EXPECT_EQ(image.channels, 3);
  EXPECT_EQ(image.texel(0, 0)[0], 1.0f);
  EXPECT_EQ(image.texel(0, 0)[1], 0.5f);
  EXPECT_EQ(image.texel(0, 0)[2], 255.0f / 128.0f);
  EXPECT_EQ(image.texel(1, 0)[0], 0.0f);
  EXPECT_EQ(image.texel(1, 0)[2], 0.0f);
  EXPECT_EQ(image.texel(2, 0)[0], 1.0f);
  EXPECT_EQ(image.texel(2, 0)[1], 2.0f);
  EXPECT_EQ(image.texel(2, 0)[2], 3.0f);
  EXPECT_EQ(image.texel(2, 0)[3], 1.0f);
}

// One texel per scanline position: value = 128 * 2^(e-136) with e = 129 + index, so the decoded red is 2^index.
Bytes indexed_pixels(int count) {
  Bytes pixels;
  for (int i = 0; i < count; ++i) append(pixels, {128, 0, 0, 129 + i});
  return pixels;
}

TEST(RadianceReader, AcceptsBottomUpAndRightToLeftOrientations) {
  TempDir dir("io_hdr_orient");
  // Stream order: p0 p1 (first scanline) p2 p3 (second scanline); red of p_i = 2^i.
  const Bytes pixels = indexed_pixels(4);
  const Image standard = read_bytes_as(dir, "a.hdr", radiance("#?RADIANCE\n", "-Y 2 +X 2", pixels));
  EXPECT_EQ(standard.texel(0, 0)[0], 1.0f);
  EXPECT_EQ(standard.texel(1, 0)[0], 2.0f);
  EXPECT_EQ(standard.texel(0, 1)[0], 4.0f);
  const Image bottom_up = read_bytes_as(dir, "b.hdr", radiance("#?RADIANCE\n", "+Y 2 +X 2", pixels));
  EXPECT_EQ(bottom_up.texel(0, 1)[0], 1.0f);
  EXPECT_EQ(bottom_up.texel(1, 1)[0], 2.0f);
  EXPECT_EQ(bottom_up.texel(0, 0)[0], 4.0f);
  const Image mirrored = read_bytes_as(dir, "c.hdr", radiance("#?RADIANCE\n", "-Y 2 -X 2", pixels));
  EXPECT_EQ(mirrored.texel(1, 0)[0], 1.0f);
  EXPECT_EQ(mirrored.texel(0, 0)[0], 2.0f);
}

TEST(RadianceReader, RejectsTransposedOrientationAndBadResolutionLines) {
  TempDir dir("io_hdr_badres");
  const Bytes pixels = indexed_pixels(4);
  EXPECT_TRUE(contains(error_message([&] { read_bytes_as(dir, "a.hdr", radiance("#?RADIANCE\n", "+X 2 -Y 2", pixels)); }),
                       "orientation"));
  EXPECT_TRUE(contains(error_message([&] { read_bytes_as(dir, "b.hdr", radiance("#?RADIANCE\n", "-Y two +X 2", pixels)); }),
                       "resolution"));
  EXPECT_TRUE(contains(error_message([&] { read_bytes_as(dir, "c.hdr", radiance("#?RADIANCE\n", "-Y 0 +X 2", pixels)); }),
                       "invalid image size"));
  EXPECT_TRUE(contains(error_message([&] { read_bytes_as(dir, "d.hdr", radiance("#?RADIANCE\n", "-Y 99999 +X 99999", pixels)); }),
                       "exceeds"));
}

TEST(RadianceReader, RejectsXyzeAndUnknownFormats) {
  TempDir dir("io_hdr_format");
  const Bytes pixels = indexed_pixels(1);
  const std::string xyze =
      error_message([&] { read_bytes_as(dir, "x.hdr", radiance("#?RADIANCE\nFORMAT=32-bit_rle_xyze\n", "-Y 1 +X 1", pixels)); });
  EXPECT_TRUE(contains(xyze, "XYZE")) << xyze;
  EXPECT_TRUE(contains(xyze, "x.hdr")) << xyze;
  EXPECT_TRUE(contains(error_message([&] { read_bytes_as(dir, "y.hdr", radiance("#?RADIANCE\nFORMAT=foo\n", "-Y 1 +X 1", pixels)); }),
                       "FORMAT"));
}

TEST(RadianceReader, AcceptsRgbeProgramTypeAndProgramLineAfterOtherLines) {
  TempDir dir("io_hdr_header");
  const Bytes pixels = indexed_pixels(2);
  EXPECT_EQ(read_bytes_as(dir, "a.hdr", radiance("#?RGBE\nEXPOSURE=2.0\n", "-Y 1 +X 2", pixels)).texel(1, 0)[0], 2.0f);
  // EXPOSURE is informational: values are returned as stored.
  EXPECT_EQ(read_bytes_as(dir, "b.hdr", radiance("VIEW= -vtv\n#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", "-Y 1 +X 2", pixels))
                .width,
            2);
}

TEST(RadianceReader, DecodesNewStyleRleScanlines) {
  TempDir dir("io_hdr_rle");
  // Width 10: marker 2 2 0 10, then each plane: a run of 6 (134, value) and a literal block of 4.
  Bytes pixels;
  append(pixels, {2, 2, 0, 10});
  append(pixels, {134, 128, 4, 10, 20, 30, 40});  // R
  append(pixels, {134, 64, 4, 1, 2, 3, 4});       // G
  append(pixels, {138, 0});                       // B: one run of 10 zeros
  append(pixels, {138, 129});                     // E: one run of 10
  const Image image = read_bytes_as(dir, "rle.hdr", radiance("#?RADIANCE\n", "-Y 1 +X 10", pixels));
  EXPECT_EQ(image.texel(0, 0)[0], 1.0f);
  EXPECT_EQ(image.texel(5, 0)[1], 0.5f);
  EXPECT_EQ(image.texel(6, 0)[0], 10.0f / 128.0f);
  EXPECT_EQ(image.texel(9, 0)[1], 4.0f / 128.0f);
  EXPECT_EQ(image.texel(9, 0)[2], 0.0f);
}

TEST(RadianceReader, RejectsMalformedRleScanlines) {
  TempDir dir("io_hdr_badrle");
  auto read_scanline = [&](std::initializer_list<int> data) {
    Bytes pixels;
    append(pixels, data);
    return error_message([&] { read_bytes_as(dir, "bad.hdr", radiance("#?RADIANCE\n", "-Y 1 +X 8", pixels)); });
  };
  EXPECT_TRUE(contains(read_scanline({2, 2, 0, 9, 136, 1}), "does not match image width"));
  EXPECT_TRUE(contains(read_scanline({2, 2, 0, 8, 137, 1}), "overruns"));                // run of 9 in width 8
  EXPECT_TRUE(contains(read_scanline({2, 2, 0, 8, 0, 1}), "zero-length"));               // a literal of 0
  EXPECT_TRUE(contains(read_scanline({2, 2, 0, 8, 136, 1, 136, 2}), "truncated"));       // planes B and E missing
  EXPECT_TRUE(contains(read_scanline({2, 2, 0, 8, 136, 1, 136, 2, 136, 3, 3, 9, 9}), "truncated"));
  const std::string message = read_scanline({2, 2, 0, 8, 136, 1, 136, 2, 136, 3, 3, 9, 9});
  EXPECT_TRUE(contains(message, "bad.hdr: scanline 0")) << message;
}

TEST(RadianceReader, DecodesOldStyleRunsInFlatScanlines) {
  TempDir dir("io_hdr_oldrle");
  Bytes pixels;
  append(pixels, {128, 0, 0, 130});  // 2.0
  append(pixels, {1, 1, 1, 3});      // repeat it 3 times
  append(pixels, {128, 0, 0, 129});  // 1.0
  append(pixels, {1, 1, 1, 1});      // repeat once ...
  append(pixels, {1, 1, 1, 1});      // ... then 1 << 8 more would overrun: use width 262 to fit exactly
  const Image image = read_bytes_as(dir, "old.hdr", radiance("#?RADIANCE\n", "-Y 1 +X 262", pixels));
  EXPECT_EQ(image.texel(0, 0)[0], 2.0f);
  EXPECT_EQ(image.texel(3, 0)[0], 2.0f);
  EXPECT_EQ(image.texel(4, 0)[0], 1.0f);
  EXPECT_EQ(image.texel(261, 0)[0], 1.0f);

  Bytes leading_run;
  append(leading_run, {1, 1, 1, 2});
  EXPECT_TRUE(contains(error_message([&] { read_bytes_as(dir, "lead.hdr", radiance("#?RADIANCE\n", "-Y 1 +X 2", leading_run)); }),
                       "no preceding pixel"));
}

TEST(RadianceReader, TruncatedHeaderAndPixelsAreErrors) {
  TempDir dir("io_hdr_trunc");
  EXPECT_TRUE(contains(error_message([&] { read_bytes_as(dir, "a.hdr", text_bytes("#?RADIANCE\nFORMAT=32-bit_rle_rgbe")); }),
                       "truncated Radiance header"));
  const std::string message =
      error_message([&] { read_bytes_as(dir, "b.hdr", radiance("#?RADIANCE\n", "-Y 2 +X 2", indexed_pixels(3))); });
  EXPECT_TRUE(contains(message, "scanline 1: truncated")) << message;
}

// ---------------------------------------------------------------------------------------------------------------
// PFM

void append_float(Bytes& bytes, float value, bool little_endian) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, 4);
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<std::uint8_t>(bits >> (8 * (little_endian ? i : 3 - i))));
}

TEST(PfmReader, PositiveScaleMeansBigEndianAndRowsRunBottomToTop) {
  TempDir dir("io_pfm_be");
  Bytes bytes = text_bytes("PF\n2 2\n1.0\n");
  for (int i = 0; i < 12; ++i) append_float(bytes, static_cast<float>(i) + 0.5f, false);
  const Image image = read_bytes_as(dir, "be.pfm", bytes);
  EXPECT_EQ(image.channels, 3);
  EXPECT_EQ(image.metadata.pixel_type, "float");
  // File row 0 (values 0.5 .. 5.5) is the bottom row.
  EXPECT_EQ(image.texel(0, 1)[0], 0.5f);
  EXPECT_EQ(image.texel(1, 1)[2], 5.5f);
  EXPECT_EQ(image.texel(0, 0)[0], 6.5f);
  EXPECT_EQ(image.texel(1, 0)[2], 11.5f);
}

TEST(PfmReader, GreyPfmHasOneChannelCopiedToRgb) {
  TempDir dir("io_pfm_grey");
  Bytes bytes = text_bytes("Pf 3 1 -2.5\n");  // any whitespace between tokens, scale magnitude ignored
  for (int i = 0; i < 3; ++i) append_float(bytes, -static_cast<float>(i), true);
  const Image image = read_bytes_as(dir, "grey.pfm", bytes);
  EXPECT_EQ(image.channels, 1);
  EXPECT_EQ(image.width, 3);
  EXPECT_EQ(image.texel(2, 0)[0], -2.0f);
  EXPECT_EQ(image.texel(2, 0)[1], -2.0f);
  EXPECT_EQ(image.texel(2, 0)[2], -2.0f);
}

TEST(PfmReader, BadHeadersAndShortRastersAreErrors) {
  TempDir dir("io_pfm_bad");
  auto message_for = [&](const std::string& header, std::size_t raster_bytes) {
    Bytes bytes = text_bytes(header);
    bytes.resize(bytes.size() + raster_bytes, 0);
    return error_message([&] { read_bytes_as(dir, "bad.pfm", bytes); });
  };
  EXPECT_TRUE(contains(message_for("PF\n1 1\n0\n", 12), "scale"));
  EXPECT_TRUE(contains(message_for("PF\n1 1\nnan\n", 12), "scale"));
  EXPECT_TRUE(contains(message_for("PF\n-1 1\n-1\n", 12), "width"));
  EXPECT_TRUE(contains(message_for("PF\n1 x\n-1\n", 12), "height"));
  EXPECT_TRUE(contains(message_for("PF\n2 2\n-1\n", 47), "truncated PFM raster"));
  EXPECT_TRUE(contains(message_for("PF\n2 2\n-1", 0), "truncated PFM header"));
  EXPECT_TRUE(contains(message_for("PF\n100000 100000\n-1\n", 12), "exceeds"));
}

TEST(PfmReader, ExtraHeaderTokenBlankLineAndTrailingBytesAreSizeMismatches) {
  TempDir dir("io_pfm_shifted");
  auto message_for = [&](const std::string& header, std::size_t extra_bytes) {
    Bytes bytes = text_bytes(header);
    for (int i = 0; i < 8 * 8 * 3; ++i) append_float(bytes, 0.25f, true);  // a full 8x8 colour raster
    bytes.resize(bytes.size() + extra_bytes, 0);
    return error_message([&] { read_bytes_as(dir, "shifted.pfm", bytes); });
  };
  // "8 8 8": the third 8 is taken as the scale, so "-1\n" lands in front of the raster.
  const std::string extra_token = message_for("PF\n8 8 8\n-1\n", 0);
  EXPECT_TRUE(contains(extra_token, "PFM raster size mismatch: 771 bytes after the header, 768 expected")) << extra_token;
  const std::string blank_line = message_for("PF\n8 8\n-1\n\n", 0);
  EXPECT_TRUE(contains(blank_line, "769 bytes after the header, 768 expected")) << blank_line;
  const std::string trailing = message_for("PF\n8 8\n-1\n", 5);
  EXPECT_TRUE(contains(trailing, "773 bytes after the header")) << trailing;
  EXPECT_NO_THROW(read_bytes_as(dir, "exact.pfm", [] {
    Bytes bytes = text_bytes("PF\n8 8\n-1\n");
    for (int i = 0; i < 8 * 8 * 3; ++i) append_float(bytes, 0.25f, true);
    return bytes;
  }()));
}

// ---------------------------------------------------------------------------------------------------------------
// PNG (built chunk by chunk with zlib so every colour type can be tested without another encoder)

void append_u32(Bytes& bytes, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) bytes.push_back(static_cast<std::uint8_t>(value >> shift));
}

void append_chunk(Bytes& png, const char type[4], const Bytes& data) {
  append_u32(png, static_cast<std::uint32_t>(data.size()));
  Bytes typed(type, type + 4);
  typed.insert(typed.end(), data.begin(), data.end());
  png.insert(png.end(), typed.begin(), typed.end());
  append_u32(png, static_cast<std::uint32_t>(crc32(0, typed.data(), static_cast<uInt>(typed.size()))));
}

struct PngSpec {
  std::uint32_t width, height;
  int bit_depth, colour_type;
  Bytes rows;                  // filtered scanlines: filter byte 0 + packed samples per row
  Bytes palette, transparency;  // PLTE / tRNS payloads (empty = absent)
};

Bytes build_png(const PngSpec& spec) {
  Bytes png = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  Bytes header;
  append_u32(header, spec.width);
  append_u32(header, spec.height);
  append(header, {spec.bit_depth, spec.colour_type, 0, 0, 0});
  append_chunk(png, "IHDR", header);
  if (!spec.palette.empty()) append_chunk(png, "PLTE", spec.palette);
  if (!spec.transparency.empty()) append_chunk(png, "tRNS", spec.transparency);
  uLongf compressed_size = compressBound(static_cast<uLong>(spec.rows.size()));
  Bytes compressed(compressed_size);
  EXPECT_EQ(compress(compressed.data(), &compressed_size, spec.rows.data(), static_cast<uLong>(spec.rows.size())), Z_OK);
  compressed.resize(compressed_size);
  append_chunk(png, "IDAT", compressed);
  append_chunk(png, "IEND", {});
  return png;
}

TEST(PngReader, PaletteWithTransparencyBecomesRgba) {
  TempDir dir("io_png_palette");
  PngSpec spec{3, 1, 8, 3, {}, {}, {}};
  append(spec.rows, {0, 0, 1, 2});
  append(spec.palette, {255, 0, 0, 0, 255, 0, 0, 0, 51});
  append(spec.transparency, {128, 255});  // entries beyond the tRNS list are opaque
  const Image image = read_bytes_as(dir, "palette.png", build_png(spec));
  EXPECT_EQ(image.channels, 4);
  EXPECT_EQ(image.metadata.pixel_type, "uint8");
  EXPECT_EQ(image.texel(0, 0)[0], 1.0f);
  EXPECT_EQ(image.texel(0, 0)[3], 128.0f / 255.0f);
  EXPECT_EQ(image.texel(1, 0)[1], 1.0f);
  EXPECT_EQ(image.texel(1, 0)[3], 1.0f);
  EXPECT_EQ(image.texel(2, 0)[2], 51.0f / 255.0f);  // code / 255, no sRGB decoding
  EXPECT_EQ(image.texel(2, 0)[3], 1.0f);
}

TEST(PngReader, PaletteWithoutTransparencyIsRgb) {
  TempDir dir("io_png_palette_rgb");
  PngSpec spec{2, 1, 8, 3, {}, {}, {}};
  append(spec.rows, {0, 1, 0});
  append(spec.palette, {10, 20, 30, 40, 50, 60});
  const Image image = read_bytes_as(dir, "palette.png", build_png(spec));
  EXPECT_EQ(image.channels, 3);
  EXPECT_EQ(image.texel(0, 0)[0], 40.0f / 255.0f);
  EXPECT_EQ(image.texel(1, 0)[2], 30.0f / 255.0f);
}

TEST(PngReader, OneBitGreyExpandsToZeroAndOne) {
  TempDir dir("io_png_1bit");
  PngSpec spec{10, 1, 1, 0, {}, {}, {}};
  append(spec.rows, {0, 0b10100000, 0b01000000});  // pixels 0 and 2 and 9 set
  const Image image = read_bytes_as(dir, "bits.png", build_png(spec));
  EXPECT_EQ(image.channels, 1);
  const float expected[10] = {1, 0, 1, 0, 0, 0, 0, 0, 0, 1};
  for (int x = 0; x < 10; ++x) {
    EXPECT_EQ(image.texel(x, 0)[0], expected[x]) << x;
    EXPECT_EQ(image.texel(x, 0)[2], expected[x]) << x;
  }
}

TEST(PngReader, GreyAlphaAndSixteenBitRgbAreDecodedAsCodes) {
  TempDir dir("io_png_types");
  PngSpec grey_alpha{2, 1, 8, 4, {}, {}, {}};
  append(grey_alpha.rows, {0, 17, 34, 255, 0});
  const Image ga = read_bytes_as(dir, "ga.png", build_png(grey_alpha));
  EXPECT_EQ(ga.channels, 4);
  EXPECT_EQ(ga.texel(0, 0)[1], 17.0f / 255.0f);
  EXPECT_EQ(ga.texel(0, 0)[3], 34.0f / 255.0f);
  EXPECT_EQ(ga.texel(1, 0)[3], 0.0f);

  PngSpec rgb16{1, 2, 16, 2, {}, {}, {}};
  append(rgb16.rows, {0, 0x12, 0x34, 0xff, 0xff, 0x00, 0x01});
  append(rgb16.rows, {0, 0x00, 0x00, 0x80, 0x00, 0xab, 0xcd});
  const Image deep = read_bytes_as(dir, "rgb16.png", build_png(rgb16));
  EXPECT_EQ(deep.channels, 3);
  EXPECT_EQ(deep.metadata.pixel_type, "uint16");
  EXPECT_EQ(deep.texel(0, 0)[0], static_cast<float>(0x1234) / 65535.0f);
  EXPECT_EQ(deep.texel(0, 0)[1], 1.0f);
  EXPECT_EQ(deep.texel(0, 0)[2], 1.0f / 65535.0f);
  EXPECT_EQ(deep.texel(0, 1)[2], static_cast<float>(0xabcd) / 65535.0f);

  PngSpec rgb_trns{2, 1, 8, 2, {}, {}, {}};
  append(rgb_trns.rows, {0, 1, 2, 3, 4, 5, 6});
  append(rgb_trns.transparency, {0, 4, 0, 5, 0, 6});  // the colour (4, 5, 6) is transparent
  const Image keyed = read_bytes_as(dir, "keyed.png", build_png(rgb_trns));
  EXPECT_EQ(keyed.channels, 4);
  EXPECT_EQ(keyed.texel(0, 0)[3], 1.0f);
  EXPECT_EQ(keyed.texel(1, 0)[3], 0.0f);
}

TEST(PngReader, DamagedFilesThrowInsteadOfAborting) {
  TempDir dir("io_png_bad");
  PngSpec spec{4, 4, 8, 2, {}, {}, {}};
  for (int y = 0; y < 4; ++y) {
    spec.rows.push_back(0);
    for (int i = 0; i < 12; ++i) spec.rows.push_back(static_cast<std::uint8_t>(y * 12 + i));
  }
  const Bytes good = build_png(spec);
  EXPECT_NO_THROW(read_bytes_as(dir, "good.png", good));

  Bytes bad_crc = good;
  bad_crc[bad_crc.size() - 13] ^= 0x40;  // last byte of the IDAT CRC
  const std::string crc_message = error_message([&] { read_bytes_as(dir, "crc.png", bad_crc); });
  EXPECT_TRUE(contains(crc_message, "crc.png: corrupt or unsupported PNG")) << crc_message;

  PngSpec short_rows = spec;
  short_rows.rows.resize(short_rows.rows.size() - 13);  // one row missing from the compressed stream
  EXPECT_TRUE(contains(error_message([&] { read_bytes_as(dir, "short.png", build_png(short_rows)); }), "short.png"));

  PngSpec huge = spec;
  huge.width = huge.height = 60000;  // 3.6e9 texels claimed by a 100-byte file
  EXPECT_TRUE(contains(error_message([&] { read_bytes_as(dir, "huge.png", build_png(huge)); }), "huge.png"));
  PngSpec impossible = spec;
  impossible.width = 4000;
  impossible.height = 4000;  // within the texel limit, but 48 MB of rows cannot fit in a ~100-byte deflate stream
  EXPECT_TRUE(contains(error_message([&] { read_bytes_as(dir, "impossible.png", build_png(impossible)); }),
                       "impossible for the file length"));
}

}  // namespace
}  // namespace blocklab
