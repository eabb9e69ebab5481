// Per-block mode usage of a `munkberg` texture drawn as a colour-coded map (Munkberg et al. 2008, Figure 4: "The
// color-coded images to the right illustrate the usage of the algorithms in different image regions") and the usage
// shares (Figure 4's left diagram). Experiment-independent: works on any EncodedTexture of the format.
//
// Colours (RGB in [0, 1], one per BlockMode; the paper does not list its palette):
//   shape_ii  blue (0.20, 0.40, 1.00)    shape_i  green (0.15, 0.80, 0.20)
//   ext_s3tc  red  (0.95, 0.20, 0.15)    two_plane yellow (1.00, 0.85, 0.10)
//   dct       purple (0.60, 0.25, 0.85)
// With an underlay image the colour is scaled by 0.35 + 0.65 * (tone-mapped luminance of the underlay texel), so the
// image's structure shows through; without, every block is a flat 4x4 patch of its colour.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/image.h"
#include "formats/format.h"
#include "formats/munkberg/munkberg_layout.h"

namespace blocklab::munkberg {

constexpr std::array<std::array<float, 3>, kBlockModeCount> kModeMapColours = {{
    {0.20f, 0.40f, 1.00f},   // shape_ii
    {0.15f, 0.80f, 0.20f},   // shape_i
    {0.95f, 0.20f, 0.15f},   // ext_s3tc
    {1.00f, 0.85f, 0.10f},   // two_plane
    {0.60f, 0.25f, 0.85f},   // dct
}};

// The mode of every block (row-major): texture.block_modes when present, otherwise read from each block's selector.
// Error unless texture.format is "munkberg" and the sizes are consistent.
std::vector<BlockMode> texture_block_modes(const EncodedTexture& texture);

// Fraction of blocks per mode (BlockMode order); sums to 1 for a non-empty texture.
std::array<double, kBlockModeCount> mode_usage_shares(const EncodedTexture& texture);

// texture.width x texture.height RGB image of the map; `underlay` (optional) must have the texture's size.
Image mode_map_image(const EncodedTexture& texture, const Image* underlay = nullptr);

// Writes mode_map_image to `path` (a .png; any extension core/image_io writes).
void write_mode_map(const EncodedTexture& texture, const std::string& path, const Image* underlay = nullptr);

}  // namespace blocklab::munkberg
