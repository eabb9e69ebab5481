// `munkberg`: the 8 bpp HDR shape-transform format of Munkberg, Clarberg, Hasselgren, Akenine-Moeller, "Practical
// HDR Texture Compression", CGF 27(6), 2008 (/work/shared/papers/munkberg2008_practical_hdr_texture_compression.txt):
// logYuv (eq. 2, black level eq. 3), 128-bit blocks whose prefix-coded mode selector chooses shape II (the 2006
// layout: 8-bit log-luminance endpoints, 4-bit indices, 2x1-subsampled shape-transform chroma), shape I (3-bit
// luminance indices, one chroma index per texel) or, with the option `modes`, section 6's rejected modes extended
// S3TC and two-plane luminance. Layout: munkberg_layout.h; decoding: munkberg_block.h, ext_s3tc_block.h,
// two_plane_block.h; mode table: munkberg_modes.h; options and decisions: formats/munkberg/README.md.
#pragma once

#include "formats/format.h"

namespace blocklab {

const Format& munkberg_format();

}  // namespace blocklab
