// The `rgbe` format (formats/rgbe): Ward's known vectors, agreement with a spec-literal transcription of "Real
// Pixels", the error bound, the exponent-range clamp, both decode offsets, true sizes for images that are not
// multiples of 4, thread-count invariance and rejection of unstorable input.
#include <gtest/gtest.h>

#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "formats/registry.h"
#include "formats/rgbe/rgbe_format.h"

namespace blocklab {
namespace {

const Format& rgbe() { return find_format("rgbe"); }
FormatOptions options_with(const std::string& decode_offset) {
  return resolve_format_options(rgbe(), {{"decode_offset", decode_offset}});
}

using Texel = std::array<unsigned, 4>;

Texel encoded(float red, float green, float blue) {
  std::uint8_t bytes[4];
  encode_rgbe_texel(red, green, blue, bytes);
  return {bytes[0], bytes[1], bytes[2], bytes[3]};
}

// Spec-literal transcription of Ward's float-to-RGBE ("Real Pixels", Graphics Gems II): scale computed as
// frexp mantissa * 256 / max in double, narrowed to float, products truncated by the unsigned char conversion.
// Written independently as the oracle for the exact (ldexp) implementation.
Texel ward_reference(float red, float green, float blue) {
  float largest = red;
  if (green > largest) largest = green;
  if (blue > largest) largest = blue;
  if (largest < 1e-32) return {0, 0, 0, 0};
  int exponent = 0;
  const float scale = static_cast<float>(std::frexp(largest, &exponent) * 256.0 / largest);
  return {static_cast<unsigned>(red * scale), static_cast<unsigned>(green * scale),
          static_cast<unsigned>(blue * scale), static_cast<unsigned>(exponent + 128)};
}

// Deterministic values spread over many octaves, with zeros and tiny values mixed in.
std::vector<float> spread_values(std::size_t count) {
  std::vector<float> values(count);
  std::uint64_t state = 12345;
  for (float& value : values) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const std::uint64_t z = state >> 11;
    const int octave = static_cast<int>(z % 200) - 120;   // 2^-120 .. 2^79 (the large ones clamp below 2^127)
    value = (z % 17 == 0) ? 0.0f : std::ldexp(static_cast<float>((z >> 8) & 0xFFFFFF) / 16777216.0f, octave);
    if (!std::isfinite(value)) value = FLT_MAX;
  }
  return values;
}

Image pattern_image(int width, int height, int channels = 3) {
  Image image(width, height, channels);
  const std::vector<float> values = spread_values(image.texel_count() * 3);
  for (std::size_t i = 0; i < image.texel_count(); ++i)
    for (int c = 0; c < 3; ++c) image.pixels[4 * i + c] = std::fabs(std::fmod(values[3 * i + c], 70000.0f));
  return image;
}

TEST(RgbeFormat, WardsKnownVectors) {
  EXPECT_EQ(encoded(1.0f, 1.0f, 1.0f), (Texel{128, 128, 128, 129}));
  EXPECT_EQ(encoded(1.0f, 0.5f, 0.25f), (Texel{128, 64, 32, 129}));
  EXPECT_EQ(encoded(0.75f, 0.0f, 0.0f), (Texel{192, 0, 0, 128}));
  EXPECT_EQ(encoded(0.0f, 0.0f, 65504.0f), (Texel{0, 0, 255, 144}));   // 65504 / 2^16 * 256 = 255.875
  EXPECT_EQ(encoded(0.0f, 0.0f, 0.0f), (Texel{0, 0, 0, 0}));
}

TEST(RgbeFormat, ValuesBelowWardsThresholdAreStoredAsZero) {
  EXPECT_EQ(encoded(1e-33f, 5e-33f, 0.0f), (Texel{0, 0, 0, 0}));
  EXPECT_EQ(encoded(9.9e-33f, 0.0f, 0.0f), (Texel{0, 0, 0, 0}));
  EXPECT_EQ(encoded(std::numeric_limits<float>::denorm_min(), 0.0f, 0.0f), (Texel{0, 0, 0, 0}));
  // Just above: 2e-32 is in [2^-106, 2^-105), so e = -105 and E = 23.
  EXPECT_EQ(encoded(2e-32f, 0.0f, 0.0f)[3], 23u);
}

TEST(RgbeFormat, MatchesTheSpecLiteralTranscriptionOfRealPixels) {
  const std::vector<float> values = spread_values(3 * 200000);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < values.size(); i += 3) {
    const float r = values[i], g = values[i + 1], b = values[i + 2];
    if (std::max(r, std::max(g, b)) >= std::ldexp(1.0f, 127)) continue;   // beyond the exponent range (below)
    if (encoded(r, g, b) != ward_reference(r, g, b)) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0u);
}

