// The BC3 oracle: a plain transcription of the Khronos Data Format Specification, S3TC chapter "BC3" (SPECS.md 2.2)
// with blocklab's reference decoding (exact fractions, formats/common/s3tc_common.h). The alpha half is decoded by
// the BC4 oracle (KDFS defines the BC3 alpha block and BC4 identically), the colour half by the BC1 oracle's colour
// decoder with the 4-colour palette forced (BC3 ignores the endpoint order). No code is shared with the search-time
// decoder.
#include <cstdint>

#include "formats/bc3/bc3_block.h"

namespace blocklab {

BlockTexels reference_decode_bc3_block(const std::uint8_t* bytes) {
  const std::array<float, 16> alpha = reference_decode_bc4_block(bytes);
  // "RGB0, RGB1, (2 RGB0 + RGB1)/3, (RGB0 + 2 RGB1)/3" for every endpoint order in BC3.
  BlockTexels texels = reference_decode_s3tc_color(bytes + 8, /*always_four_colors=*/true);
  for (int i = 0; i < 16; ++i) texels.rgba[i][3] = alpha[i];
  return texels;
}

}  // namespace blocklab
