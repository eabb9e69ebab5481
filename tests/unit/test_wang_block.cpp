// The `wang` block (formats/wang/wang_block.h, wang_shader.h, wang_reference_decode.cpp): pack/unpack round trips,
// the templated decoder against the Format's float decoder and the spec-literal oracle, the eq. 3 / eq. 4
// branch-free identity (Claim 3.1), eq. 6 / eq. 7, and LUVW / LUV of known colours.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>

#include "formats/wang/wang_block.h"
#include "formats/wang/wang_color_space.h"
#include "formats/wang/wang_zone_encoding.h"

namespace blocklab {
namespace {

using wang::ColorSpace;
using wang::LuminanceSplit;
using wang::Residual;

void random_bytes(std::mt19937& rng, std::uint8_t* bytes, int count) {
  for (int k = 0; k < count; ++k) bytes[k] = static_cast<std::uint8_t>(rng() & 0xffu);
}

wang::Zones random_zones(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  wang::Zones z;
  z.tmin = unit(rng) * 0.01;
  z.t1 = z.tmin + unit(rng) * 2.0;
  z.tmax = z.t1 + unit(rng) * 5000.0;
  z.smin = -unit(rng) * 3.0;
  z.s1 = z.smin + unit(rng);
  z.s2 = z.s1 + unit(rng) * 2.0;
  z.smax = z.s2 + unit(rng) * 4.0;
  return z;
}

TEST(WangBlock, PackOfUnpackReproducesRandomBytes) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 2000; ++trial) {
    std::uint8_t bytes[wang::kBlockBytes], again[wang::kBlockBytes];
    random_bytes(rng, bytes, wang::kBlockBytes);
    wang::pack_block(wang::unpack_block(bytes), again);
    ASSERT_EQ(0, std::memcmp(bytes, again, sizeof(bytes))) << "trial " << trial;
  }
}

TEST(WangBlock, TemplatedDecoderFloatDecoderAndOracleAgreeBitForBitOnRandomBlocks) {
  std::mt19937 rng(12);
  for (int trial = 0; trial < 3000; ++trial) {
    std::uint8_t bytes[wang::kBlockBytes];
    random_bytes(rng, bytes, wang::kBlockBytes);
    const wang::Zones zones = random_zones(rng);
    const ColorSpace space = trial % 2 ? ColorSpace::luv : ColorSpace::luvw;
    const Residual residual = trial % 3 == 0 ? Residual::s : (trial % 3 == 1 ? Residual::ratio : Residual::none);
    const LuminanceSplit split = trial % 5 == 0 ? LuminanceSplit::one_range : LuminanceSplit::two_zones;
    wang::DecodeSetup setup;
    setup.constants = wang::shader_constants(zones, split, residual);
    setup.space = space;
    setup.residual = residual;
    const BlockTexels decoded = wang::decode_block_bytes(setup, bytes);
    const BlockTexels oracle = wang::reference_decode_block(zones, split, space, residual, bytes);
    float templated[16][3];
    wang::decode_block(setup, wang::unpack_block(bytes), templated);
    double as_double[16][3];
    wang::decode_block(setup, wang::unpack_block(bytes), as_double);
    for (int texel = 0; texel < 16; ++texel)
      for (int channel = 0; channel < 3; ++channel) {
        const float value = decoded.rgba[texel][channel];
        ASSERT_TRUE(std::isfinite(value) && value >= 0.0f);
        ASSERT_EQ(value, oracle.rgba[texel][channel]) << "trial " << trial << " texel " << texel;
        ASSERT_EQ(value, templated[texel][channel]) << "trial " << trial << " texel " << texel;
        // double runs the same operations without float rounding: close (to float rounding of the largest
        // constant), not equal.
        ASSERT_NEAR(as_double[texel][channel], value, 1e-6 * (10.0 + zones.tmax));
      }
  }
}

TEST(WangBlock, IntervalDecoderEnclosesAndJetDecoderEqualsTheDoubleDecoder) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 200; ++trial) {
    std::uint8_t bytes[wang::kBlockBytes];
    random_bytes(rng, bytes, wang::kBlockBytes);
    wang::DecodeSetup setup;
    setup.constants = wang::shader_constants(random_zones(rng), LuminanceSplit::two_zones, Residual::s);
    const wang::BlockParams params = wang::unpack_block(bytes);
    double point[16][3];
    Interval box[16][3];
    ceres::Jet<double, 2> jet[16][3];
    wang::decode_block(setup, params, point);
    wang::decode_block(setup, params, box);
    wang::decode_block(setup, params, jet);
    for (int texel = 0; texel < 16; ++texel)
      for (int channel = 0; channel < 3; ++channel) {
        ASSERT_LE(box[texel][channel].lower(), point[texel][channel]);
        ASSERT_GE(box[texel][channel].upper(), point[texel][channel]);
        // ceres divides by multiplying with the reciprocal: equal up to rounding.
        ASSERT_NEAR(jet[texel][channel].a, point[texel][channel], 1e-12 * (1.0 + std::abs(point[texel][channel])));
      }
  }
}