TEST(RgbeFormat, ExponentRangeSaturatesAtTwoToThe127) {
  // 2^127 needs E = 256: clamped to E = 255 and the bytes saturate, i.e. stored as 255 * 2^119.
  EXPECT_EQ(encoded(std::ldexp(1.0f, 127), 0.0f, 0.0f), (Texel{255, 0, 0, 255}));
  EXPECT_EQ(encoded(FLT_MAX, std::ldexp(1.0f, 120), 0.0f), (Texel{255, 2, 0, 255}));
  // Just below 2^127 is representable normally.
  EXPECT_EQ(encoded(std::ldexp(1.5f, 126), 0.0f, 0.0f), (Texel{192, 0, 0, 255}));
  const std::uint8_t saturated[4] = {255, 255, 255, 255};
  float rgb[3];
  decode_rgbe_texel(saturated, RgbeDecodeOffset::none, rgb);
  EXPECT_EQ(rgb[0], std::ldexp(255.0f, 119));
}

TEST(RgbeFormat, DecodeIsBytesTimesTwoToTheEMinus136WithOptionalHalfOffset) {
  const std::uint8_t one[4] = {128, 64, 1, 129};
  float rgb[3];
  decode_rgbe_texel(one, RgbeDecodeOffset::none, rgb);
  EXPECT_EQ(rgb[0], 1.0f);
  EXPECT_EQ(rgb[1], 0.5f);
  EXPECT_EQ(rgb[2], std::ldexp(1.0f, -7));
  decode_rgbe_texel(one, RgbeDecodeOffset::half, rgb);
  EXPECT_EQ(rgb[0], 128.5f / 128.0f);
  EXPECT_EQ(rgb[1], 64.5f / 128.0f);
  EXPECT_EQ(rgb[2], 1.5f / 128.0f);
  // E == 0 is zero whatever the mantissa bytes hold, for both offsets.
  const std::uint8_t zero_exponent[4] = {200, 17, 3, 0};
  for (const RgbeDecodeOffset offset : {RgbeDecodeOffset::none, RgbeDecodeOffset::half}) {
    decode_rgbe_texel(zero_exponent, offset, rgb);
    EXPECT_EQ(rgb[0], 0.0f);
    EXPECT_EQ(rgb[1], 0.0f);
    EXPECT_EQ(rgb[2], 0.0f);
  }
  // The smallest unit, E = 1: 2^-135 is a float subnormal and exact.
  const std::uint8_t smallest[4] = {1, 0, 0, 1};
  decode_rgbe_texel(smallest, RgbeDecodeOffset::none, rgb);
  EXPECT_EQ(rgb[0], std::ldexp(1.0f, -135));
}

TEST(RgbeFormat, EveryFourBytePatternDecodesToAFiniteNonNegativeValue) {
  float rgb[3];
  for (unsigned exponent = 0; exponent < 256; ++exponent)
    for (unsigned byte = 0; byte < 256; ++byte) {
      const std::uint8_t texel[4] = {static_cast<std::uint8_t>(byte), 0, 255, static_cast<std::uint8_t>(exponent)};
      decode_rgbe_texel(texel, RgbeDecodeOffset::half, rgb);
      ASSERT_TRUE(std::isfinite(rgb[0]) && rgb[0] >= 0.0f && std::isfinite(rgb[2])) << exponent << " " << byte;
    }
}

