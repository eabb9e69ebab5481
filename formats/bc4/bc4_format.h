// `bc4`: BC4 / ATI1 / RGTC1 unsigned, 4 bpp, one channel (Khronos Data Format Specification, RGTC chapter;
// SPECS.md 2.2). Block layout and reference decoding: formats/bc4/bc4_block.h; encoder: formats/bc4/bc4_encoder.h.
//
// Options: channel = r | g | b | a (which source channel is stored; default r, alpha of a source without alpha is
// 1), search = fast | default | exhaustive, solver = builtin. The decoded image is a one-channel (grey) image:
// the stored value in R, G and B (core/image.h's luminance convention), so compare it with the chosen channel.
#pragma once

#include "formats/format.h"

namespace blocklab {

const Format& bc4_format();

}  // namespace blocklab
