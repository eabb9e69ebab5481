// The 8 bpp variant's additive luminance residual (Banterle et al. 2008, section 4.3, eq. 4: delta_a = L_ori - L_rec),
// "quantized linearly into 8 bit in the alpha channel which is subsequently compressed by DXT5".
//
// Stored: a per-texture range [lo, hi] (side data `residual_range`, two floats) and per texel a BC3 alpha value
// a in [0, 1] (formats/bc4 block, bytes 0-7 of the BC3 block). Decoded residual (float, -ffp-contract=off):
//   delta = lo + (hi - lo) * a.
// Encoder decisions (the paper gives only "quantized linearly"):
//   * Range. The residual of a bright texel can be 10^4 times the luminance of a dark one, and a linear step fitted
//     to the full range [min delta, max delta] would bury every dark texel under quantisation noise (in the log
//     domain the metrics use, a residual step larger than L ruins the texel). So the range is fitted: steps
//     s = span / 255 * 2^(-j/2), j = 0..47, each with the zero residual on a code k0 (lo = -k0 s, hi = (255 - k0) s;
//     k0 from the full range's proportion and from {0, 32, 128, 224, 255}), residuals outside the range clipped;
//     the pair with the smallest mean squared log2 luminance error on a fixed subsample (every texel, or a stride
//     giving at most 16384 of them) wins, and "no residual" (lo = hi = 0) is a candidate too.
//   * Block. fit_bc4_block (formats/bc4) on the unrounded target codes (delta - lo) / s fixes the endpoints; then each
//     texel takes the palette entry that minimises ITS log2 luminance error as the decoder computes it (any index is
//     a valid block, so this only changes which of the 8 values a texel uses; ties go to the lower index).
#pragma once

#include <cstddef>
#include <vector>

#include "formats/bc4/bc4_block.h"
#include "formats/common/s3tc_color_fit.h"   // S3tcSearch

namespace blocklab {

struct ResidualRange {
  float lo = 0.0f;
  float hi = 0.0f;
};

// The decoder's dequantisation.
inline float dequantise_residual(const ResidualRange& range, float alpha_value) {
  return range.lo + (range.hi - range.lo) * alpha_value;
}

// Fits the range on the luminances of the original texture and of the reconstruction without residual (same
// length, any order; non-finite values are not allowed).
ResidualRange fit_residual_range(const std::vector<float>& original, const std::vector<float>& reconstructed);

// One alpha block for 16 texels (original luminance, reconstructed luminance without residual).
Bc4Params encode_residual_block(const float original[16], const float reconstructed[16], const ResidualRange& range,
                                S3tcSearch search);

// The squared log2 error of a decoded luminance (reconstructed + residual, clamped at 0 as the decoder does) against
// the original, both floored at 2^-24 (metrics/zero_rule.h).
double residual_log2_error(float original, float reconstructed, float residual);

}  // namespace blocklab
