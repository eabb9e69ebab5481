// BC6H fuzz (formats/bc6h): fully random 128-bit blocks, so every mode number including the reserved ones (19, 23,
// 27, 31) and every field value occurs; the fast decoder decode(unpack(bytes)) must equal the spec-literal oracle
// bit for bit for UF16 and SF16, and the format's decode of a random texture must not throw.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "formats/bc6h/bc6h_decode.h"
#include "formats/bc6h/bc6h_params.h"
#include "formats/bc6h/bc6h_reference_decode.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

TEST(Bc6hFuzz, RandomBlocksDecodeIdenticallyInTheFastDecoderAndTheOracle) {
  std::mt19937_64 random(20261127);
  int per_mode[bc6h::kModeCount + 1] = {};
  for (int trial = 0; trial < 100000; ++trial) {
    std::uint8_t bytes[16];
    for (auto& byte : bytes) byte = static_cast<std::uint8_t>(random());
    const bc6h::Params params = bc6h::unpack(bytes);
    ++per_mode[params.mode_index + 1];
    for (const bool is_signed : {false, true}) {
      std::uint16_t fast[16][3], oracle[16][3];
      bc6h::decode(params, is_signed, fast);
      bc6h::reference_decode(bytes, is_signed, oracle);
      ASSERT_EQ(std::memcmp(fast, oracle, sizeof fast), 0) << "trial " << trial << (is_signed ? " SF16" : " UF16");
      if (params.mode_index == bc6h::kReservedModeIndex) {
        for (auto& texel : fast) EXPECT_TRUE(texel[0] == 0 && texel[1] == 0 && texel[2] == 0);
      }
    }
  }
  for (int m = 0; m <= bc6h::kModeCount; ++m) EXPECT_GT(per_mode[m], 0) << "mode slot " << m << " never drawn";
}

TEST(Bc6hFuzz, RandomTexturesDecodeWithoutErrorsToFiniteOrNegativeInfinityValues) {
  std::mt19937_64 random(7);
  for (const char* name : {"bc6h", "bc6h_sf"}) {
    const Format& format = find_format(name);
    EncodedTexture texture;
    texture.format = name;
    texture.options = resolve_format_options(format, {});
    texture.width = 37;
    texture.height = 21;
    texture.channels = 3;
    texture.block_bytes = 16;
    texture.blocks.resize(10 * 6 * 16);
    for (auto& byte : texture.blocks) byte = static_cast<std::uint8_t>(random());
    const Image decoded = format.decode(texture, CodecContext{2, 1});
    for (std::size_t i = 0; i < decoded.texel_count(); ++i)
      for (int c = 0; c < 3; ++c) {
        const float value = decoded.pixels[i * 4 + c];
        EXPECT_FALSE(std::isnan(value));
        // Only SF16's -0x8000 interpolant gives an infinity, and only the negative one.
        if (std::isinf(value)) {
          EXPECT_TRUE(value < 0 && std::string(name) == "bc6h_sf");
        }
      }
  }
}

}  // namespace
}  // namespace blocklab
