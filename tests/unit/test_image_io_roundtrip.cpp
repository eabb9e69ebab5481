// write_image -> read_image round trips on small synthetic images, for every writer: EXR float (exact), EXR half
// (within half precision, exact for half-representable values), PFM (bit-exact), PNG 8/16 (exact on code values,
// clamping and rounding), Radiance .hdr (within RGBE precision, exact for RGBE-representable values), odd sizes
// including 1x1.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image_io.h"
#include "test_image_io_common.h"

namespace blocklab {
namespace {

using test_io::synthetic_image;
using test_io::TempDir;

const std::vector<std::pair<int, int>> kSizes = {{1, 1}, {2, 3}, {7, 5}, {13, 1}, {1, 9}, {37, 11}};

void expect_same_size(const Image& expected, const Image& actual) {
  ASSERT_EQ(actual.width, expected.width);
  ASSERT_EQ(actual.height, expected.height);
  ASSERT_EQ(actual.pixels.size(), expected.pixels.size());
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(ExrRoundTrip, FloatIsBitExactIncludingNegativeTinyAndHugeValues) {
  TempDir dir("io_exr_float");
  for (const int channels : {3, 4}) {
    for (const auto& [w, h] : kSizes) {
      Image image = synthetic_image(w, h, channels, false, static_cast<std::uint32_t>(w * 31 + h));
      image.texel(0, 0)[0] = -3.25f;
      image.texel(w - 1, h - 1)[1] = 1e-30f;
      image.texel(w / 2, h / 2)[2] = 3.0e38f;
      const std::string path = dir.file("float.exr");
      write_image(path, image, WriteOptions{ExrPixelType::float32, 8});
      const Image loaded = read_image(path);
      expect_same_size(image, loaded);
      EXPECT_EQ(loaded.channels, channels);
      EXPECT_EQ(loaded.metadata.pixel_type, "float");
      EXPECT_EQ(loaded.metadata.container, "exr");
      for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        ASSERT_TRUE(same_bits(image.pixels[i], loaded.pixels[i])) << w << "x" << h << " index " << i;
      }
    }
  }
}

TEST(ExrRoundTrip, HalfIsWithinHalfPrecisionAndExactForHalfValues) {
  TempDir dir("io_exr_half");
  for (const auto& [w, h] : kSizes) {
    const Image image = synthetic_image(w, h, 3, false, static_cast<std::uint32_t>(w + 7 * h));
    const std::string path = dir.file("half.exr");
    write_image(path, image);  // half is the default
    const Image loaded = read_image(path);
    expect_same_size(image, loaded);
    EXPECT_EQ(loaded.metadata.pixel_type, "half");
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
      // Values here are normal halves (2^-10 .. 2^10): round-to-nearest error is at most half an ulp, 2^-11 relative.
      EXPECT_NEAR(loaded.pixels[i], image.pixels[i], std::ldexp(std::fabs(image.pixels[i]), -11)) << i;
    }
  }
  // k / 1024 for k < 2048 and multiples of 32 are exact halves: they must come back unchanged.
  Image exact(64, 2, 4);
  for (int x = 0; x < 64; ++x) {
    for (int c = 0; c < 4; ++c) {
      exact.texel(x, 0)[c] = static_cast<float>(x * 29 + c) / 1024.0f;
      // Multiples of 32 below 65536 are halves (the half spacing is 32 in the top octave): up to 32352.
      exact.texel(x, 1)[c] = static_cast<float>(x * 512 + c * 32);
    }
  }
  const std::string path = dir.file("exact.exr");
  write_image(path, exact);
  const Image loaded = read_image(path);
  EXPECT_EQ(loaded.channels, 4);
  for (std::size_t i = 0; i < exact.pixels.size(); ++i) ASSERT_EQ(loaded.pixels[i], exact.pixels[i]) << i;
}

TEST(ExrRoundTrip, LuminanceOnlyImageIsWrittenAsEqualRgb) {
  TempDir dir("io_exr_grey");
  const Image grey = synthetic_image(5, 4, 1, false);
  const std::string path = dir.file("grey.exr");
  write_image(path, grey, WriteOptions{ExrPixelType::float32, 8});
  const Image loaded = read_image(path);
  EXPECT_EQ(loaded.channels, 3);
  for (std::size_t i = 0; i < grey.pixels.size(); ++i) ASSERT_EQ(loaded.pixels[i], grey.pixels[i]);
}

TEST(ExrRoundTrip, ChromaticitiesAreWrittenBack) {
  TempDir dir("io_exr_chroma");
  Image image = synthetic_image(3, 3, 3, false);
  image.metadata.chromaticities = std::array<float, 8>{0.7347f, 0.2653f, 0.0f, 1.0f, 0.0001f, -0.077f, 0.32168f, 0.33767f};
  const std::string path = dir.file("chroma.exr");
  write_image(path, image);
  const Image loaded = read_image(path);
  ASSERT_TRUE(loaded.metadata.chromaticities.has_value());
  EXPECT_EQ(*loaded.metadata.chromaticities, *image.metadata.chromaticities);
  write_image(path, synthetic_image(3, 3, 3, false));
  EXPECT_FALSE(read_image(path).metadata.chromaticities.has_value());
}

TEST(PfmRoundTrip, ColourIsBitExactAndRowOrderPreserved) {
  TempDir dir("io_pfm");
  for (const auto& [w, h] : kSizes) {
    Image image = synthetic_image(w, h, 3, false, static_cast<std::uint32_t>(3 * w + h));
    image.texel(0, 0)[0] = -1.5f;
    image.texel(0, h - 1)[2] = std::numeric_limits<float>::infinity();
    image.texel(w - 1, 0)[1] = std::numeric_limits<float>::quiet_NaN();
    const std::string path = dir.file("image.pfm");
    write_image(path, image);
    const Image loaded = read_image(path);
    expect_same_size(image, loaded);
    EXPECT_EQ(loaded.channels, 3);
    EXPECT_EQ(loaded.metadata.container, "pfm");
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
      ASSERT_TRUE(same_bits(image.pixels[i], loaded.pixels[i])) << w << "x" << h << " index " << i;
    }
  }
}

