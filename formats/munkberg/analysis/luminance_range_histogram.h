// Figure 8 of Munkberg et al. 2008 (section 7.3): the distribution over 4x4 blocks of the log-luminance range
// max(Ybar) - min(Ybar), Ybar = log2 Y of eq. 2, black texels (Y = 0, the eq. 3 black level) excluded.
//
// Precision equivalence (section 7.3, eq. 16): k-bit uniform quantisation of log-luminance over the half range
// [2^-16, 2^16] (32 log2 units) has a maximum error of 32 / 2^(k+1); the 4-bit per-texel index of the 2006 luminance
// encoding over a block's range R has R / 2^(4+1). The block is at least as precise as k bits when
// R <= 32 * 2^4 / 2^k = 2^(9 - k): R <= 0.5 is 10 bits (the paper: 51.0 % of blocks), R <= 2 is 8 bits (84.7 %),
// R <= 8 is 6 bits (99.8 %).
//
// Blocks follow core/blocks.h (row-major, clamp-to-edge padding, which repeats texels and never changes a range).
// A block whose 16 texels are all black has no range and is counted apart.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/munkberg/munkberg_color_spaces.h"
#include "core/image.h"

namespace blocklab::munkberg {

// log2 units the half type spans (section 7.3: "approximately [2^-16, 2^16]") and the index bits of a block.
constexpr double kHalfLogLuminanceSpan = 32.0;
constexpr int kLuminanceIndexBits = 4;

// R such that a block of range <= R is at least as precise as `bits`-bit log-luminance (see above); bits in [1, 30].
double range_for_precision_bits(int bits);

struct BlockLuminanceRanges {
  std::vector<double> ranges;        // one per block with at least one non-black texel, in block order
  std::size_t blocks = 0;            // all blocks of the image
  std::size_t black_blocks = 0;      // blocks with only black texels (no range)
  std::size_t black_texels = 0;      // black texels inside the image
};

// Per-block ranges of log2 Y. Ybar uses core/color_spaces.h (rgb_to_logyuv, floored at 2^-28 for 0 < Y < 2^-28).
BlockLuminanceRanges block_log_luminance_ranges(const Image& image);

// Counts of ranges in bins [i w, (i + 1) w) for i < bins - 1; the last bin also takes every range >= (bins - 1) w.
// Throws Error unless bin_width > 0 (finite) and bins >= 1, or when a range is NaN.
std::vector<std::uint64_t> range_histogram(const std::vector<double>& ranges, double bin_width, int bins);

// Share (0..1) of ranges <= limit; 0 for an empty list.
double fraction_within(const std::vector<double>& ranges, double limit);

}  // namespace blocklab::munkberg
