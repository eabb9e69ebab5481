// 4x4 block tiling of an image of any size (1x1 upward).
//
// Block (bx, by) covers texels x in [4bx, 4bx+3], y in [4by, 4by+3]; texel i of a block is (i % 4, i / 4)
// (i = x + 4y, the order of every BCn spec). Blocks are numbered row-major: index = by * blocks_x + bx.
// Edge padding: a texel outside the image takes the value of the nearest texel inside it (clamp-to-edge), so the
// padding never adds a colour the block did not have and a 1x1 image becomes a constant block. Decoders write
// back only texels inside the image.
#pragma once

#include <cstddef>

#include "core/image.h"

namespace blocklab {

constexpr int kBlockSize = 4;
constexpr int kBlockTexels = 16;

struct BlockGrid {
  int width = 0;
  int height = 0;
  int blocks_x = 0;
  int blocks_y = 0;
  BlockGrid() = default;
  BlockGrid(int w, int h) : width(w), height(h), blocks_x((w + 3) / 4), blocks_y((h + 3) / 4) {}
  std::size_t block_count() const { return static_cast<std::size_t>(blocks_x) * static_cast<std::size_t>(blocks_y); }
};

// One block's texels, RGBA, texel i = x + 4y.
struct BlockTexels {
  float rgba[kBlockTexels][4];
};

// Reads block `index` with clamp-to-edge padding.
BlockTexels load_block(const Image& image, const BlockGrid& grid, std::size_t index);
// Writes the texels of block `index` that lie inside the image.
void store_block(Image& image, const BlockGrid& grid, std::size_t index, const BlockTexels& block);

}  // namespace blocklab