TEST(RgbeFormat, ErrorIsBelowOneUnitWhichIsAtMostTwoToTheMinus7OfTheMaxChannel) {
  // Truncation ("none"): 0 <= c - decoded < 2^(e-8) <= 2^-7 * m; centred ("half"): |c - decoded| <= 2^-8 * m.
  const std::vector<float> values = spread_values(3 * 100000);
  for (std::size_t i = 0; i < values.size(); i += 3) {
    const float input[3] = {values[i], values[i + 1], values[i + 2]};
    const float largest = std::max(input[0], std::max(input[1], input[2]));
    if (static_cast<double>(largest) < kRgbeZeroThreshold || largest >= std::ldexp(1.0f, 127)) continue;
    int exponent = 0;
    std::frexp(largest, &exponent);
    const double unit = std::ldexp(1.0, exponent - 8);
    std::uint8_t bytes[4];
    encode_rgbe_texel(input[0], input[1], input[2], bytes);
    float truncated[3], centred[3];
    decode_rgbe_texel(bytes, RgbeDecodeOffset::none, truncated);
    decode_rgbe_texel(bytes, RgbeDecodeOffset::half, centred);
    for (int c = 0; c < 3; ++c) {
      const double error = static_cast<double>(input[c]) - truncated[c];
      ASSERT_GE(error, 0.0);
      ASSERT_LT(error, unit);
      ASSERT_LE(error, std::ldexp(static_cast<double>(largest), -7));
      ASSERT_LE(std::fabs(static_cast<double>(input[c]) - centred[c]), std::ldexp(static_cast<double>(largest), -8));
    }
  }
}

TEST(RgbeFormat, DecodeOffsetIsAChoiceOption) {
  EXPECT_EQ(resolve_format_options(rgbe(), {}).at("decode_offset"), "none");
  EXPECT_THROW(resolve_format_options(rgbe(), {{"decode_offset", "quarter"}}), Error);
  // The option changes decoding only: the bytes are the same.
  const Image image = pattern_image(9, 6);
  const EncodedTexture none = rgbe().encode(image, options_with("none"), CodecContext{1, 1});
  const EncodedTexture half = rgbe().encode(image, options_with("half"), CodecContext{1, 1});
  EXPECT_EQ(none.blocks, half.blocks);
  const Image decoded = rgbe().decode(half, CodecContext{1, 1});
  std::uint8_t bytes[4];
  float expected[3];
  encode_rgbe_texel(image.texel(8, 5)[0], image.texel(8, 5)[1], image.texel(8, 5)[2], bytes);
  decode_rgbe_texel(bytes, RgbeDecodeOffset::half, expected);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(decoded.texel(8, 5)[c], expected[c]);
}

TEST(RgbeFormat, StoresTexelsInBcnOrder) {
  Image image(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) image.texel(x, y)[0] = static_cast<float>(1 + x + 4 * y);
  const EncodedTexture texture = rgbe().encode(image, options_with("none"), CodecContext{1, 1});
  ASSERT_EQ(texture.blocks.size(), 64u);
  for (int i = 0; i < 16; ++i) {
    const Texel expected = encoded(static_cast<float>(1 + i), 0.0f, 0.0f);
    for (int b = 0; b < 4; ++b) EXPECT_EQ(texture.blocks[4 * i + b], expected[b]) << "texel " << i;
  }
}

