// The BC3 oracle: a plain transcription of the Khronos Data Format Specification, S3TC chapter "BC3" (SPECS.md 2.2)
// with blocklab's reference decoding (exact fractions, formats/common/s3tc_common.h). The alpha half is decoded by
// the BC4 oracle (KDFS defines the BC3 alpha block and BC4 identically); the colour half is decoded here, because
// BC3 differs from BC1 in always using the 4-colour palette. No code is shared with the search-time decoder.
#include <cstdint>

#include "formats/bc3/bc3_block.h"

namespace blocklab {

BlockTexels reference_decode_bc3_block(const std::uint8_t* bytes) {
  const std::array<float, 16> alpha = reference_decode_bc4_block(bytes);
  const std::uint8_t* color_bytes = bytes + 8;
  const unsigned color0 = static_cast<unsigned>(color_bytes[0]) + 256u * color_bytes[1];
  const unsigned color1 = static_cast<unsigned>(color_bytes[2]) + 256u * color_bytes[3];
  const unsigned long bits = static_cast<unsigned long>(color_bytes[4]) + 256ul * color_bytes[5] +
                             65536ul * color_bytes[6] + 16777216ul * color_bytes[7];
  const int red0_5 = static_cast<int>(color0 / 2048u), green0_6 = static_cast<int>((color0 / 32u) % 64u),
            blue0_5 = static_cast<int>(color0 % 32u);
  const int red1_5 = static_cast<int>(color1 / 2048u), green1_6 = static_cast<int>((color1 / 32u) % 64u),
            blue1_5 = static_cast<int>(color1 % 32u);
  const int rgb0[3] = {red0_5 * 8 + red0_5 / 4, green0_6 * 4 + green0_6 / 16, blue0_5 * 8 + blue0_5 / 4};
  const int rgb1[3] = {red1_5 * 8 + red1_5 / 4, green1_6 * 4 + green1_6 / 16, blue1_5 * 8 + blue1_5 / 4};

  BlockTexels texels;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      const int i = 4 * y + x;
      const int code = static_cast<int>((bits >> (2 * i)) & 3ul);
      for (int c = 0; c < 3; ++c) {
        // "RGB0, RGB1, (2 RGB0 + RGB1)/3, (RGB0 + 2 RGB1)/3" for every endpoint order in BC3.
        int numerator, denominator;
        if (code == 0) { numerator = rgb0[c]; denominator = 1; }
        else if (code == 1) { numerator = rgb1[c]; denominator = 1; }
        else if (code == 2) { numerator = 2 * rgb0[c] + rgb1[c]; denominator = 3; }
        else { numerator = rgb0[c] + 2 * rgb1[c]; denominator = 3; }
        texels.rgba[i][c] = static_cast<float>(static_cast<double>(numerator) / (denominator * 255.0));
      }
      texels.rgba[i][3] = alpha[i];
    }
  }
  return texels;
}

}  // namespace blocklab
