// The `fp16` format (formats/fp16): known bytes, every finite half value round-tripping bit for bit, true sizes
// for images that are not multiples of 4, thread-count invariance and rejection of corrupt input.
#include <gtest/gtest.h>

#include "test_float_bits.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <Imath/half.h>

#include "core/error.h"
#include "formats/fp16/fp16_format.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

const Format& fp16() { return find_format("fp16"); }
FormatOptions defaults() { return resolve_format_options(fp16(), {}); }

// The two little-endian bytes fp16 stores for `value` (in a 1x1 image, texel 0, channel R).
unsigned stored_half(float value) {
  Image image(1, 1);
  image.texel(0, 0)[0] = value;
  const EncodedTexture texture = fp16().encode(image, defaults(), CodecContext{1, 1});
  return texture.blocks[0] | (static_cast<unsigned>(texture.blocks[1]) << 8);
}

// Deterministic test pattern (splitmix64-style hash -> values spread over several octaves).
Image pattern_image(int width, int height, int channels = 3) {
  Image image(width, height, channels);
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  for (float& value : image.pixels) {
    state += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    value = std::ldexp(static_cast<float>(z & 0xFFFFFF), static_cast<int>((z >> 24) % 24) - 32);
  }
  return image;
}

TEST(Fp16Format, KnownValuesGiveKnownLittleEndianBytes) {
  EXPECT_EQ(stored_half(1.0f), 0x3C00u);
  {
    Image image(1, 1);
    image.texel(0, 0)[0] = 1.0f;
    const EncodedTexture texture = fp16().encode(image, defaults(), CodecContext{1, 1});
    EXPECT_EQ(texture.blocks[0], 0x00);   // low byte first
    EXPECT_EQ(texture.blocks[1], 0x3C);
  }
  EXPECT_EQ(stored_half(0.0f), 0x0000u);
  EXPECT_EQ(stored_half(0.5f), 0x3800u);
  EXPECT_EQ(stored_half(2.0f), 0x4000u);
  EXPECT_EQ(stored_half(65504.0f), 0x7BFFu);
  EXPECT_EQ(stored_half(std::ldexp(1.0f, -24)), 0x0001u);   // smallest subnormal half
  EXPECT_EQ(stored_half(std::ldexp(1.0f, -14)), 0x0400u);   // smallest normal half
}

TEST(Fp16Format, RoundsToNearestWithTiesToEven) {
  EXPECT_EQ(stored_half(1.0f + std::ldexp(1.0f, -11)), 0x3C00u);       // halfway 0x3C00/0x3C01: even is 0x3C00
  EXPECT_EQ(stored_half(1.0f + 3 * std::ldexp(1.0f, -11)), 0x3C02u);   // halfway 0x3C01/0x3C02: even is 0x3C02
  EXPECT_EQ(stored_half(1.0f + std::ldexp(1.0f, -11) + std::ldexp(1.0f, -20)), 0x3C01u);   // above halfway
  EXPECT_EQ(stored_half(std::ldexp(1.0f, -26)), 0x0000u);   // below half the smallest subnormal: 0
  EXPECT_EQ(stored_half(std::ldexp(3.0f, -26)), 0x0001u);   // 0.75 * 2^-24 rounds up to 2^-24
}

TEST(Fp16Format, ValuesAboveTheLargestHalfClampTo65504AndNeverInf) {
  EXPECT_EQ(stored_half(65519.0f), 0x7BFFu);
  EXPECT_EQ(stored_half(65520.0f), 0x7BFFu);   // round-to-nearest would give Inf here
  EXPECT_EQ(stored_half(1e30f), 0x7BFFu);
  EXPECT_EQ(stored_half(std::numeric_limits<float>::infinity()), 0x7BFFu);
}

