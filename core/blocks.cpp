// 4x4 block tiling with clamp-to-edge padding (core/blocks.h). Texel i of a block is (i % 4, i / 4), i = x + 4y, the
// order of every BCn spec (Khronos Data Format Specification, S3TC/BPTC chapters); blocks are row-major.
#include "core/blocks.h"

#include <algorithm>
#include <string>

#include "core/error.h"

namespace blocklab {

namespace {

// The grid must describe this image and `index` must name one of its blocks; anything else is a caller bug that
// would read or write out of bounds, so it is reported as an Error rather than trusted.
void check_block_access(const char* who, const Image& image, const BlockGrid& grid, std::size_t index) {
  if (image.width < 1 || image.height < 1)
    fail(who, "image is empty (" + std::to_string(image.width) + "x" + std::to_string(image.height) + ")");
  if (grid.width != image.width || grid.height != image.height)
    fail(who, "block grid is for a " + std::to_string(grid.width) + "x" + std::to_string(grid.height) +
                  " image but the image is " + std::to_string(image.width) + "x" + std::to_string(image.height));
  if (image.pixels.size() != image.texel_count() * 4)
    fail(who, "image holds " + std::to_string(image.pixels.size()) + " floats, expected " +
                  std::to_string(image.texel_count() * 4));
  if (index >= grid.block_count())
    fail(who, "block index " + std::to_string(index) + " is outside the " + std::to_string(grid.block_count()) +
                  " blocks of the image");
}

}  // namespace

BlockTexels load_block(const Image& image, const BlockGrid& grid, std::size_t index) {
  check_block_access("load_block", image, grid, index);
  const int origin_x = static_cast<int>(index % static_cast<std::size_t>(grid.blocks_x)) * kBlockSize;
  const int origin_y = static_cast<int>(index / static_cast<std::size_t>(grid.blocks_x)) * kBlockSize;
  BlockTexels block{};
  for (int y = 0; y < kBlockSize; ++y) {
    // Clamp-to-edge: a row below the image repeats the last row (origin_y is always inside the image).
    const int source_y = std::min(origin_y + y, image.height - 1);
    for (int x = 0; x < kBlockSize; ++x) {
      // Clamp-to-edge: a column right of the image repeats the last column.
      const int source_x = std::min(origin_x + x, image.width - 1);
      const float* texel = image.texel(source_x, source_y);
      std::copy(texel, texel + 4, block.rgba[x + kBlockSize * y]);
    }
  }
  return block;
}

void store_block(Image& image, const BlockGrid& grid, std::size_t index, const BlockTexels& block) {
  check_block_access("store_block", image, grid, index);
  const int origin_x = static_cast<int>(index % static_cast<std::size_t>(grid.blocks_x)) * kBlockSize;
  const int origin_y = static_cast<int>(index / static_cast<std::size_t>(grid.blocks_x)) * kBlockSize;
  // Padding texels (outside the image) are dropped: only the part of the block inside the image is written.
  const int rows = std::min(kBlockSize, image.height - origin_y);
  const int columns = std::min(kBlockSize, image.width - origin_x);
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < columns; ++x) {
      const float* texel = block.rgba[x + kBlockSize * y];
      std::copy(texel, texel + 4, image.texel(origin_x + x, origin_y + y));
    }
}

}  // namespace blocklab
