// BC1 blocks (formats/bc1/bc1_block.h): the search-time decoder agrees bit for bit with the spec-literal oracle on
// 10^5 random blocks and on every block the encoder emits for real images; pack(unpack(b)) == b; the mode is
// decided on the packed words; canonical forms keep the decoded texels; the templated decoder works with Jet and
// Interval.
#include <gtest/gtest.h>

#include <ceres/jet.h>

#include "core/error.h"
#include "formats/bc1/bc1_block.h"
#include "formats/registry.h"
#include "test_s3tc_helpers.h"

namespace blocklab {
namespace {

using s3tc_test::float_bits;

void expect_same_texels(const BlockTexels& a, const BlockTexels& b, const std::string& context) {
  for (int texel = 0; texel < 16; ++texel)
    for (int c = 0; c < 4; ++c)
      ASSERT_EQ(float_bits(a.rgba[texel][c]), float_bits(b.rgba[texel][c]))
          << context << " texel " << texel << " channel " << c;
}

TEST(Bc1Block, RandomBlocksDecodeBitIdenticallyToTheReferenceDecoder) {
  const std::size_t count = 100000;
  const std::vector<std::uint8_t> blocks = s3tc_test::random_blocks(count, 8, 11);
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint8_t* block = blocks.data() + 8 * i;
    expect_same_texels(decode_bc1_params(unpack_bc1_block(block)), reference_decode_bc1_block(block),
                       "block " + std::to_string(i));
  }
}

TEST(Bc1Block, PackOfUnpackReproducesEveryRandomBlock) {
  const std::size_t count = 100000;
  const std::vector<std::uint8_t> blocks = s3tc_test::random_blocks(count, 8, 12);
  for (std::size_t i = 0; i < count; ++i) {
    std::uint8_t packed[8];
    pack_bc1_block(unpack_bc1_block(blocks.data() + 8 * i), packed);
    ASSERT_EQ(0, std::memcmp(packed, blocks.data() + 8 * i, 8)) << "block " << i;
  }
}

TEST(Bc1Block, FourColorBlockDecodesToExactThirds) {
  // color0 = white (0xFFFF) > color1 = black (0x0000); codes 0, 1, 2, 3 in texels 0..3 (index word 0b11100100).
  const std::uint8_t block[8] = {0xFF, 0xFF, 0x00, 0x00, 0xE4, 0x00, 0x00, 0x00};
  const BlockTexels texels = reference_decode_bc1_block(block);
  EXPECT_EQ(texels.rgba[0][0], 1.0f);
  EXPECT_EQ(texels.rgba[1][1], 0.0f);
  EXPECT_EQ(texels.rgba[2][2], static_cast<float>(510.0 / 765.0));
  EXPECT_EQ(texels.rgba[3][0], static_cast<float>(255.0 / 765.0));
  EXPECT_EQ(texels.rgba[3][3], 1.0f);   // opaque
  EXPECT_EQ(unpack_bc1_block(block).mode, Bc1Mode::four_color);
}

TEST(Bc1Block, ThreeColorBlockHasMidpointAndOpaqueBlack) {
  // color0 = 0x0000 <= color1 = 0xFFFF; codes 0, 1, 2, 3.
  const std::uint8_t block[8] = {0x00, 0x00, 0xFF, 0xFF, 0xE4, 0x00, 0x00, 0x00};
  const BlockTexels texels = decode_bc1_params(unpack_bc1_block(block));
  EXPECT_EQ(texels.rgba[2][0], 0.5f);
  EXPECT_EQ(texels.rgba[3][0], 0.0f);
  EXPECT_EQ(texels.rgba[3][1], 0.0f);
  EXPECT_EQ(texels.rgba[3][3], 1.0f);
}

TEST(Bc1Block, ModeIsDecidedOnPackedWordsAndEqualWordsAreThreeColor) {
  // Equal endpoints: 3-colour mode, so code 3 is black, not the endpoint colour.
  const std::uint8_t equal[8] = {0x34, 0x12, 0x34, 0x12, 0xFF, 0xFF, 0xFF, 0xFF};
  EXPECT_EQ(unpack_bc1_block(equal).mode, Bc1Mode::three_color);
  EXPECT_EQ(reference_decode_bc1_block(equal).rgba[5][0], 0.0f);
  // 0x8000 (R = 16) > 0x07FF (G = 63, B = 31) as words although the second is brighter in G and B.
  const std::uint8_t ordered[8] = {0x00, 0x80, 0xFF, 0x07, 0, 0, 0, 0};
  EXPECT_EQ(unpack_bc1_block(ordered).mode, Bc1Mode::four_color);
}

TEST(Bc1Block, ExpansionIsBitReplication) {
  for (int v = 0; v < 32; ++v) {
    EXPECT_EQ(expand_5bit(v), (v << 3) | (v >> 2));
    EXPECT_EQ(expand_565_scalar(static_cast<double>(v), 0), static_cast<double>(expand_5bit(v)));
  }
  for (int v = 0; v < 64; ++v) EXPECT_EQ(expand_565_scalar(static_cast<double>(v), 1), static_cast<double>(expand_6bit(v)));
  EXPECT_EQ(expand_5bit(3), 24);   // round(3 * 255 / 31) would be 25 (SPECS.md 2.1)
}

TEST(Bc1Block, CanonicalFormsPackAndDecodeLikeTheOriginalParams) {
  std::mt19937_64 random(13);
  for (int trial = 0; trial < 20000; ++trial) {
    Bc1Params params;
    for (int e = 0; e < 2; ++e)
      for (int c = 0; c < 3; ++c)
        params.endpoints[e][c] = static_cast<int>(random() % (trial % 7 == 0 ? 2 : rgb565_channel_max(c) + 1));
    for (auto& index : params.indices) index = static_cast<std::uint8_t>(random() % 4);
    params.mode = (random() & 1) ? Bc1Mode::four_color : Bc1Mode::three_color;
    const BlockTexels expected = decode_bc1_params(params);   // the params' own palette, whatever the order
    const Bc1Params canonical = canonicalise_bc1(params);
    std::uint8_t packed[8];
    ASSERT_NO_THROW(pack_bc1_block(canonical, packed)) << "trial " << trial;
    expect_same_texels(reference_decode_bc1_block(packed), expected, "trial " + std::to_string(trial));
    // BC3 colour: always 4-colour; only four_color params are meaningful there.
    if (params.mode == Bc1Mode::four_color) {
      const Bc1Params bc3 = canonicalise_bc3_color(params);
      EXPECT_TRUE(bc1_endpoint_word(bc3, 0) > bc1_endpoint_word(bc3, 1) ||
                  (bc1_endpoint_word(bc3, 0) == bc1_endpoint_word(bc3, 1) &&
                   bc3.indices == std::array<std::uint8_t, 16>{}));
      expect_same_texels(decode_bc1_params(bc3), expected, "bc3 trial " + std::to_string(trial));
    }
  }
}

TEST(Bc1Block, PackRejectsAModeThatDisagreesWithTheEndpointOrder) {
  Bc1Params params;
  params.endpoints = {{{1, 2, 3}, {4, 5, 6}}};   // word0 < word1
  params.mode = Bc1Mode::four_color;
  std::uint8_t packed[8];
  EXPECT_THROW(pack_bc1_block(params, packed), Error);
  params.endpoints[0][0] = 32;   // out of range
  params.mode = Bc1Mode::three_color;
  EXPECT_THROW(pack_bc1_block(params, packed), Error);
}

TEST(Bc1Block, TemplatedDecoderAgreesForJetAndInterval) {
  const std::vector<std::uint8_t> blocks = s3tc_test::random_blocks(200, 8, 14);
  using Jet = ceres::Jet<double, 6>;
  for (std::size_t i = 0; i < 200; ++i) {
    const Bc1Params params = unpack_bc1_block(blocks.data() + 8 * i);
    double e0[3], e1[3], rgb[16][3];
    Jet j0[3], j1[3], jet_rgb[16][3];
    Interval i0[3], i1[3], interval_rgb[16][3];
    for (int c = 0; c < 3; ++c) {
      e0[c] = params.endpoints[0][c];
      e1[c] = params.endpoints[1][c];
      j0[c] = Jet(e0[c], c);
      j1[c] = Jet(e1[c], 3 + c);
      i0[c] = Interval(e0[c]);
      i1[c] = Interval(e1[c]);
    }
    bc1_decode(e0, e1, params.mode, params.indices, rgb);
    bc1_decode(j0, j1, params.mode, params.indices, jet_rgb);
    bc1_decode(i0, i1, params.mode, params.indices, interval_rgb);
    for (int texel = 0; texel < 16; ++texel)
      for (int c = 0; c < 3; ++c) {
        EXPECT_DOUBLE_EQ(jet_rgb[texel][c].a, rgb[texel][c]);   // ceres divides as a * (1 / b): within 4 ulp
        EXPECT_LE(interval_rgb[texel][c].lower(), rgb[texel][c]);
        EXPECT_GE(interval_rgb[texel][c].upper(), rgb[texel][c]);
      }
  }
}

TEST(Bc1Block, EncoderOutputOnRealImagesDecodesBitIdenticallyToTheReference) {
  const std::vector<Image> crops = s3tc_test::real_crops();
  if (crops.empty()) GTEST_SKIP() << "shared LDR images not found under " << BLOCKLAB_TEST_SHARED_DATA;
  const Format& bc1 = find_format("bc1");
  for (const std::string search : {"fast", "default", "exhaustive"}) {
    const FormatOptions options = resolve_format_options(bc1, {{"search", search}});
    for (const Image& crop : crops) {
      const EncodedTexture texture = bc1.encode(crop, options, CodecContext{0, 1});
      const Image decoded = bc1.decode(texture, CodecContext{0, 1});
      const BlockGrid grid(crop.width, crop.height);
      Image reference(crop.width, crop.height, decoded.channels);
      for (std::size_t b = 0; b < grid.block_count(); ++b) {
        const std::uint8_t* block = texture.blocks.data() + 8 * b;
        std::uint8_t repacked[8];
        pack_bc1_block(unpack_bc1_block(block), repacked);
        ASSERT_EQ(0, std::memcmp(repacked, block, 8));
        store_block(reference, grid, b, reference_decode_bc1_block(block));
      }
      for (std::size_t i = 0; i < decoded.pixels.size(); ++i)
        ASSERT_EQ(float_bits(decoded.pixels[i]), float_bits(reference.pixels[i])) << search << " sample " << i;
    }
  }
}

}  // namespace
}  // namespace blocklab
