// `bc1`: BC1 / DXT1 (S3TC), 4 bpp opaque RGB (Khronos Data Format Specification, S3TC chapter; SPECS.md 2.1).
// Block layout, mode rules and the reference decoding: formats/bc1/bc1_block.h, formats/common/s3tc_common.h.
// Encoder: formats/common/s3tc_color_fit.h. Decisions and options: formats/bc1/README.md.
//
// Options: search = fast | default | exhaustive; weights = "r,g,b" per-channel error weights (default "1,1,1");
// solver = builtin (the only value until the solver library is wired). Alpha of the source is ignored: the decoded
// image is RGB (a 4-channel source decodes as 3 channels), code 3 of the 3-colour mode is opaque black.
#pragma once

#include "formats/format.h"

namespace blocklab {

const Format& bc1_format();

}  // namespace blocklab
