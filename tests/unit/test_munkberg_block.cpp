// `munkberg` blocks (formats/munkberg/munkberg_block.h): pack(unpack(b)) == b for random blocks; the templated
// decoder agrees bit for bit with the spec-literal reference decoder on random blocks; hand-built blocks decode to the
// documented values (true black of eq. 3, log-luminance interpolation, shape II's shared pair indices, landmarks of
// the shape); pack rejects out-of-range fields naming them; decode_block<T> works with Interval (enclosing the double
// decode) and Jet (same value).
#include <gtest/gtest.h>

#include "test_float_bits.h"

#include <ceres/jet.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/error.h"
#include "core/interval.h"
#include "formats/munkberg/munkberg_block.h"

namespace blocklab::munkberg {
namespace {

std::vector<std::uint8_t> random_blocks(std::size_t count, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::vector<std::uint8_t> blocks(count * kBlockBytes);
  for (auto& byte : blocks) byte = static_cast<std::uint8_t>(random() & 0xFFu);
  // Force a shape selector (munkberg_layout.h): even blocks shape II (bit 0 = 0), odd blocks shape I (bits 1, 0).
  for (std::size_t b = 0; b < count; ++b) {
    std::uint8_t& first = blocks[b * kBlockBytes];
    first = b % 2 == 0 ? static_cast<std::uint8_t>(first & ~1u) : static_cast<std::uint8_t>((first | 1u) & ~2u);
  }
  return blocks;
}

void expect_same_texels(const BlockTexels& a, const BlockTexels& b, const std::string& context) {
  for (int texel = 0; texel < 16; ++texel)
    for (int c = 0; c < 4; ++c)
      ASSERT_EQ(float_bits(a.rgba[texel][c]), float_bits(b.rgba[texel][c]))
          << context << " texel " << texel << " channel " << c;
}

TEST(MunkbergBlock, PackOfUnpackReproducesEveryRandomBlock) {
  const std::size_t count = 50000;
  const std::vector<std::uint8_t> blocks = random_blocks(count, 21);
  for (std::size_t i = 0; i < count; ++i) {
    std::uint8_t packed[kBlockBytes];
    pack_block(unpack_block(blocks.data() + kBlockBytes * i), packed);
    ASSERT_EQ(0, std::memcmp(packed, blocks.data() + kBlockBytes * i, kBlockBytes)) << "block " << i;
  }
}

TEST(MunkbergBlock, RandomBlocksDecodeBitIdenticallyToTheReferenceDecoder) {
  const std::size_t count = 20000;
  const std::vector<std::uint8_t> blocks = random_blocks(count, 22);
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint8_t* block = blocks.data() + kBlockBytes * i;
    expect_same_texels(decode_params(unpack_block(block), default_shape_set()),
                       reference_decode_block(block, default_shape_set()), "block " + std::to_string(i));
  }
}

Params grey_block(Mode mode) {
  Params p;
  p.mode = mode;
  p.shape = 0;
  // Base colours at grey chroma (wb, wr) ~ (14.5, 38) / 127 both: every landmark is that point.
  p.base = {14, 38, 14, 38};
  return p;
}

TEST(MunkbergBlock, TrueBlackIsTheZeroLuminanceNumeratorOnly) {
  for (const Mode mode : {Mode::shape_ii, Mode::shape_i}) {
    Params p = grey_block(mode);
    const int n = lum_levels_minus_one(mode);
    p.lum = {0, 200};
    p.lum_index[0] = 0;                           // q = 0: black (eq. 3)
    p.lum_index[1] = 1;                           // q = 200: 2^(-16 + 32 * 200 / (255 n))
    p.lum_index[2] = static_cast<std::uint8_t>(n);   // q = 200 n: the upper endpoint
    std::uint8_t bytes[kBlockBytes];
    pack_block(p, bytes);
    const BlockTexels t = reference_decode_block(bytes, default_shape_set());
    for (int c = 0; c < 3; ++c) EXPECT_EQ(t.rgba[0][c], 0.0f);
    const double y1 = std::exp2(-16.0 + (32.0 * 200.0) / (255.0 * n));
    const double y2 = std::exp2(-16.0 + (32.0 * 200.0 * n) / (255.0 * n));
    const double u = 14.0 / 127.0, v = 38.0 / 127.0;
    EXPECT_EQ(t.rgba[1][0], static_cast<float>((v * y1) / kRec601WeightR));
    EXPECT_EQ(t.rgba[2][2], static_cast<float>((u * y2) / kRec601WeightB));
    EXPECT_EQ(t.rgba[2][1], static_cast<float>(((1.0 - u - v) * y2) / kRec601WeightG));
    EXPECT_EQ(t.rgba[2][3], 1.0f);
    // Both endpoints 0: every texel black. Endpoint code 0 at the top index: black too.
    p.lum = {0, 0};
    pack_block(p, bytes);
    const BlockTexels all_black = reference_decode_block(bytes, default_shape_set());
    for (int i = 0; i < kTexels; ++i) EXPECT_EQ(all_black.rgba[i][1], 0.0f);
    p.lum = {9, 0};
    pack_block(p, bytes);
    EXPECT_EQ(reference_decode_block(bytes, default_shape_set()).rgba[2][0], 0.0f);   // index n selects e1 = 0
    EXPECT_GT(reference_decode_block(bytes, default_shape_set()).rgba[1][0], 0.0f);
  }
}

TEST(MunkbergBlock, ShapeOneAnchorSwapDecodesIdenticallyAndPacksWithTexelZeroBelowFour) {
  std::mt19937_64 random(31);
  for (int trial = 0; trial < 500; ++trial) {
    Params p = grey_block(Mode::shape_i);
    p.lum = {static_cast<int>(random() % 256), static_cast<int>(random() % 256)};
    for (auto& l : p.lum_index) l = static_cast<std::uint8_t>(random() % 8);
    for (auto& k : p.chroma_index) k = static_cast<std::uint8_t>(random() % 4);
    Params canonical = p;
    canonicalize_anchor(&canonical);
    EXPECT_LE(canonical.lum_index[0], kShape1AnchorIndexMax);
    expect_same_texels(decode_params(p, default_shape_set()), decode_params(canonical, default_shape_set()),
                       "trial " + std::to_string(trial));
    std::uint8_t bytes[kBlockBytes];
    if (p.lum_index[0] > kShape1AnchorIndexMax) {
      EXPECT_THROW(pack_block(p, bytes), Error);
    }
    pack_block(canonical, bytes);
    EXPECT_EQ(unpack_block(bytes), canonical);
    EXPECT_EQ(block_mode_of(bytes), BlockMode::shape_i);
  }
}

TEST(MunkbergBlock, ShapeTwoTexelPairsShareTheirChromaIndex) {
  Params p = grey_block(Mode::shape_ii);
  p.shape = 1;                 // square
  p.base = {20, 20, 60, 20};   // B0 = (20, 20)/127, B1 = (60, 20)/127; landmark 2 = (60, 60)/127, 3 = (20, 60)/127
  p.lum = {128, 128};
  for (int g = 0; g < kShape2ChromaGroups; ++g) p.chroma_index[static_cast<std::size_t>(g)] = static_cast<std::uint8_t>(g % 4);
  const BlockTexels t = decode_params(p, default_shape_set());
  for (int i = 0; i < kTexels; i += 2)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(t.rgba[i][c], t.rgba[i + 1][c]) << "pair " << i / 2;
  // Group 2 uses landmark 2 = (60, 60) / 127: B = u Y / wb with Y = 2^0 = 1 (code 128 -> -16 + 32 * 128 / 255).
  const double y = std::exp2(-16.0 + 32.0 * 128.0 / 255.0);
  EXPECT_FLOAT_EQ(t.rgba[4][2], static_cast<float>((60.0 / 127.0) * y / kRec601WeightB));
  EXPECT_FLOAT_EQ(t.rgba[6][0], static_cast<float>((60.0 / 127.0) * y / kRec601WeightR));   // group 3: v = 60/127
  EXPECT_FLOAT_EQ(t.rgba[6][2], static_cast<float>((20.0 / 127.0) * y / kRec601WeightB));
}

TEST(MunkbergBlock, GreenIsNeverNegativeWhenLandmarksLeaveTheChromaTriangle) {
  Params p = grey_block(Mode::shape_i);
  p.base = {127, 127, 127, 127};   // u = v = 1: 1 - u - v = -1
  p.lum = {100, 100};
  const BlockTexels t = decode_params(p, default_shape_set());
  for (int i = 0; i < kTexels; ++i) EXPECT_EQ(t.rgba[i][1], 0.0f);
}

TEST(MunkbergBlock, PackRejectsOutOfRangeFieldsNamingThem) {
  std::uint8_t bytes[kBlockBytes];
  const auto expect_rejects = [&](Params p, const std::string& field) {
    try {
      pack_block(p, bytes);
      ADD_FAILURE() << "accepted bad " << field;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  Params p = grey_block(Mode::shape_i);
  p.shape = 8;
  expect_rejects(p, "shape");
  p = grey_block(Mode::shape_i);
  p.base[3] = 128;
  expect_rejects(p, "base[3]");
  p = grey_block(Mode::shape_i);
  p.lum[1] = 256;
  expect_rejects(p, "lum[1]");
  p = grey_block(Mode::shape_i);
  p.lum_index[5] = 8;   // shape I has 3-bit indices
  expect_rejects(p, "lum_index[5]");
  p = grey_block(Mode::shape_ii);
  p.chroma_index[8] = 1;   // shape II has 8 groups: group 8 is unused and must be 0
  expect_rejects(p, "chroma_index[8]");
  p = grey_block(Mode::shape_ii);
  p.lum_index[5] = 15;   // fine in shape II
  EXPECT_NO_THROW(pack_block(p, bytes));
  p = grey_block(Mode::shape_i);
  p.lum_index[0] = 4;    // shape I's anchor texel holds 0..3 only
  expect_rejects(p, "lum_index[0]");
  // A block of another mode is not a shape block.
  std::uint8_t other[kBlockBytes] = {0x03};   // selector 1,1,0: ext_s3tc
  EXPECT_THROW(unpack_block(other), Error);
}

TEST(MunkbergBlock, TemplatedDecoderWorksWithIntervalsAndJets) {
  const std::vector<std::uint8_t> blocks = random_blocks(200, 23);
  using Jet = ceres::Jet<double, 6>;
  for (std::size_t b = 0; b < 200; ++b) {
    const Params p = unpack_block(blocks.data() + kBlockBytes * b);
    const std::array<double, 6> x = decode_parameters(p);
    double rgb[kTexels][3];
    decode_block(p, default_shape_set(), x.data(), rgb);
    Interval xi[6];
    Jet xj[6];
    for (int k = 0; k < 6; ++k) {
      xi[k] = Interval(x[static_cast<std::size_t>(k)]);
      xj[k] = Jet(x[static_cast<std::size_t>(k)], k);
    }
    Interval rgb_i[kTexels][3];
    Jet rgb_j[kTexels][3];
    decode_block(p, default_shape_set(), xi, rgb_i);
    decode_block(p, default_shape_set(), xj, rgb_j);
    for (int i = 0; i < kTexels; ++i)
      for (int c = 0; c < 3; ++c) {
        EXPECT_LE(rgb_i[i][c].lower(), rgb[i][c]);
        EXPECT_GE(rgb_i[i][c].upper(), rgb[i][c]);
        EXPECT_NEAR(rgb_j[i][c].a, rgb[i][c], 1e-12 * (1.0 + std::abs(rgb[i][c])));
      }
  }
}

}  // namespace
}  // namespace blocklab::munkberg
