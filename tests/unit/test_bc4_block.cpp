// BC4 blocks and the `bc4` format (formats/bc4): decoder == oracle bit for bit on 10^5 random blocks and on encoder
// output for real images, pack(unpack(b)) == b, both modes with their constants, canonical forms, search levels
// ordered by error (exhaustive = the true optimum over all 256 x 256 pairs), the channel option.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.h"
#include "formats/bc4/bc4_block.h"
#include "formats/bc4/bc4_encoder.h"
#include "formats/common/s3tc_endpoint_problem.h"
#include "formats/registry.h"
#include "test_s3tc_helpers.h"

namespace blocklab {
namespace {

using s3tc_test::float_bits;

TEST(Bc4Block, RandomBlocksDecodeBitIdenticallyToTheReferenceDecoder) {
  const std::size_t count = 100000;
  const std::vector<std::uint8_t> blocks = s3tc_test::random_blocks(count, 8, 21);
  for (std::size_t i = 0; i < count; ++i) {
    const std::array<float, 16> fast = decode_bc4_params(unpack_bc4_block(blocks.data() + 8 * i));
    const std::array<float, 16> oracle = reference_decode_bc4_block(blocks.data() + 8 * i);
    for (int t = 0; t < 16; ++t) ASSERT_EQ(float_bits(fast[t]), float_bits(oracle[t])) << "block " << i << " texel " << t;
  }
}

TEST(Bc4Block, PackOfUnpackReproducesEveryRandomBlock) {
  const std::size_t count = 100000;
  const std::vector<std::uint8_t> blocks = s3tc_test::random_blocks(count, 8, 22);
  for (std::size_t i = 0; i < count; ++i) {
    std::uint8_t packed[8];
    pack_bc4_block(unpack_bc4_block(blocks.data() + 8 * i), packed);
    ASSERT_EQ(0, std::memcmp(packed, blocks.data() + 8 * i, 8)) << "block " << i;
  }
}

TEST(Bc4Block, EightValueAndSixValueModesDecodeToExactFractionsAndConstants) {
  // Codes 0..7 in texels 0..7: 3-bit fields 0,1,2,...,7 -> 48-bit word 0o76543210.
  const std::uint64_t field = 076543210ull;
  std::uint8_t block[8] = {70, 0};
  for (int b = 0; b < 6; ++b) block[2 + b] = static_cast<std::uint8_t>((field >> (8 * b)) & 0xFF);
  std::array<float, 16> values = reference_decode_bc4_block(block);
  EXPECT_EQ(values[0], static_cast<float>(70 / 255.0));
  EXPECT_EQ(values[2], static_cast<float>(420 / (7 * 255.0)));   // (6 * 70 + 0) / 7
  EXPECT_EQ(values[7], static_cast<float>(70 / (7 * 255.0)));    // (70 + 6 * 0) / 7
  block[0] = 0;
  block[1] = 50;   // red0 <= red1: 6-value mode
  values = reference_decode_bc4_block(block);
  EXPECT_EQ(values[2], static_cast<float>(50 / (5 * 255.0)));
  EXPECT_EQ(values[6], 0.0f);
  EXPECT_EQ(values[7], 1.0f);
}

TEST(Bc4Block, CanonicalFormsPackAndDecodeLikeTheOriginalParams) {
  std::mt19937_64 random(23);
  for (int trial = 0; trial < 20000; ++trial) {
    Bc4Params params;
    params.endpoints = {static_cast<int>(random() % 256), static_cast<int>(trial % 5 == 0 ? random() % 2 : random() % 256)};
    for (auto& index : params.indices) index = static_cast<std::uint8_t>(random() % 8);
    params.mode = (random() & 1) ? Bc4Mode::eight_value : Bc4Mode::six_value;
    const std::array<float, 16> expected = decode_bc4_params(params);
    std::uint8_t packed[8];
    ASSERT_NO_THROW(pack_bc4_block(canonicalise_bc4(params), packed));
    const std::array<float, 16> decoded = reference_decode_bc4_block(packed);
    for (int t = 0; t < 16; ++t) ASSERT_EQ(float_bits(decoded[t]), float_bits(expected[t])) << trial;
  }
}

TEST(Bc4Block, PackRejectsInconsistentModeAndOutOfRangeFields) {
  Bc4Params params;
  params.endpoints = {10, 20};
  params.mode = Bc4Mode::eight_value;
  std::uint8_t packed[8];
  EXPECT_THROW(pack_bc4_block(params, packed), Error);
  params.mode = Bc4Mode::six_value;
  params.indices[3] = 8;
  EXPECT_THROW(pack_bc4_block(params, packed), Error);
}

TEST(Bc4Encoder, ExhaustiveFindsTheTrueOptimumAndDefaultAndFastAreNoBetter) {
  std::mt19937_64 random(24);
  for (int trial = 0; trial < 12; ++trial) {
    float values[16];
    for (float& v : values) v = static_cast<float>(random() % 256);
    if (trial % 3 == 0) values[0] = 0.0f, values[1] = 255.0f;   // extremes favour the 6-value mode
    float brute = 1e30f;
    for (int a = 0; a < 256; ++a)
      for (int b = 0; b < 256; ++b)
        brute = std::min(brute, evaluate_bc4_candidate(values, a, b, a > b ? Bc4Mode::eight_value : Bc4Mode::six_value, nullptr));
    float errors[3];
    const S3tcSearch levels[3] = {S3tcSearch::fast, S3tcSearch::standard, S3tcSearch::exhaustive};
    for (int level = 0; level < 3; ++level) {
      const Bc4Params params = fit_bc4_block(values, levels[level]);
      errors[level] = evaluate_bc4_candidate(values, params.endpoints[0], params.endpoints[1], params.mode, nullptr);
    }
    EXPECT_FLOAT_EQ(errors[2], brute) << trial;
    EXPECT_LE(errors[2], errors[1]);
    EXPECT_LE(errors[1], errors[0]);
  }
}

TEST(Bc4Encoder, EndpointProblemErrorEqualsTheEncoderError) {
  const float values[16] = {0, 3, 9, 27, 81, 243, 200, 150, 100, 50, 25, 12, 6, 255, 128, 64};
  const Bc4Params params = fit_bc4_block(values, S3tcSearch::standard);
  Bc4EndpointError error;
  error.mode = params.mode;
  for (int t = 0; t < 16; ++t) error.targets[t] = values[t] / 255.0;
  const auto problem = make_bc4_endpoint_problem(error);
  const double x[2] = {static_cast<double>(params.endpoints[0]), static_cast<double>(params.endpoints[1])};
  const double encoder_error =
      evaluate_bc4_candidate(values, params.endpoints[0], params.endpoints[1], params.mode, nullptr) / (255.0 * 255.0);
  EXPECT_NEAR(problem.eval(x), encoder_error, 1e-6);
}

TEST(Bc4Format, EncodesTheChosenChannelAndDecodesGreyOnRealImages) {
  std::vector<Image> crops = s3tc_test::real_crops();
  if (crops.empty()) GTEST_SKIP() << "shared LDR images not found under " << BLOCKLAB_TEST_SHARED_DATA;
  const Format& bc4 = find_format("bc4");
  for (const std::string channel : {"r", "g", "a"}) {
    const FormatOptions options = resolve_format_options(bc4, {{"channel", channel}});
    for (const Image& crop : crops) {
      const EncodedTexture texture = bc4.encode(crop, options, CodecContext{0, 1});
      EXPECT_EQ(texture.blocks, bc4.encode(crop, options, CodecContext{1, 1}).blocks);
      const Image decoded = bc4.decode(texture, CodecContext{0, 1});
      ASSERT_EQ(decoded.channels, 1);
      const BlockGrid grid(crop.width, crop.height);
      for (std::size_t b = 0; b < grid.block_count(); ++b) {
        const std::array<float, 16> oracle = reference_decode_bc4_block(texture.blocks.data() + 8 * b);
        const int x0 = static_cast<int>(b % grid.blocks_x) * 4, y0 = static_cast<int>(b / grid.blocks_x) * 4;
        for (int t = 0; t < 16; ++t) {
          const int x = x0 + t % 4, y = y0 + t / 4;
          if (x >= crop.width || y >= crop.height) continue;
          ASSERT_EQ(float_bits(decoded.texel(x, y)[0]), float_bits(oracle[t]));
          ASSERT_EQ(decoded.texel(x, y)[1], decoded.texel(x, y)[0]);
        }
      }
      // The stored channel is close to the source (BC4 error is small on 8-bit data).
      const int c = channel == "r" ? 0 : channel == "g" ? 1 : 3;
      double sum = 0;
      for (std::size_t i = 0; i < crop.texel_count(); ++i) sum += std::pow(255.0 * (decoded.pixels[i * 4] - crop.pixels[i * 4 + c]), 2);
      EXPECT_LT(sum / crop.texel_count(), 30.0) << channel;
    }
  }
}

}  // namespace
}  // namespace blocklab
