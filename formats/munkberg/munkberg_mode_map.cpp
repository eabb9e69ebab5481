// Colour-coded per-block mode map and usage shares of a `munkberg` texture (formats/munkberg/munkberg_mode_map.h;
// Munkberg et al. 2008, Figure 4).
#include "formats/munkberg/munkberg_mode_map.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/image_io.h"

namespace blocklab::munkberg {

namespace {

int blocks_across(int size) { return (size + 3) / 4; }

}  // namespace

std::vector<BlockMode> texture_block_modes(const EncodedTexture& texture) {
  if (texture.format != "munkberg")
    fail("munkberg mode map", "texture format is '" + texture.format + "', not 'munkberg'");
  if (texture.width < 1 || texture.height < 1) fail("munkberg mode map", "empty texture");
  const std::size_t count =
      static_cast<std::size_t>(blocks_across(texture.width)) * static_cast<std::size_t>(blocks_across(texture.height));
  if (texture.blocks.size() != count * static_cast<std::size_t>(kBlockBytes))
    fail("munkberg mode map", "blocks hold " + std::to_string(texture.blocks.size()) + " bytes, expected " +
                                  std::to_string(count * kBlockBytes));
  std::vector<BlockMode> modes(count);
  for (std::size_t b = 0; b < count; ++b) {
    if (!texture.block_modes.empty()) {
      if (texture.block_modes.size() != count || texture.block_modes[b] >= kBlockModeCount)
        fail("munkberg mode map", "block_modes has a wrong size or an index >= " + std::to_string(kBlockModeCount));
      modes[b] = static_cast<BlockMode>(texture.block_modes[b]);
    } else {
      // Not recorded (e.g. a texture read from a .blk file): the selector says it.
      modes[b] = block_mode_of(texture.blocks.data() + b * static_cast<std::size_t>(kBlockBytes));
    }
  }
  return modes;
}

std::array<double, kBlockModeCount> mode_usage_shares(const EncodedTexture& texture) {
  const std::vector<BlockMode> modes = texture_block_modes(texture);
  std::array<double, kBlockModeCount> shares{};
  for (const BlockMode m : modes) shares[static_cast<std::size_t>(m)] += 1.0;
  for (double& s : shares) s /= static_cast<double>(modes.size());
  return shares;
}

Image mode_map_image(const EncodedTexture& texture, const Image* underlay) {
  const std::vector<BlockMode> modes = texture_block_modes(texture);
  if (underlay != nullptr && (underlay->width != texture.width || underlay->height != texture.height))
    fail("munkberg mode map", "underlay is " + std::to_string(underlay->width) + "x" + std::to_string(underlay->height) +
                                  ", texture " + std::to_string(texture.width) + "x" + std::to_string(texture.height));
  Image out(texture.width, texture.height, 3);
  const int across = blocks_across(texture.width);
  for (int y = 0; y < texture.height; ++y)
    for (int x = 0; x < texture.width; ++x) {
      const BlockMode mode = modes[static_cast<std::size_t>(y / 4) * static_cast<std::size_t>(across) + static_cast<std::size_t>(x / 4)];
      const auto& colour = kModeMapColours[static_cast<std::size_t>(mode)];
      float shade = 1.0f;
      if (underlay != nullptr) {
        const float* t = underlay->texel(x, y);
        const double lum = 0.299 * t[0] + 0.587 * t[1] + 0.114 * t[2];
        // Reinhard tone map, then gamma 1/2.2; negative or NaN luminance (not from the input policy) counts as 0.
        const double mapped = lum > 0.0 ? std::pow(lum / (1.0 + lum), 1.0 / 2.2) : 0.0;
        shade = static_cast<float>(0.35 + 0.65 * mapped);
      }
      float* o = out.texel(x, y);
      for (int c = 0; c < 3; ++c) o[c] = colour[static_cast<std::size_t>(c)] * shade;
    }
  return out;
}

void write_mode_map(const EncodedTexture& texture, const std::string& path, const Image* underlay) {
  write_image(path, mode_map_image(texture, underlay));
}

}  // namespace blocklab::munkberg
