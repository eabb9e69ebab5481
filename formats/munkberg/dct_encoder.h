// Encoder of the fixed-rate DCT mode (formats/munkberg/dct_block.h; Munkberg et al. 2008, section 6.2). The block
// goes to logYuv (eq. 2; Ybar clamped to the half range, texels darker than 2^-16 aimed at true black), each channel
// is transformed and every coefficient quantised to its nearest code (nearest level for AC, nearest uniform step for
// DC: the least-squares choice per channel, the transform being orthonormal); then a coordinate descent over the
// codes (one code up or down at a time, strict improvements, `refine_passes` passes) in the block's log2[RGB] error,
// the metric the modes compete in, which the clamps, the exp2 of the luminance and the channel products make
// different from the transform-domain error. Blocks with black texels are also tried with black aimed below the
// range (kDctBlackTargetLow), which keeps more of them at the true-black bottom after quantisation.
#pragma once

#include <array>
#include <cstdint>

#include "core/blocks.h"
#include "formats/munkberg/dct_block.h"

namespace blocklab::munkberg {

// Ybar targets of texels with luminance <= 2^-16 (true black included): the bottom of the range, and the lower
// alternative tried for blocks that have such texels.
constexpr double kDctBlackTarget = kLogLumMin;
constexpr double kDctBlackTargetLow = kLogLumMin - 2.0;

using DctChannelSamples = std::array<std::array<double, kTexels>, kDctChannelCount>;

// The values the transform codes: Ybar (log2 Y clamped to 16 above; black_target for Y <= 2^-16), u, v (eq. 2; a
// black texel has grey chrominance, core/color_spaces.h). Training uses the same targets (black_target = -16).
DctChannelSamples dct_block_targets(const BlockTexels& texels, double black_target);

// Nearest code of `value` for coefficient k (DC: nearest uniform step, clamped to the range; AC: nearest level, ties
// to the lower level).
unsigned dct_nearest_code(const DctChannelTable& table, int k, double value);

// The whole mode; `error` (optional) receives the block's log2[RGB] error (block_log2_error).
DctParams encode_dct(const BlockTexels& texels, const DctTables& tables, int refine_passes, double* error = nullptr);

}  // namespace blocklab::munkberg
