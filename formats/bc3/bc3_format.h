// `bc3`: BC3 / DXT5 (S3TC), 8 bpp RGBA: a BC4-style alpha block plus a 4-colour BC1 colour block (Khronos Data
// Format Specification, S3TC chapter; SPECS.md 2.2, 2.5). Block layout and reference decoding:
// formats/bc3/bc3_block.h; colour encoder formats/common/s3tc_color_fit.h (4-colour only, color0 > color1 always),
// alpha encoder formats/bc4/bc4_encoder.h.
//
// Options: search = fast | default | exhaustive (colour and alpha), weights = "r,g,b" colour error weights,
// solver = builtin. Alpha is the source's alpha (1 for sources without alpha); colour error is not weighted by
// alpha. The decoded image has the source's channel count (alpha present only for 4-channel sources).
#pragma once

#include "formats/format.h"

namespace blocklab {

const Format& bc3_format();

}  // namespace blocklab