TEST(Fp16Format, StoresTexelsInBcnOrderWithChannelsRgb) {
  Image image(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 3; ++c) image.texel(x, y)[c] = static_cast<float>(100 * (x + 4 * y) + c);
  const EncodedTexture texture = fp16().encode(image, defaults(), CodecContext{1, 1});
  ASSERT_EQ(texture.blocks.size(), 96u);
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 3; ++c) {
      const unsigned bits = texture.blocks[(3 * i + c) * 2] | (texture.blocks[(3 * i + c) * 2 + 1] << 8);
      EXPECT_EQ(bits, Imath::half(static_cast<float>(100 * i + c)).bits()) << "texel " << i << " channel " << c;
    }
}

TEST(Fp16Format, RoundTripsEveryFiniteHalfValueExactly) {
  // Every finite half: 31 exponents x 1024 mantissas x 2 signs = 63488 values (31744 of them non-negative).
  std::vector<float> values;
  for (unsigned bits = 0; bits < 0x10000u; ++bits) {
    if (!fp16_bits_are_finite(bits)) continue;
    Imath::half half_value;
    half_value.setBits(static_cast<unsigned short>(bits));
    values.push_back(static_cast<float>(half_value));
  }
  ASSERT_EQ(values.size(), 63488u);
  Image image(256, 248);   // 63488 texels
  const std::size_t count = values.size();
  for (std::size_t i = 0; i < count; ++i) {
    float* texel = &image.pixels[4 * i];
    texel[0] = values[i];                     // each channel sees every value once, at different positions
    texel[1] = values[(i + 1000) % count];
    texel[2] = values[(i + 31744) % count];
  }
  const EncodedTexture texture = fp16().encode(image, defaults(), CodecContext{2, 1});
  const Image decoded = fp16().decode(texture, CodecContext{2, 1});
  ASSERT_EQ(decoded.width, 256);
  ASSERT_EQ(decoded.height, 248);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    if (float_bits(image.pixels[i]) != float_bits(decoded.pixels[i])) ++mismatches;   // bits: -0 stays -0
  EXPECT_EQ(mismatches, 0u);
}

TEST(Fp16Format, NonMultipleOfFourSizesKeepTheirSizeAndDecodeTheTexelsInside) {
  for (const auto& size : {std::pair<int, int>{1, 1}, {5, 3}, {4, 5}, {7, 1}}) {
    SCOPED_TRACE(std::to_string(size.first) + "x" + std::to_string(size.second));
    Image image(size.first, size.second);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        for (int c = 0; c < 3; ++c) image.texel(x, y)[c] = 0.25f * static_cast<float>(1 + x + 8 * y + 64 * c);
    const EncodedTexture texture = fp16().encode(image, defaults(), CodecContext{1, 1});
    EXPECT_EQ(texture.width, size.first);
    EXPECT_EQ(texture.height, size.second);
    EXPECT_EQ(texture.blocks.size(), static_cast<std::size_t>((size.first + 3) / 4 * ((size.second + 3) / 4)) * 96u);
    const Image decoded = fp16().decode(texture, CodecContext{1, 1});
    ASSERT_EQ(decoded.width, size.first);
    ASSERT_EQ(decoded.height, size.second);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        for (int c = 0; c < 3; ++c) EXPECT_EQ(decoded.texel(x, y)[c], image.texel(x, y)[c]);
        EXPECT_EQ(decoded.texel(x, y)[3], 1.0f);
      }
  }
}

TEST(Fp16Format, OneByOneImageIsAConstantBlock) {
  Image image(1, 1);
  image.texel(0, 0)[0] = 3.0f;
  image.texel(0, 0)[1] = 0.125f;
  image.texel(0, 0)[2] = 1000.0f;
  const EncodedTexture texture = fp16().encode(image, defaults(), CodecContext{1, 1});
  for (int i = 1; i < 16; ++i)   // clamp-to-edge padding repeats texel 0
    EXPECT_EQ(0, std::memcmp(&texture.blocks[0], &texture.blocks[6 * i], 6)) << "texel " << i;
}

