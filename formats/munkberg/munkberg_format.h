// `munkberg`: the 8 bpp HDR shape-transform format of Munkberg, Clarberg, Hasselgren, Akenine-Moeller, "Practical
// HDR Texture Compression", CGF 27(6), 2008 (/work/shared/papers/munkberg2008_practical_hdr_texture_compression.txt):
// logYuv (eq. 2, black level eq. 3), 128-bit blocks with one mode bit choosing shape II (the 2006 layout: 8-bit
// log-luminance endpoints, 4-bit indices, 2x1-subsampled shape-transform chroma) or shape I (3-bit luminance
// indices, one chroma index per texel). Layout: munkberg_layout.h; decoding: munkberg_block.h; encoder:
// munkberg_encoder.h; options and decisions: formats/munkberg/README.md.
#pragma once

#include "formats/format.h"

namespace blocklab {

const Format& munkberg_format();

}  // namespace blocklab
