// The loop every block format shares: tile the image into 4x4 blocks (core/blocks.h, clamp-to-edge padding), encode
// or decode each block in parallel (core/parallel.h), each block writing only its own slot, so the bytes and pixels
// do not depend on the thread count. A format supplies only its per-block functions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "core/blocks.h"
#include "core/parallel.h"
#include "formats/format.h"

namespace blocklab {

// encode_block(const BlockTexels& texels, std::size_t block_index, std::uint8_t* out) writes `block_bytes` bytes to
// `out` and returns the block's mode index (into format.modes()). The image must already have passed the input policy.
template <class EncodeBlock>
EncodedTexture encode_blocks(const Format& format, const Image& image, const FormatOptions& options,
                             const CodecContext& context, int block_bytes, EncodeBlock&& encode_block) {
  validate_encoder_input(image, format.name());
  const BlockGrid grid(image.width, image.height);
  EncodedTexture texture;
  texture.format = format.name();
  texture.options = options;
  texture.width = image.width;
  texture.height = image.height;
  texture.channels = image.channels;
  texture.block_bytes = block_bytes;
  texture.blocks.resize(grid.block_count() * static_cast<std::size_t>(block_bytes));
  texture.block_modes.assign(grid.block_count(), 0);
  std::uint8_t* blocks = texture.blocks.data();
  std::uint8_t* modes = texture.block_modes.data();
  parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
    const BlockTexels texels = load_block(image, grid, index);
    modes[index] = static_cast<std::uint8_t>(
        encode_block(texels, index, blocks + index * static_cast<std::size_t>(block_bytes)));
  });
  return texture;
}

// decode_block(const std::uint8_t* bytes, std::size_t block_index) returns the block's BlockTexels. The texture is
// validated first (validate_encoded_texture). `decoded_channels` is the channel count of the returned image.
template <class DecodeBlock>
Image decode_blocks(const Format& format, const EncodedTexture& texture, const CodecContext& context,
                    int decoded_channels, DecodeBlock&& decode_block) {
  validate_encoded_texture(format, texture, format.name());
  const BlockGrid grid(texture.width, texture.height);
  Image image(texture.width, texture.height, decoded_channels);
  const std::uint8_t* blocks = texture.blocks.data();
  const std::size_t block_bytes = static_cast<std::size_t>(texture.block_bytes);
  parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
    store_block(image, grid, index, decode_block(blocks + index * block_bytes, index));
  });
  return image;
}

// Channel count of a decoded image for formats that store RGB only: a 4-channel source decodes as RGB (alpha = 1);
// 1- and 3-channel sources keep their count (a luminance source has R = G = B).
inline int rgb_only_decoded_channels(int source_channels) { return source_channels == 4 ? 3 : source_channels; }

}  // namespace blocklab
