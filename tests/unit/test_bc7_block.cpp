// BC7 block layer (formats/bc7): the fast decoder decode(unpack(b)) agrees bit for bit with the spec-literal
// reference_decode on 10^6 random 128-bit blocks covering every mode, pack(unpack(b)) == b for every non-reserved
// block, hand-made blocks decode to hand-computed values, and pack rejects values that do not fit.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <random>

#include "core/error.h"
#include "formats/bc7/bc7_decode.h"
#include "formats/bc7/bc7_params.h"
#include "formats/bc7/bc7_reference_decode.h"

namespace blocklab {
namespace bc7 {
namespace {

using Block = std::array<std::uint8_t, 16>;

Block random_block(std::mt19937_64& random) {
  Block block;
  const std::uint64_t low = random(), high = random();
  for (int i = 0; i < 8; ++i) {
    block[i] = static_cast<std::uint8_t>(low >> (8 * i));
    block[8 + i] = static_cast<std::uint8_t>(high >> (8 * i));
  }
  return block;
}

// Random block whose mode is `mode` (the low mode+1 bits of byte 0 forced to the mode pattern).
Block random_block_of_mode(std::mt19937_64& random, int mode) {
  Block block = random_block(random);
  const unsigned mask = (2u << mode) - 1u;
  block[0] = static_cast<std::uint8_t>((block[0] & ~mask) | (1u << mode));
  return block;
}

bool fast_equals_reference(const Block& block) {
  std::uint8_t reference[16][4];
  reference_decode(block.data(), reference);
  std::uint8_t fast[16][4];
  decode(unpack(block.data()), fast);
  return std::memcmp(reference, fast, sizeof fast) == 0;
}

TEST(Bc7Block, FastDecoderMatchesReferenceOnAMillionRandomBlocks) {
  std::mt19937_64 random(20240611);
  int mode_counts[9] = {};
  int mismatches = 0;
  for (int n = 0; n < 1000000; ++n) {
    // Uniform random bytes give mode 0 half the time; every 4th block is forced to a uniformly chosen mode so
    // that every mode is well represented.
    const Block block = (n % 4 == 0) ? random_block_of_mode(random, static_cast<int>(random() % 8)) : random_block(random);
    ++mode_counts[mode_of_first_byte(block[0])];
    if (!fast_equals_reference(block)) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0);
  for (int mode = 0; mode <= kReservedMode; ++mode) EXPECT_GT(mode_counts[mode], 0) << "mode " << mode;
  EXPECT_GT(mode_counts[7], 10000);
}

TEST(Bc7Block, PackOfUnpackReproducesEveryNonReservedBlock) {
  std::mt19937_64 random(7);
  for (int n = 0; n < 200000; ++n) {
    const Block block = random_block_of_mode(random, n % 8);
    const Params params = unpack(block.data());
    Block packed{};
    pack(params, packed.data());
    ASSERT_EQ(packed, block) << "mode " << n % 8;
    EXPECT_EQ(unpack(packed.data()), params);
  }
}

TEST(Bc7Block, ReservedModeDecodesToZeroInAllChannels) {
  std::mt19937_64 random(3);
  for (int n = 0; n < 100; ++n) {
    Block block = random_block(random);
    block[0] = 0;
    std::uint8_t reference[16][4];
    reference_decode(block.data(), reference);
    std::uint8_t fast[16][4];
    const Params params = unpack(block.data());
    EXPECT_EQ(params.mode, kReservedMode);
    decode(params, fast);
    for (int i = 0; i < 16; ++i)
      for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(reference[i][c], 0);
        EXPECT_EQ(fast[i][c], 0);
      }
  }
  Params reserved;
  Block out{};
  EXPECT_THROW(pack(reserved, out.data()), Error);
}

TEST(Bc7Block, HandMadeMode6BlockDecodesToHandComputedValues) {
  // Mode 6: 7-bit RGBA endpoints + P-bit per endpoint, 4-bit indices. E0 code 0 with P 0 -> 0; E1 code 127 with
  // P 1 -> 255. Index k decodes to ((64 - w) * 0 + w * 255 + 32) >> 6 with w the 4-bit weight of k.
  Params params;
  params.mode = 6;
  for (int c = 0; c < 4; ++c) {
    params.endpoints[0][0][c] = 0;
    params.endpoints[0][1][c] = 127;
  }
  params.pbits[0][0] = 0;
  params.pbits[0][1] = 1;
  for (int i = 0; i < 16; ++i) params.indices[i] = static_cast<std::uint8_t>(i == 0 ? 0 : i);   // anchor < 8
  Block block{};
  pack(params, block.data());
  EXPECT_EQ(block[0], 0x40);   // mode 6: six zero bits then a one
  std::uint8_t reference[16][4];
  reference_decode(block.data(), reference);
  const int weights[16] = {0, 4, 9, 13, 17, 21, 26, 30, 34, 38, 43, 47, 51, 55, 60, 64};
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(reference[i][c], (weights[i] * 255 + 32) >> 6) << "texel " << i;
  EXPECT_EQ(reference[15][0], 255);
  EXPECT_EQ(reference[5][0], 84);   // (21 * 255 + 32) >> 6 = 5387 >> 6 = 84
}

TEST(Bc7Block, RotationSwapsAlphaWithTheNamedChannelAfterInterpolation) {
  // Mode 5, constant block: colour endpoints (10, 20, 30) -> 7-bit codes expand by replication; alpha 8-bit 200.
  for (int rotation = 0; rotation < 4; ++rotation) {
    Params params;
    params.mode = 5;
    params.rotation = rotation;
    params.endpoints[0][0][0] = params.endpoints[0][1][0] = 5;    // 5 << 1 | 0 = 10
    params.endpoints[0][0][1] = params.endpoints[0][1][1] = 10;   // 20
    params.endpoints[0][0][2] = params.endpoints[0][1][2] = 15;   // 30
    params.endpoints[0][0][3] = params.endpoints[0][1][3] = 200;
    Block block{};
    pack(params, block.data());
    std::uint8_t out[16][4];
    reference_decode(block.data(), out);
    int expected[4] = {10, 20, 30, 200};
    if (rotation > 0) std::swap(expected[3], expected[rotation - 1]);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(out[7][c], expected[c]) << "rotation " << rotation << " channel " << c;
    EXPECT_TRUE(fast_equals_reference(block));
  }
}

TEST(Bc7Block, PackRejectsFieldsThatDoNotFit) {
  Block out{};
  Params params;
  params.mode = 1;
  params.partition = 64;   // 6 bits
  EXPECT_THROW(pack(params, out.data()), Error);
  params.partition = 0;
  params.endpoints[0][0][0] = 64;   // mode 1 colour: 6 bits
  EXPECT_THROW(pack(params, out.data()), Error);
  params.endpoints[0][0][0] = 0;
  params.indices[0] = 4;   // anchor of subset 0 stores 2 of 3 bits
  EXPECT_THROW(pack(params, out.data()), Error);
  params.indices[0] = 0;
  params.pbits[1][0] = 1;   // mode 1 shares one P-bit per subset
  params.pbits[1][1] = 0;
  EXPECT_THROW(pack(params, out.data()), Error);
  params.pbits[1][1] = 1;
  EXPECT_NO_THROW(pack(params, out.data()));
  try {
    params.indices[15] = 9;
    pack(params, out.data());
    FAIL() << "expected an Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("index"), std::string::npos) << error.what();
  }
}

TEST(Bc7Block, SwappingEndpointsAndMirroringIndicesDecodesIdentically) {
  // The property the encoder's anchor fix relies on: w[2^b - 1 - i] = 64 - w[i] for every index size.
  for (int bits = 2; bits <= 4; ++bits) {
    const int* weights = index_weights(bits);
    for (int i = 0; i < (1 << bits); ++i) EXPECT_EQ(weights[(1 << bits) - 1 - i], 64 - weights[i]);
    for (int e0 = 0; e0 < 256; e0 += 5)
      for (int e1 = 0; e1 < 256; e1 += 7)
        for (int i = 0; i < (1 << bits); ++i)
          ASSERT_EQ(interpolate(e0, e1, weights[i]), interpolate(e1, e0, weights[(1 << bits) - 1 - i]));
  }
}

}  // namespace
}  // namespace bc7
}  // namespace blocklab