TEST(RgbeFormat, NonMultipleOfFourSizesKeepTheirSizeAndDecodeTheTexelsInside) {
  for (const auto& size : {std::pair<int, int>{1, 1}, {5, 3}, {3, 9}}) {
    SCOPED_TRACE(std::to_string(size.first) + "x" + std::to_string(size.second));
    Image image(size.first, size.second);
    // Values with at most 8 significant bits relative to their texel's max are stored exactly.
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        image.texel(x, y)[0] = 0.25f * static_cast<float>(128 + x + 8 * y);
        image.texel(x, y)[1] = 0.25f * static_cast<float>(x + 1);
        image.texel(x, y)[2] = 0.0f;
      }
    const EncodedTexture texture = rgbe().encode(image, options_with("none"), CodecContext{1, 1});
    EXPECT_EQ(texture.width, size.first);
    EXPECT_EQ(texture.height, size.second);
    EXPECT_EQ(texture.blocks.size(), static_cast<std::size_t>((size.first + 3) / 4 * ((size.second + 3) / 4)) * 64u);
    const Image decoded = rgbe().decode(texture, CodecContext{1, 1});
    ASSERT_EQ(decoded.width, size.first);
    ASSERT_EQ(decoded.height, size.second);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        for (int c = 0; c < 4; ++c) EXPECT_EQ(decoded.texel(x, y)[c], image.texel(x, y)[c]) << x << "," << y;
  }
}

TEST(RgbeFormat, OutputIsByteIdenticalAtOneTwoAndFourThreads) {
  const Image image = pattern_image(41, 19);
  const EncodedTexture one = rgbe().encode(image, options_with("none"), CodecContext{1, 1});
  const Image decoded_one = rgbe().decode(one, CodecContext{1, 1});
  for (int threads : {2, 4}) {
    const EncodedTexture many = rgbe().encode(image, options_with("none"), CodecContext{threads, 1});
    EXPECT_EQ(one.blocks, many.blocks) << threads << " threads";
    const Image decoded_many = rgbe().decode(one, CodecContext{threads, 1});
    EXPECT_EQ(0, std::memcmp(decoded_one.pixels.data(), decoded_many.pixels.data(),
                             decoded_one.pixels.size() * sizeof(float)));
  }
}

TEST(RgbeFormat, LuminanceSourcesStayGrey) {
  Image grey = pattern_image(6, 6, 1);
  for (std::size_t i = 0; i < grey.texel_count(); ++i) grey.pixels[4 * i + 1] = grey.pixels[4 * i + 2] = grey.pixels[4 * i];
  const Image decoded = rgbe().decode(rgbe().encode(grey, options_with("half"), CodecContext{1, 1}), CodecContext{1, 1});
  EXPECT_EQ(decoded.channels, 1);
  for (std::size_t i = 0; i < decoded.texel_count(); ++i) {
    EXPECT_EQ(decoded.pixels[4 * i], decoded.pixels[4 * i + 1]);
    EXPECT_EQ(decoded.pixels[4 * i], decoded.pixels[4 * i + 2]);
  }
}

TEST(RgbeFormat, EncodeRejectsNegativeNanAndInfNamingThePixel) {
  for (const float bad : {-1.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    Image image(4, 3);
    image.texel(3, 2)[2] = bad;
    try {
      rgbe().encode(image, options_with("none"), CodecContext{2, 1});
      FAIL() << bad << " accepted";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("rgbe: pixel (3, 2) channel B is"), std::string::npos) << error.what();
    }
  }
  // The texel function itself never has undefined behaviour on such values.
  EXPECT_EQ(encoded(-1.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f), (Texel{0, 0, 0, 0}));
  EXPECT_EQ(encoded(std::numeric_limits<float>::infinity(), 0.0f, 0.0f), (Texel{255, 0, 0, 255}));
}

TEST(RgbeFormat, DecodeRejectsInconsistentTexturesAndUnresolvedOptions) {
  const EncodedTexture good = rgbe().encode(Image(5, 5), options_with("none"), CodecContext{1, 1});
  EncodedTexture long_data = good;
  long_data.blocks.push_back(0);
  EXPECT_THROW(rgbe().decode(long_data, CodecContext{1, 1}), Error);
  EncodedTexture bad_mode = good;
  bad_mode.block_modes[0] = 1;   // rgbe has one mode
  EXPECT_THROW(rgbe().decode(bad_mode, CodecContext{1, 1}), Error);
  EncodedTexture no_options = good;
  no_options.options.clear();
  EXPECT_THROW(rgbe().decode(no_options, CodecContext{1, 1}), Error);
}

}  // namespace
}  // namespace blocklab
