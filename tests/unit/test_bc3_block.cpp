// BC3 blocks and the `bc3` format (formats/bc3): decoder == oracle bit for bit on 10^5 random blocks (colour always
// 4-colour, whatever the endpoint order) and on encoder output for real images, pack(unpack(b)) == b, the encoder's
// colour blocks always in the portable form (color0 > color1, or equal with all codes 0), alpha encoded.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "formats/bc3/bc3_block.h"
#include "formats/registry.h"
#include "test_s3tc_helpers.h"

namespace blocklab {
namespace {

using s3tc_test::float_bits;

TEST(Bc3Block, RandomBlocksDecodeBitIdenticallyToTheReferenceDecoder) {
  const std::size_t count = 100000;
  const std::vector<std::uint8_t> blocks = s3tc_test::random_blocks(count, 16, 31);
  for (std::size_t i = 0; i < count; ++i) {
    const BlockTexels fast = decode_bc3_params(unpack_bc3_block(blocks.data() + 16 * i));
    const BlockTexels oracle = reference_decode_bc3_block(blocks.data() + 16 * i);
    for (int t = 0; t < 16; ++t)
      for (int c = 0; c < 4; ++c) ASSERT_EQ(float_bits(fast.rgba[t][c]), float_bits(oracle.rgba[t][c])) << i;
  }
}

TEST(Bc3Block, PackOfUnpackReproducesEveryRandomBlock) {
  const std::size_t count = 100000;
  const std::vector<std::uint8_t> blocks = s3tc_test::random_blocks(count, 16, 32);
  for (std::size_t i = 0; i < count; ++i) {
    std::uint8_t packed[16];
    pack_bc3_block(unpack_bc3_block(blocks.data() + 16 * i), packed);
    ASSERT_EQ(0, std::memcmp(packed, blocks.data() + 16 * i, 16)) << "block " << i;
  }
}

TEST(Bc3Block, ColourIsFourColourEvenWhenColor0IsNotGreater) {
  // color0 = 0x0000 <= color1 = 0xFFFF: BC1 would give black for code 3; BC3 gives (C0 + 2 C1) / 3.
  std::uint8_t block[16] = {255, 255, 0, 0, 0, 0, 0, 0, 0x00, 0x00, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
  const BlockTexels texels = reference_decode_bc3_block(block);
  EXPECT_EQ(texels.rgba[0][0], static_cast<float>(510.0 / 765.0));
  EXPECT_EQ(texels.rgba[0][3], 1.0f);   // 6-value alpha mode (255 <= 255), code 0 = 255
}

TEST(Bc3Format, EncoderWritesPortableColourBlocksAndKeepsAlphaOnRealImages) {
  std::vector<Image> crops = s3tc_test::real_crops();
  if (crops.empty()) GTEST_SKIP() << "shared LDR images not found under " << BLOCKLAB_TEST_SHARED_DATA;
  const Format& bc3 = find_format("bc3");
  for (const std::string search : {"fast", "default", "exhaustive"}) {
    const FormatOptions options = resolve_format_options(bc3, {{"search", search}});
    for (const Image& crop : crops) {
      const EncodedTexture texture = bc3.encode(crop, options, CodecContext{0, 1});
      EXPECT_EQ(texture.blocks, bc3.encode(crop, options, CodecContext{1, 1}).blocks);
      const Image decoded = bc3.decode(texture, CodecContext{0, 1});
      EXPECT_EQ(decoded.channels, crop.channels);
      const BlockGrid grid(crop.width, crop.height);
      Image reference(crop.width, crop.height, crop.channels);
      for (std::size_t b = 0; b < grid.block_count(); ++b) {
        const std::uint8_t* block = texture.blocks.data() + 16 * b;
        const Bc1Params color = unpack_bc3_block(block).color;
        const unsigned word0 = bc1_endpoint_word(color, 0), word1 = bc1_endpoint_word(color, 1);
        ASSERT_TRUE(word0 > word1 || (word0 == word1 && color.indices == std::array<std::uint8_t, 16>{})) << b;
        BlockTexels texels = reference_decode_bc3_block(block);
        if (crop.channels != 4)
          for (auto& t : texels.rgba) t[3] = 1.0f;
        store_block(reference, grid, b, texels);
      }
      for (std::size_t i = 0; i < decoded.pixels.size(); ++i)
        ASSERT_EQ(float_bits(decoded.pixels[i]), float_bits(reference.pixels[i])) << search << " sample " << i;
      if (crop.channels == 4) {
        double sum = 0;
        for (std::size_t i = 0; i < crop.texel_count(); ++i)
          sum += std::pow(255.0 * (decoded.pixels[i * 4 + 3] - crop.pixels[i * 4 + 3]), 2);
        EXPECT_LT(sum / crop.texel_count(), 30.0);
      }
    }
  }
}

}  // namespace
}  // namespace blocklab
