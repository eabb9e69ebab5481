// `downscaled`: a standard BCn format (bc1, bc3, bc4, bc7) at a reduced resolution, the "scaled DXTC" baseline of
// Mavridis & Papaioannou 2012 (section 4, Table 4 "gain over the scaled DXTC format"): the texture is shrunk with a
// Lanczos filter so that the inner format's blocks cost the target rate (inner bpp * scale^2 per texel of the true
// size), and decoded by the inner decoder followed by bilinear upscaling to the true size.
//
// Options: inner = bc1 | bc3 | bc4 | bc7; scale in [0.01, 1] (reduced side = round(side * scale), at least 1) or
// bpp > 0 (then scale = sqrt(bpp / inner bpp), overriding scale); source = rgb | bt601_luma (bt601_luma codes the
// BT.601 luma as a one-channel image, the gray baselines); lanczos_lobes = 1..8 (3: Lanczos-3); inner_preset = fast |
// medium | thorough (the inner format's preset; the presets of this format set it). Side data: `reduced_size` =
// [width, height] of the stored blocks (Format::stored_block_count). Resampling: core/resample.h. Decisions:
// formats/downscaled/README.md.
#pragma once

#include "formats/format.h"

namespace blocklab {

const Format& downscaled_format();

}  // namespace blocklab