TEST(PfmRoundTrip, WriterProducesLittleEndianColourWithBottomRowFirst) {
  TempDir dir("io_pfm_layout");
  Image image(1, 2, 3);
  image.texel(0, 0)[0] = 1.0f;  // top row
  image.texel(0, 1)[0] = 2.0f;  // bottom row
  const std::string path = dir.file("layout.pfm");
  write_image(path, image);
  const auto bytes = test_io::read_bytes(path);
  const std::string header = "PF\n1 2\n-1.0\n";
  ASSERT_EQ(bytes.size(), header.size() + 2 * 12);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(header.size())), header);
  float first;
  std::memcpy(&first, &bytes[header.size()], 4);  // little-endian host
  EXPECT_EQ(first, 2.0f);
}

TEST(PngRoundTrip, SixteenBitCodesAreExact) {
  TempDir dir("io_png16");
  for (const int channels : {1, 3, 4}) {
    for (const auto& [w, h] : kSizes) {
      Image image(w, h, channels);
      std::uint32_t code = 12345u * static_cast<std::uint32_t>(w + h + channels);
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          float* t = image.texel(x, y);
          for (int c = 0; c < 4; ++c) {
            code = (code * 1103515245u + 12345u) & 0xffffu;
            t[c] = static_cast<float>(code) / 65535.0f;
          }
          if (channels == 1) t[1] = t[2] = t[0];
          if (channels != 4) t[3] = 1.0f;  // alpha of a source without alpha is stored as 1
        }
      }
      const std::string path = dir.file("image16.png");
      write_image(path, image, WriteOptions{ExrPixelType::half, 16});
      const Image loaded = read_image(path);
      expect_same_size(image, loaded);
      EXPECT_EQ(loaded.channels, channels);
      EXPECT_EQ(loaded.metadata.pixel_type, "uint16");
      EXPECT_FALSE(loaded.metadata.is_hdr);
      for (std::size_t i = 0; i < image.pixels.size(); ++i) ASSERT_EQ(loaded.pixels[i], image.pixels[i]) << i;
    }
  }
}

TEST(PngRoundTrip, EightBitCodesAreExact) {
  TempDir dir("io_png8");
  for (const int channels : {1, 3, 4}) {
    Image image(256, 3, channels);
    for (int y = 0; y < 3; ++y) {
      for (int x = 0; x < 256; ++x) {
        float* t = image.texel(x, y);
        for (int c = 0; c < (channels == 1 ? 1 : channels); ++c) t[c] = static_cast<float>((x + 85 * c + y) % 256) / 255.0f;
        if (channels == 1) t[1] = t[2] = t[0];
      }
    }
    const std::string path = dir.file("image8.png");
    write_image(path, image);
    const Image loaded = read_image(path);
    expect_same_size(image, loaded);
    EXPECT_EQ(loaded.channels, channels);
    EXPECT_EQ(loaded.metadata.pixel_type, "uint8");
    for (std::size_t i = 0; i < image.pixels.size(); ++i) ASSERT_EQ(loaded.pixels[i], image.pixels[i]) << i;
  }
}

TEST(PngRoundTrip, WriterClampsToUnitRangeAndRoundsToNearestCode) {
  TempDir dir("io_png_clamp");
  Image image(6, 1, 3);
  const float inputs[6] = {-0.5f, 1.7f, std::numeric_limits<float>::quiet_NaN(), 10.4f / 255.0f, 10.6f / 255.0f,
                           std::numeric_limits<float>::infinity()};
  const float expected[6] = {0.0f, 1.0f, 0.0f, 10.0f / 255.0f, 11.0f / 255.0f, 1.0f};
  for (int x = 0; x < 6; ++x) image.texel(x, 0)[0] = image.texel(x, 0)[1] = image.texel(x, 0)[2] = inputs[x];
  const std::string path = dir.file("clamp.png");
  write_image(path, image);
  const Image loaded = read_image(path);
  for (int x = 0; x < 6; ++x) EXPECT_EQ(loaded.texel(x, 0)[0], expected[x]) << x;
}

