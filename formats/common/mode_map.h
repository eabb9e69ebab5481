// Per-block mode usage of any block format: the share of blocks each mode wins and a colour-coded map, the figure
// Munkberg et al. 2008 draw in Figure 4 ("the color-coded images to the right illustrate the usage of the
// algorithms in different image regions"), for every format whose encoder records EncodedTexture::block_modes
// (formats/common/block_codec.h records it for every block format).
//
// Palette: mode index k takes colour k of the Okabe-Ito palette (Okabe & Ito 2008, "Color Universal Design"; the
// eight colours stay distinguishable under the common colour-vision deficiencies), in Format::modes() order:
//   0 orange, 1 sky blue, 2 bluish green, 3 yellow, 4 blue, 5 vermillion, 6 reddish purple, 7 grey.
// Formats with more than eight modes reuse the palette at half brightness for indices 8..15 (none has so far).
// With an underlay image the colour is scaled by 0.35 + 0.65 * (Reinhard-tone-mapped, gamma-2.2 luminance of the
// underlay texel), so the image's structure shows through; without, every block is a flat 4x4 patch of its colour.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/image.h"
#include "formats/format.h"

namespace blocklab {

using ModeColour = std::array<float, 3>;   // linear RGB in [0, 1]

// Colour of mode index `mode` (see the palette above). Error for mode >= 16.
ModeColour mode_colour(std::size_t mode);

// Fraction of the texture's blocks per mode, in Format::modes() order (`mode_names`); sums to 1. Error when the
// texture records no block modes, when their count is not the block count, or when an index is out of range.
std::vector<double> mode_shares(const EncodedTexture& texture, const std::vector<std::string>& mode_names);

// "name=share;name=share" in mode order with shares to 4 decimals (the CSV form of mode_shares).
std::string mode_shares_text(const std::vector<double>& shares, const std::vector<std::string>& mode_names);

// texture.width x texture.height RGB image of the map; `underlay` (optional) must have the texture's size.
Image mode_map_image(const EncodedTexture& texture, const std::vector<std::string>& mode_names,
                     const Image* underlay = nullptr);

// One line per mode: "<name>: <colour name> (r, g, b), <share>%", for a legend beside the written map.
std::string mode_map_legend(const std::vector<double>& shares, const std::vector<std::string>& mode_names);

}  // namespace blocklab
