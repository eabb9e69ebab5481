// BC7 robustness: random bits never crash any decoder (fast, reference, Format::decode), random images of odd sizes
// and random alpha encode to blocks both decoders agree on. Meant to run under ASan/UBSan as well.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "formats/bc7/bc7_decode.h"
#include "formats/bc7/bc7_reference_decode.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

TEST(Bc7Fuzz, RandomBitsNeverCrashAnyDecoder) {
  std::mt19937_64 random(99);
  const Format& bc7 = find_format("bc7");
  EncodedTexture texture;
  texture.format = "bc7";
  texture.options = resolve_format_options(bc7, {});
  texture.width = 13;
  texture.height = 9;
  texture.channels = 4;
  texture.block_bytes = 16;
  texture.blocks.resize(4 * 3 * 16);
  for (int round = 0; round < 3000; ++round) {
    for (auto& byte : texture.blocks) byte = static_cast<std::uint8_t>(random());
    const Image image = bc7.decode(texture, {1, 1});
    ASSERT_EQ(image.width, 13);
    for (std::size_t block = 0; block < 12; ++block) {
      std::uint8_t reference[16][4], fast[16][4];
      bc7::reference_decode(texture.blocks.data() + block * 16, reference);
      bc7::decode(bc7::unpack(texture.blocks.data() + block * 16), fast);
      ASSERT_EQ(std::memcmp(reference, fast, sizeof fast), 0);
    }
  }
}

TEST(Bc7Fuzz, RandomImagesEncodeToBlocksBothDecodersAgreeOn) {
  std::mt19937 random(4);
  const Format& bc7 = find_format("bc7");
  for (int round = 0; round < 12; ++round) {
    const int width = 1 + random() % 23, height = 1 + random() % 19;
    const int channels = (round % 3 == 0) ? 1 : (round % 3 == 1 ? 3 : 4);
    Image image(width, height, channels);
    for (std::size_t i = 0; i < image.texel_count(); ++i)
      for (int c = 0; c < 4; ++c) {
        // Mix of extremes, random values and out-of-range values (clamped by the encoder).
        const int kind = random() % 8;
        image.pixels[i * 4 + c] = kind == 0 ? 0.0f : kind == 1 ? 1.0f : kind == 2 ? 3.0f : (random() % 1000) / 999.0f;
        if (channels == 1 && c > 0 && c < 3) image.pixels[i * 4 + c] = image.pixels[i * 4];
        if (channels != 4 && c == 3) image.pixels[i * 4 + c] = 1.0f;
      }
    const char* preset = round % 2 ? "thorough" : "fast";
    const EncodedTexture texture = bc7.encode(image, resolve_format_options(bc7, {{"preset", preset}}), {});
    for (std::size_t block = 0; block * 16 < texture.blocks.size(); ++block) {
      std::uint8_t reference[16][4], fast[16][4];
      bc7::reference_decode(texture.blocks.data() + block * 16, reference);
      bc7::decode(bc7::unpack(texture.blocks.data() + block * 16), fast);
      ASSERT_EQ(std::memcmp(reference, fast, sizeof fast), 0);
    }
    const Image decoded = bc7.decode(texture, {});
    EXPECT_EQ(decoded.width, width);
    EXPECT_EQ(decoded.channels, channels);
  }
}

}  // namespace
}  // namespace blocklab