// RGBE keeps 8 mantissa bits relative to the largest channel: any channel's error is below max_channel / 128.
TEST(RadianceRoundTrip, ValuesAreWithinRgbePrecisionForRleAndFlatWidths) {
  TempDir dir("io_hdr");
  // Widths 1..7 and > 0x7fff are written flat; 8..0x7fff with new-style RLE.
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{{1, 1}, {7, 3}, {8, 2}, {37, 11}, {300, 4}}) {
    const Image image = synthetic_image(w, h, 3, false, static_cast<std::uint32_t>(w * h));
    const std::string path = dir.file("image.hdr");
    write_image(path, image);
    const Image loaded = read_image(path);
    expect_same_size(image, loaded);
    EXPECT_EQ(loaded.channels, 3);
    EXPECT_EQ(loaded.metadata.pixel_type, "rgbe");
    for (std::size_t i = 0; i < image.texel_count(); ++i) {
      const float* in = &image.pixels[4 * i];
      const float* out = &loaded.pixels[4 * i];
      const float largest = std::max(in[0], std::max(in[1], in[2]));
      for (int c = 0; c < 3; ++c) {
        // Ward's truncating encoder with the no-offset decoder: decoded <= original, short by < 1/128 of max.
        ASSERT_LE(out[c], in[c]) << w << "x" << h << " texel " << i;
        ASSERT_LT(in[c] - out[c], largest / 128.0f) << w << "x" << h << " texel " << i;
      }
      ASSERT_EQ(out[3], 1.0f);
    }
  }
}

TEST(RadianceRoundTrip, RepresentableValuesAreExactAndUnstorableValuesAreMapped) {
  TempDir dir("io_hdr_exact");
  Image image(9, 1, 3);
  const float rows[9][3] = {
      {1.0f, 0.5f, 0.25f},                                   // mantissas 128, 64, 32 with exponent 129
      {255.0f / 128.0f, 1.0f, 0.0f},                         // 255 * 2^-7
      {0.0f, 0.0f, 0.0f},                                    // black: exponent byte 0
      {-1.0f, 2.0f, std::numeric_limits<float>::quiet_NaN()},  // negative and NaN -> 0
      {std::ldexp(200.0f, -100), 0.0f, 0.0f},               // small but above Ward's 1e-32 threshold
      {1e-33f, 1e-33f, 1e-33f},                              // below the threshold -> black
      {std::numeric_limits<float>::infinity(), 0.0f, 0.0f}, // saturates to 255 * 2^119
      {3.0e38f, 1.0f, 0.0f},                                 // saturates too; 1.0 is far below max -> 0
      {65504.0f, 32.0f, 1.0f},
  };
  for (int x = 0; x < 9; ++x)
    for (int c = 0; c < 3; ++c) image.texel(x, 0)[c] = rows[x][c];
  const std::string path = dir.file("exact.hdr");
  write_image(path, image);
  const Image loaded = read_image(path);
  const float max_rgbe = std::ldexp(255.0f, 119);
  const float expected[9][3] = {
      {1.0f, 0.5f, 0.25f}, {255.0f / 128.0f, 1.0f, 0.0f}, {0, 0, 0}, {0.0f, 2.0f, 0.0f},
      {std::ldexp(200.0f, -100), 0, 0}, {0, 0, 0}, {max_rgbe, 0, 0}, {max_rgbe, 0, 0},
      // 65504 = 255.875 * 2^8: mantissa truncates to 255 -> 65280; 32 and 1 are below max / 256 -> 0.
      {65280.0f, 0.0f, 0.0f}};
  for (int x = 0; x < 9; ++x) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(loaded.texel(x, 0)[c], expected[x][c]) << "texel " << x << " channel " << c;
  }
}

TEST(RadianceRoundTrip, ConstantImageIsRunLengthEncoded) {
  TempDir dir("io_hdr_rle");
  Image image(1000, 3, 3);
  for (float& v : image.pixels) v = 0.75f;
  const std::string path = dir.file("flat_colour.hdr");
  write_image(path, image);
  // Per scanline: 4 marker bytes + 4 planes * 8 runs (7 * 127 + 111) * 2 bytes = 68, far below 4000 flat bytes.
  EXPECT_LT(test_io::read_bytes(path).size(), 3u * 68u + 100u);
  const Image loaded = read_image(path);
  for (std::size_t i = 0; i < loaded.texel_count(); ++i) ASSERT_EQ(loaded.pixels[4 * i + 1], 0.75f);
}

TEST(WriteImage, ExtensionIsCaseInsensitive) {
  TempDir dir("io_ext");
  const Image image = synthetic_image(4, 4, 3, true);
  for (const char* name : {"a.EXR", "b.Png", "c.PFM", "d.HDR"}) {
    ASSERT_NO_THROW(write_image(dir.file(name), image)) << name;
    EXPECT_EQ(read_image(dir.file(name)).width, 4) << name;
  }
}

}  // namespace
}  // namespace blocklab
