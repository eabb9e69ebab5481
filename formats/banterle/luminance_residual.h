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
//   * Exact zero code. lo and hi are floats and the decoder computes lo + (hi - lo) * a in float, so the separately
//     rounded -k0 s and (255 - k0) s generally decode code k0 to a tiny non-zero residual (not 0). Every black texel
//     (colour half l = 0, LUT entry 0 = 0) then decodes to that residual: invisible to log2 error (below the 2^-24
//     floor), but on ../shared/data/hdr/v2_LowResLeftView_composited.exr (23 % black background) it is 2^-29, which
//     lowered the decoded image's smallest luminance so that mPSNR's automatic range ran to stop 29, where it is a
//     visible code value on every background texel: 17.8 dB (4 bpp: 31.2; 8 bpp with the exact zero code: 31.7). So lo is
//     moved by at most kMaxZeroUlps ulps until code k0 decodes to exactly 0.0f (zero_exact_residual_range; k0 = 0
//     and k0 = 255 are exact by construction: lo = 0, or hi = 0 and a = 1).
//   * Block. fit_bc4_block (formats/bc4) on the unrounded target codes (delta - lo) / s fixes the endpoints; then each
//     texel takes the palette entry that minimises ITS log2 luminance error as the decoder computes it (any index is
//     a valid block, so this only changes which of the 8 values a texel uses). Entries with the same log2 error
//     (both sides below the 2^-24 floor, e.g. a black texel and several entries that decode to 0 or to less than
//     2^-24) are separated by the absolute luminance error, then by the lower index: a black texel takes an entry
//     that decodes to exactly 0 whenever the palette has one.
//   * Lit black texels. A black source texel whose colour half decodes to l > 0 (BC3's colour half has no black
//     code, so a block shared with bright texels lights it) is decoded exactly by any residual <= -reconstructed,
//     but the code-unit BC4 fit aims at its exact target and may leave no entry that low. Such blocks get a second
//     BC4 fit with those targets at code 0 (= lo, also the 6-value mode's constant), and the block with the smaller
//     summed log2 error (then absolute error; the first on a tie) is kept.
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

// The range whose code k0 (0..255, a = float(k0 / 255.0)) decodes to exactly 0.0f with step `step` > 0:
// lo = float(-k0 step), hi = float((255 - k0) step), then lo moved by up to kMaxZeroUlps ulps (nearest first,
// upwards first) until dequantise_residual(range, a) == 0.0f. Returns false (range untouched) if none does (never
// observed: on 2e5 random (step, k0) pairs at most 3 ulps were needed).
constexpr int kMaxZeroUlps = 64;
bool zero_exact_residual_range(double step, int k0, ResidualRange& range);

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