TEST(Fp16Format, OutputIsByteIdenticalAtOneTwoAndFourThreads) {
  const Image image = pattern_image(37, 23);
  const EncodedTexture one = fp16().encode(image, defaults(), CodecContext{1, 1});
  for (int threads : {2, 4}) {
    const EncodedTexture many = fp16().encode(image, defaults(), CodecContext{threads, 1});
    EXPECT_EQ(one.blocks, many.blocks) << threads << " threads";
    EXPECT_EQ(one.block_modes, many.block_modes);
    const Image decoded_one = fp16().decode(one, CodecContext{1, 1});
    const Image decoded_many = fp16().decode(one, CodecContext{threads, 1});
    EXPECT_EQ(0, std::memcmp(decoded_one.pixels.data(), decoded_many.pixels.data(),
                             decoded_one.pixels.size() * sizeof(float)));
  }
}

TEST(Fp16Format, RecordsSourceChannelsAndDropsAlpha) {
  Image rgba(2, 2, 4);
  rgba.texel(1, 1)[3] = 0.5f;
  const EncodedTexture texture = fp16().encode(rgba, defaults(), CodecContext{1, 1});
  EXPECT_EQ(texture.channels, 4);
  EXPECT_EQ(texture.block_modes, std::vector<std::uint8_t>(1, 0));
  const Image decoded = fp16().decode(texture, CodecContext{1, 1});
  EXPECT_EQ(decoded.channels, 3);
  EXPECT_EQ(decoded.texel(1, 1)[3], 1.0f);
  Image grey(2, 2, 1);
  EXPECT_EQ(fp16().decode(fp16().encode(grey, defaults(), CodecContext{1, 1}), CodecContext{1, 1}).channels, 1);
}

TEST(Fp16Format, EncodeRejectsNanNamingThePixel) {
  Image image(3, 2);
  image.texel(2, 1)[1] = std::numeric_limits<float>::quiet_NaN();
  try {
    fp16().encode(image, defaults(), CodecContext{2, 1});
    FAIL() << "NaN accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("fp16: pixel (2, 1) channel G is NaN"), std::string::npos)
        << error.what();
  }
}

TEST(Fp16Format, DecodeRejectsInfAndNanBitPatterns) {
  Image image(8, 4);
  EncodedTexture texture = fp16().encode(image, defaults(), CodecContext{1, 1});
  for (const unsigned bits : {0x7C00u, 0xFC00u, 0x7E00u, 0x7C01u}) {
    EncodedTexture corrupt = texture;
    corrupt.blocks[96 + 2 * 4] = static_cast<std::uint8_t>(bits & 0xFF);      // block 1, texel 1, channel G
    corrupt.blocks[96 + 2 * 4 + 1] = static_cast<std::uint8_t>(bits >> 8);
    try {
      fp16().decode(corrupt, CodecContext{2, 1});
      FAIL() << "bits " << bits << " accepted";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("fp16: block 1 texel 1 channel G holds a non-finite half"),
                std::string::npos)
          << error.what();
    }
  }
}

TEST(Fp16Format, DecodeRejectsInconsistentTextures) {
  const EncodedTexture good = fp16().encode(Image(5, 5), defaults(), CodecContext{1, 1});
  EncodedTexture short_data = good;
  short_data.blocks.pop_back();
  EXPECT_THROW(fp16().decode(short_data, CodecContext{1, 1}), Error);
  EncodedTexture wrong_block_bytes = good;
  wrong_block_bytes.block_bytes = 64;
  EXPECT_THROW(fp16().decode(wrong_block_bytes, CodecContext{1, 1}), Error);
  EncodedTexture wrong_format = good;
  wrong_format.format = "rgbe";
  EXPECT_THROW(fp16().decode(wrong_format, CodecContext{1, 1}), Error);
  EncodedTexture zero_width = good;
  zero_width.width = 0;
  EXPECT_THROW(fp16().decode(zero_width, CodecContext{1, 1}), Error);
  EncodedTexture bad_side_data = good;
  bad_side_data.side_data["scale"] = {1.0, std::numeric_limits<double>::infinity()};
  EXPECT_THROW(fp16().decode(bad_side_data, CodecContext{1, 1}), Error);
}

}  // namespace
}  // namespace blocklab
