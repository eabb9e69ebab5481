// `munkberg` mode map (formats/munkberg/munkberg_mode_map.h; Munkberg et al. 2008, Figure 4): each block's 4x4 patch
// has its mode's colour (from block_modes, or from the selector when block_modes is absent), the underlay shades it,
// usage shares count blocks per mode and sum to 1, the PNG is written and reads back at the texture's size, and
// textures of another format or inconsistent sizes are errors.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/image_io.h"
#include "formats/munkberg/munkberg_mode_map.h"

namespace blocklab::munkberg {
namespace {

// A 10x6 texture (3x2 blocks, the last column/row partial) with the given block modes; each block's first byte
// carries the matching selector.
EncodedTexture texture_with_modes(const std::vector<int>& modes) {
  static const std::uint8_t selector[kBlockModeCount] = {0x00, 0x01, 0x03, 0x07, 0x0F};
  EncodedTexture texture;
  texture.format = "munkberg";
  texture.width = 10;
  texture.height = 6;
  texture.block_bytes = kBlockBytes;
  texture.blocks.assign(modes.size() * kBlockBytes, 0);
  for (std::size_t b = 0; b < modes.size(); ++b) {
    texture.blocks[b * kBlockBytes] = selector[modes[b]];
    texture.block_modes.push_back(static_cast<std::uint8_t>(modes[b]));
  }
  return texture;
}

TEST(MunkbergModeMap, EachBlockPatchHasItsModesColourAndSharesCountBlocks) {
  EncodedTexture texture = texture_with_modes({0, 1, 2, 3, 1, 1});
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) texture.block_modes.clear();   // from the selectors instead
    const Image map = mode_map_image(texture);
    ASSERT_EQ(map.width, 10);
    ASSERT_EQ(map.height, 6);
    const int expected[6] = {0, 1, 2, 3, 1, 1};
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 10; ++x) {
        const int mode = expected[(y / 4) * 3 + x / 4];
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(map.texel(x, y)[c], kModeMapColours[static_cast<std::size_t>(mode)][static_cast<std::size_t>(c)]);
      }
    const auto shares = mode_usage_shares(texture);
    EXPECT_DOUBLE_EQ(shares[0], 1.0 / 6.0);
    EXPECT_DOUBLE_EQ(shares[1], 3.0 / 6.0);
    EXPECT_DOUBLE_EQ(shares[2], 1.0 / 6.0);
    EXPECT_DOUBLE_EQ(shares[3], 1.0 / 6.0);
  }
}

TEST(MunkbergModeMap, UnderlayShadesTheColourByItsLuminance) {
  const EncodedTexture texture = texture_with_modes({2, 2, 2, 2, 2, 2});
  Image underlay(10, 6);   // black everywhere except one bright texel
  for (int c = 0; c < 3; ++c) underlay.texel(5, 2)[c] = 1000.0f;
  const Image map = mode_map_image(texture, &underlay);
  EXPECT_FLOAT_EQ(map.texel(0, 0)[0], 0.35f * kModeMapColours[2][0]);
  EXPECT_GT(map.texel(5, 2)[0], 0.99f * kModeMapColours[2][0]);
  Image wrong(9, 6);
  EXPECT_THROW(mode_map_image(texture, &wrong), Error);
}

TEST(MunkbergModeMap, WritesAPngOfTheTexturesSize) {
  const EncodedTexture texture = texture_with_modes({0, 1, 2, 3, 0, 1});
  const std::string path = (std::filesystem::temp_directory_path() / "blocklab_test_munkberg_mode_map.png").string();
  write_mode_map(texture, path);
  const Image back = read_image(path);
  EXPECT_EQ(back.width, 10);
  EXPECT_EQ(back.height, 6);
  // Green (shape_i) block: 8-bit rounding of 0.8.
  EXPECT_NEAR(back.texel(5, 0)[1], 0.8f, 1.0f / 255.0f);
  std::remove(path.c_str());
}

TEST(MunkbergModeMap, OtherFormatsAndInconsistentTexturesAreErrors) {
  EncodedTexture texture = texture_with_modes({0, 1, 2, 3, 0, 1});
  texture.format = "bc1";
  EXPECT_THROW(mode_map_image(texture), Error);
  texture = texture_with_modes({0, 1, 2});   // 3 blocks for a 3x2 grid
  EXPECT_THROW(mode_usage_shares(texture), Error);
  texture = texture_with_modes({0, 1, 2, 3, 0, 1});
  texture.block_modes[4] = 7;
  EXPECT_THROW(mode_map_image(texture), Error);
}

}  // namespace
}  // namespace blocklab::munkberg
