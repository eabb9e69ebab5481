// core/blocks.h: 4x4 tiling with clamp-to-edge padding. For sizes from 1x1 to odd 767x1023: block count, texel
// order (i = x + 4y, row-major blocks), padding texels equal to the nearest edge texel, an exact load/store round
// trip, and inconsistent grids or indices reported as an Error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "core/blocks.h"
#include "core/error.h"

namespace blocklab {
namespace {

// Every channel of every texel gets a distinct value (encodes x, y, channel), so a texel read from the wrong
// place can never match by accident.
Image coordinate_image(int width, int height) {
  Image image(width, height, 4);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 4; ++c) image.texel(x, y)[c] = static_cast<float>((y * 2048 + x) * 4 + c);
  return image;
}

const std::pair<int, int> kSizes[] = {{1, 1}, {1, 7}, {7, 1}, {5, 5}, {4, 4}, {8, 3}, {3, 8}, {16, 16}, {767, 1023}};

TEST(BlockTiling, BlockCountIsCeilOfEachDimensionOverFour) {
  for (const auto& [width, height] : kSizes) {
    const BlockGrid grid(width, height);
    EXPECT_EQ(grid.blocks_x, (width + 3) / 4);
    EXPECT_EQ(grid.blocks_y, (height + 3) / 4);
    EXPECT_EQ(grid.block_count(), static_cast<std::size_t>((width + 3) / 4) * ((height + 3) / 4));
  }
  EXPECT_EQ(BlockGrid(767, 1023).block_count(), 192u * 256u);
  EXPECT_EQ(BlockGrid(1, 1).block_count(), 1u);
}

TEST(BlockTiling, LoadedTexelsFollowTheBcnOrderAndPaddingRepeatsTheNearestEdgeTexel) {
  for (const auto& [width, height] : kSizes) {
    const Image image = coordinate_image(width, height);
    const BlockGrid grid(width, height);
    for (std::size_t index = 0; index < grid.block_count(); ++index) {
      const BlockTexels block = load_block(image, grid, index);
      const int bx = static_cast<int>(index) % grid.blocks_x, by = static_cast<int>(index) / grid.blocks_x;
      for (int i = 0; i < kBlockTexels; ++i) {
        // Texel i is (i % 4, i / 4) in the block; outside the image the nearest texel inside it (clamp).
        const int x = std::min(4 * bx + i % 4, width - 1);
        const int y = std::min(4 * by + i / 4, height - 1);
        for (int c = 0; c < 4; ++c)
          ASSERT_EQ(block.rgba[i][c], image.texel(x, y)[c])
              << width << "x" << height << " block " << index << " texel " << i << " channel " << c;
      }
    }
  }
}

TEST(BlockTiling, OneByOneImageBecomesAConstantBlock) {
  Image image(1, 1, 4);
  const float value[4] = {0.25f, 2.0f, 65504.0f, 0.5f};
  std::copy(value, value + 4, image.texel(0, 0));
  const BlockTexels block = load_block(image, BlockGrid(1, 1), 0);
  for (int i = 0; i < kBlockTexels; ++i)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(block.rgba[i][c], value[c]);
}

TEST(BlockTiling, LoadThenStoreOfEveryBlockReproducesTheImageExactly) {
  for (const auto& [width, height] : kSizes) {
    const Image source = coordinate_image(width, height);
    const BlockGrid grid(width, height);
    Image target(width, height, 4);
    std::fill(target.pixels.begin(), target.pixels.end(), std::numeric_limits<float>::quiet_NaN());
    for (std::size_t index = 0; index < grid.block_count(); ++index)
      store_block(target, grid, index, load_block(source, grid, index));
    ASSERT_EQ(target.pixels.size(), source.pixels.size());
    for (std::size_t k = 0; k < source.pixels.size(); ++k)
      ASSERT_EQ(target.pixels[k], source.pixels[k]) << width << "x" << height << " float " << k;
  }
}

TEST(BlockTiling, StoreWritesOnlyTheTexelsOfItsBlockThatLieInsideTheImage) {
  // 5x5: block 3 (bx = 1, by = 1) covers only texel (4, 4); the 15 padding texels are dropped.
  Image image(5, 5, 4);
  std::fill(image.pixels.begin(), image.pixels.end(), -1.0f);
  BlockTexels block{};
  for (int i = 0; i < kBlockTexels; ++i)
    for (int c = 0; c < 4; ++c) block.rgba[i][c] = static_cast<float>(i);
  store_block(image, BlockGrid(5, 5), 3, block);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x)
      EXPECT_EQ(image.texel(x, y)[0], (x == 4 && y == 4) ? 0.0f : -1.0f) << x << "," << y;
  // Block 1 (bx = 1, by = 0) covers column 4 of rows 0..3: texels i = 0, 4, 8, 12.
  store_block(image, BlockGrid(5, 5), 1, block);
  for (int y = 0; y < 4; ++y) EXPECT_EQ(image.texel(4, y)[2], static_cast<float>(4 * y));
  EXPECT_EQ(image.texel(3, 0)[0], -1.0f);
}

TEST(BlockTiling, MismatchedGridOrOutOfRangeIndexIsAnError) {
  Image image(8, 3, 3);
  const BlockGrid grid(8, 3);
  EXPECT_THROW(load_block(image, grid, grid.block_count()), Error);
  EXPECT_THROW(load_block(image, BlockGrid(9, 3), 0), Error);
  BlockTexels block{};
  EXPECT_THROW(store_block(image, grid, 2, block), Error);
  EXPECT_THROW(store_block(image, BlockGrid(8, 4), 0, block), Error);
  Image empty;
  EXPECT_THROW(load_block(empty, BlockGrid(), 0), Error);
  Image truncated(8, 3, 3);
  truncated.pixels.resize(10);
  EXPECT_THROW(load_block(truncated, grid, 0), Error);
}

}  // namespace
}  // namespace blocklab
