// Log-domain refinement of a tone-mapped BC1/BC3 colour block (blocklab's encoder decision for the `banterle`
// format; the paper does not say how its S3TC encoder was run).
//
// WHY. The S3TC colour encoder (formats/common/s3tc_color_fit.h) minimises squared error in 8-bit code units of the
// tone-mapped texture. After the inverse TMO the metrics measure log2 error, where a channel decoded as 0 for a
// source value of 10^-3 costs (log2 10^-3 + 24)^2 ~ 200 (the 2^-24 zero rule), while the same code-unit error on a
// bright texel costs almost nothing. Measured on ../shared/data/hdr/ennis.hdr at 4 bpp before this step: 2.9 % of
// the samples decoded to 0 carried 89 % of the squared log2[RGB] error.
//
// WHAT (the block's bytes stay a valid block of the same kind):
//   1. Every texel takes the palette entry whose DECODED HDR colour (Listing 1 through the LUT, residual 0) is
//      nearest in sum_RGB (log2 max(src, 2^-24) - log2 max(out, 2^-24))^2; ties go to the lower index.
//   2. Blocks that still have a texel with error > kCatastrophicError (4 = two stops on one channel) get a
//      hill climb of the six RGB565 endpoint coordinates by +-1 with the same error (and step 1 after each move),
//      at most kMaxPasses sweeps, first strictly improving move taken. Endpoint order may flip; the result is
//      canonicalised (canonicalise_bc1 / canonicalise_bc3_color), which keeps the decoded texels.
// Deterministic (fixed order, strict improvements), per block, no shared state.
#pragma once

#include "core/blocks.h"
#include "formats/banterle/itmo_lut.h"
#include "formats/bc1/bc1_block.h"

namespace blocklab {

constexpr double kCatastrophicError = 4.0;

// `source`: the original HDR texels of the block. `bc3`: the block is a BC3 colour half (always 4-colour).
// Returns the refined block's log-domain error (sum over texels and channels).
double refine_color_block_log_domain(const BlockTexels& source, const ItmoLut& lut, bool bc3, Bc1Params& params);

}  // namespace blocklab
