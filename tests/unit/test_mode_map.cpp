// Generic block-mode maps (formats/common/mode_map.h): shares count recorded block modes and sum to 1, each block's
// 4x4 patch (partial at the right/bottom edge) has its mode's Okabe-Ito colour, an underlay shades it, the CSV text
// and legend list modes in order, and textures without (or with inconsistent) block modes are errors that say why.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "formats/common/mode_map.h"

namespace blocklab {
namespace {

const std::vector<std::string> kNames = {"first", "second", "third"};

// A 10x6 texture: 3x2 blocks, the last column and row partial.
EncodedTexture texture_with_modes(const std::vector<std::uint8_t>& modes) {
  EncodedTexture texture;
  texture.format = "fake";
  texture.width = 10;
  texture.height = 6;
  texture.block_modes = modes;
  return texture;
}

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

TEST(ModeMap, SharesCountBlocksPerModeInModeOrder) {
  const std::vector<double> shares = mode_shares(texture_with_modes({0, 2, 2, 2, 0, 2}), kNames);
  ASSERT_EQ(shares.size(), 3u);
  EXPECT_DOUBLE_EQ(shares[0], 2.0 / 6.0);
  EXPECT_DOUBLE_EQ(shares[1], 0.0);
  EXPECT_DOUBLE_EQ(shares[2], 4.0 / 6.0);
  EXPECT_EQ(mode_shares_text(shares, kNames), "first=0.3333;second=0.0000;third=0.6667");
}

TEST(ModeMap, EveryTexelOfABlockHasItsModesColourIncludingPartialEdgeBlocks) {
  const Image map = mode_map_image(texture_with_modes({0, 1, 2, 2, 1, 0}), kNames);
  ASSERT_EQ(map.width, 10);
  ASSERT_EQ(map.height, 6);
  const struct { int x, y; std::size_t mode; } probes[] = {{0, 0, 0}, {3, 3, 0}, {4, 0, 1}, {9, 3, 2}, {0, 4, 2},
                                                           {5, 5, 1}, {9, 5, 0}, {8, 4, 0}};
  for (const auto& p : probes) {
    const ModeColour expected = mode_colour(p.mode);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(map.texel(p.x, p.y)[c], expected[static_cast<std::size_t>(c)]) << p.x << "," << p.y;
  }
}

TEST(ModeMap, PaletteIsOkabeItoThenHalfBrightnessAndStopsAtSixteen) {
  EXPECT_FLOAT_EQ(mode_colour(0)[0], 230 / 255.0f);   // orange E69F00
  EXPECT_FLOAT_EQ(mode_colour(4)[2], 178 / 255.0f);   // blue 0072B2
  EXPECT_FLOAT_EQ(mode_colour(9)[1], 0.5f * 180 / 255.0f);   // sky blue, second round
  EXPECT_NE(error_of([] { mode_colour(16); }).find("no colour for mode index 16"), std::string::npos);
}

TEST(ModeMap, UnderlayDarkensBlackTexelsAndKeepsBrightOnes) {
  const EncodedTexture texture = texture_with_modes({1, 1, 1, 1, 1, 1});
  Image underlay(10, 6, 3);   // zeros: black
  underlay.texel(2, 2)[0] = underlay.texel(2, 2)[1] = underlay.texel(2, 2)[2] = 1e9f;   // tone-maps to ~1
  const Image map = mode_map_image(texture, kNames, &underlay);
  const ModeColour colour = mode_colour(1);
  EXPECT_FLOAT_EQ(map.texel(0, 0)[2], colour[2] * 0.35f);
  EXPECT_NEAR(map.texel(2, 2)[2], colour[2], 1e-6);
  Image wrong(9, 6, 3);
  EXPECT_NE(error_of([&] { mode_map_image(texture, kNames, &wrong); }).find("underlay is 9x6, texture 10x6"),
            std::string::npos);
}

TEST(ModeMap, LegendNamesEachModeItsColourAndShare) {
  const std::string legend = mode_map_legend({0.25, 0.75, 0.0}, kNames);
  EXPECT_NE(legend.find("first: orange (0.902, 0.624, 0.000), 25.00%\n"), std::string::npos) << legend;
  EXPECT_NE(legend.find("second: sky blue"), std::string::npos) << legend;
  EXPECT_NE(legend.find("third: bluish green (0.000, 0.620, 0.451), 0.00%\n"), std::string::npos) << legend;
}

TEST(ModeMap, MissingWrongSizedOrOutOfRangeBlockModesAreErrors) {
  EXPECT_NE(error_of([] { mode_shares(texture_with_modes({}), kNames); }).find("records no block modes"),
            std::string::npos);
  EXPECT_NE(error_of([] { mode_shares(texture_with_modes({0, 1}), kNames); })
                .find("block_modes holds 2 entries for 6 blocks"),
            std::string::npos);
  EXPECT_NE(error_of([] { mode_shares(texture_with_modes({0, 1, 2, 3, 0, 0}), kNames); })
                .find("mode index 3 but format 'fake' has 3 modes"),
            std::string::npos);
}

}  // namespace
}  // namespace blocklab