// Claim 3.1: with eq. 3's assignment, eq. 4 reconstructs L in both zones without a branch.
TEST(WangBlock, Eq3AssignmentDecodesByEq4InBothZonesWithoutABranch) {
  wang::Zones zones;
  zones.tmin = 0.05;
  zones.t1 = 1.5;
  zones.tmax = 900.0;
  for (double l = zones.tmin; l <= zones.tmax; l *= 1.37) {
    const std::array<double, 2> a = wang::luminance_targets(l, zones, LuminanceSplit::two_zones);
    const double eq4 = a[0] * (zones.tmax - zones.t1) + a[1] * (zones.t1 - zones.tmin) + zones.tmin;
    EXPECT_NEAR(eq4, l, 1e-12 * zones.tmax) << "L " << l;
    if (l <= zones.t1) {
      EXPECT_EQ(a[0], 0.0);   // tex0.a = 0 in the low zone
    } else {
      EXPECT_EQ(a[1], 1.0);   // tex1.a = 1 in the high zone
    }
  }
  // Linear filtering commutes with eq. 4 (Appendix A): the filtered targets decode to the filtered luminance.
  const double la = 0.7, lb = 40.0, w = 0.3;
  const auto a = wang::luminance_targets(la, zones, LuminanceSplit::two_zones);
  const auto b = wang::luminance_targets(lb, zones, LuminanceSplit::two_zones);
  const double filtered = (w * a[0] + (1 - w) * b[0]) * (zones.tmax - zones.t1) +
                          (w * a[1] + (1 - w) * b[1]) * (zones.t1 - zones.tmin) + zones.tmin;
  EXPECT_NEAR(filtered, w * la + (1 - w) * lb, 1e-12 * zones.tmax);
}

TEST(WangBlock, Eq6AssignmentDecodesByEq7AndOneRangeSplitsTwelveBits) {
  wang::Zones zones;
  zones.smin = -2.0;
  zones.s1 = -0.1;
  zones.s2 = 0.3;
  zones.smax = 5.0;
  for (double s = zones.smin; s <= zones.smax; s += 0.0625) {
    const std::array<double, 3> t = wang::residual_targets(s, zones);
    const double eq7 = t[0] * (zones.s1 - zones.smin) + t[1] * (zones.s2 - zones.s1) + t[2] * (zones.smax - zones.s2) +
                       zones.smin;
    EXPECT_NEAR(eq7, s, 1e-12) << "S " << s;
  }
  zones.tmin = 0.0;
  zones.tmax = 4095.0;
  const std::array<double, 2> a = wang::luminance_targets(1234.0, zones, LuminanceSplit::one_range);
  EXPECT_EQ(a[0] * 63.0, 19.0);   // 1234 = 19 * 64 + 18
  EXPECT_EQ(a[1] * 63.0, 18.0);
}

TEST(WangBlock, LuvwAndLuvOfKnownColoursAndTheirInverses) {
  const float rgb[3] = {3.0f, 4.0f, 12.0f};   // |RGB| = 13
  const wang::LuminanceChroma luvw = wang::to_luminance_chroma(ColorSpace::luvw, rgb);
  EXPECT_DOUBLE_EQ(luvw.luminance, 13.0);
  EXPECT_DOUBLE_EQ(luvw.chroma[0], 3.0 / 13.0);
  EXPECT_DOUBLE_EQ(luvw.chroma[1], 4.0 / 13.0);
  EXPECT_DOUBLE_EQ(luvw.chroma[2], 12.0 / 13.0);
  const wang::LuminanceChroma luv = wang::to_luminance_chroma(ColorSpace::luv, rgb);
  EXPECT_DOUBLE_EQ(luv.luminance, 3.0 + 8.0 + 12.0);
  EXPECT_DOUBLE_EQ(luv.chroma[0], 3.0 / 23.0);
  EXPECT_DOUBLE_EQ(luv.chroma[1], 8.0 / 23.0);
  for (const ColorSpace space : {ColorSpace::luvw, ColorSpace::luv}) {
    const wang::LuminanceChroma lc = wang::to_luminance_chroma(space, rgb);
    const double chroma[3] = {lc.chroma[0], lc.chroma[1], lc.chroma[2]};
    double back[3];
    wang::to_rgb(space, chroma, lc.luminance, back);
    for (int channel = 0; channel < 3; ++channel) EXPECT_NEAR(back[channel], rgb[channel], 1e-12);
  }
  const float black[3] = {0.0f, 0.0f, 0.0f};
  EXPECT_EQ(wang::to_luminance_chroma(ColorSpace::luvw, black).luminance, 0.0);
}

TEST(WangBlock, TextureUnitRoundsBc3InterpolantsToTheNearestEightBitValue) {
  // (2 * 255 + 0) / 3 = 170 exactly; (6 a0 + a1) / 7 with a0 = 10, a1 = 0 is 8.571 -> 9.
  EXPECT_EQ(wang::texture_unit_value(170.0 / 255.0) * 255.0, 170.0);
  EXPECT_EQ(wang::texture_unit_value(60.0 / 7.0 / 255.0) * 255.0, 9.0);
  EXPECT_EQ(wang::texture_unit_value(0.0), 0.0);
  EXPECT_EQ(wang::texture_unit_value(1.0), 1.0);
}

}  // namespace
}  // namespace blocklab
