// The loop every block format shares: tile the image into 4x4 blocks (core/blocks.h, clamp-to-edge padding), encode
// or decode each block in parallel (core/parallel.h), each block writing only its own slot, so the bytes and pixels
// do not depend on the thread count. A format supplies only its per-block functions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/blocks.h"
#include "core/parallel.h"
#include "formats/format.h"

namespace blocklab {

// An encoded texture of `format` for `image` with every block slot allocated (zero bytes, mode 0).
inline EncodedTexture empty_encoded_texture(const Format& format, const Image& image, const FormatOptions& options,
                                           int block_bytes, std::size_t block_count) {
  EncodedTexture texture;
  texture.format = format.name();
  texture.options = options;
  texture.width = image.width;
  texture.height = image.height;
  texture.channels = image.channels;
  texture.block_bytes = block_bytes;
  texture.blocks.resize(block_count * static_cast<std::size_t>(block_bytes));
  texture.block_modes.assign(block_count, 0);
  return texture;
}

// encode_block(const BlockTexels& texels, std::size_t block_index, std::uint8_t* out) writes `block_bytes` bytes to
// `out` and returns the block's mode index (into format.modes()). The image must already have passed the input policy.
template <class EncodeBlock>
EncodedTexture encode_blocks(const Format& format, const Image& image, const FormatOptions& options,
                             const CodecContext& context, int block_bytes, EncodeBlock&& encode_block) {
  validate_encoder_input(image, format.name());
  const BlockGrid grid(image.width, image.height);
  EncodedTexture texture = empty_encoded_texture(format, image, options, block_bytes, grid.block_count());
  std::uint8_t* blocks = texture.blocks.data();
  std::uint8_t* modes = texture.block_modes.data();
  parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
    const BlockTexels texels = load_block(image, grid, index);
    modes[index] = static_cast<std::uint8_t>(
        encode_block(texels, index, blocks + index * static_cast<std::size_t>(block_bytes)));
  });
  return texture;
}

// The same with one workspace per worker thread (astcenc's working buffers): make_workspace() returns a
// std::unique_ptr<W> for a worker's first block, and encode_block(texels, block_index, out, W& workspace) gets that
// worker's workspace for every block it encodes. Which worker encodes which block depends on the scheduling, so a
// workspace may hold scratch buffers only (cleared before use), never state a block's bytes depend on.
template <class MakeWorkspace, class EncodeBlock>
EncodedTexture encode_blocks(const Format& format, const Image& image, const FormatOptions& options,
                             const CodecContext& context, int block_bytes, MakeWorkspace&& make_workspace,
                             EncodeBlock&& encode_block) {
  validate_encoder_input(image, format.name());
  const BlockGrid grid(image.width, image.height);
  EncodedTexture texture = empty_encoded_texture(format, image, options, block_bytes, grid.block_count());
  std::uint8_t* blocks = texture.blocks.data();
  std::uint8_t* modes = texture.block_modes.data();
  std::vector<decltype(make_workspace())> workspaces(static_cast<std::size_t>(parallel_worker_count(context.threads)));
  parallel_for_worker_index(grid.block_count(), context.threads, [&](std::size_t index, int worker) {
    auto& workspace = workspaces[static_cast<std::size_t>(worker)];   // this worker's slot only
    if (!workspace) workspace = make_workspace();
    const BlockTexels texels = load_block(image, grid, index);
    modes[index] = static_cast<std::uint8_t>(
        encode_block(texels, index, blocks + index * static_cast<std::size_t>(block_bytes), *workspace));
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
