// The BC1 oracle: a deliberately plain transcription of the Khronos Data Format Specification, S3TC chapter,
// "BC1 with no alpha" (SPECS.md 2.1), with blocklab's reference decoding (formats/common/s3tc_common.h): RGB565
// expanded by bit replication, interpolants as exact fractions. It shares no code with the search-time decoder
// (bc1_block.cpp / s3tc_common.h) on purpose: tests compare the two bit for bit.
#include <cstdint>

#include "formats/bc1/bc1_block.h"

namespace blocklab {

BlockTexels reference_decode_s3tc_color(const std::uint8_t* bytes, bool always_four_colors) {
  // "color0 and color1 are 16-bit unsigned integers stored little-endian."
  const unsigned color0 = static_cast<unsigned>(bytes[0]) + 256u * static_cast<unsigned>(bytes[1]);
  const unsigned color1 = static_cast<unsigned>(bytes[2]) + 256u * static_cast<unsigned>(bytes[3]);
  // "bits is a 32-bit unsigned integer, from which a two-bit control code is extracted for a texel at location
  // (x, y) in the block using: code(x, y) = bits[2 * (4 * y + x) + 1 .. 2 * (4 * y + x) + 0]."
  const unsigned long bits = static_cast<unsigned long>(bytes[4]) + 256ul * bytes[5] + 65536ul * bytes[6] +
                             16777216ul * bytes[7];

  // RGB565: red in the 5 most significant bits, then 6 bits of green, then 5 of blue; each widened to 8 bits by
  // replicating its top bits into the vacated low bits.
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
        // Each palette entry as an exact fraction numerator / denominator of 8-bit code values.
        int numerator, denominator;
        if (always_four_colors || color0 > color1) {
          // "color0 > color1" (and every endpoint order in BC3): RGB0, RGB1, (2 RGB0 + RGB1) / 3, (RGB0 + 2 RGB1) / 3.
          if (code == 0) { numerator = rgb0[c]; denominator = 1; }
          else if (code == 1) { numerator = rgb1[c]; denominator = 1; }
          else if (code == 2) { numerator = 2 * rgb0[c] + rgb1[c]; denominator = 3; }
          else { numerator = rgb0[c] + 2 * rgb1[c]; denominator = 3; }
        } else {
          // "color0 <= color1": RGB0, RGB1, (RGB0 + RGB1) / 2, black.
          if (code == 0) { numerator = rgb0[c]; denominator = 1; }
          else if (code == 1) { numerator = rgb1[c]; denominator = 1; }
          else if (code == 2) { numerator = rgb0[c] + rgb1[c]; denominator = 2; }
          else { numerator = 0; denominator = 1; }
        }
        // To [0, 1] with ONE rounding of the exact rational (dividing by 3 and then by 255 would round twice).
        texels.rgba[i][c] = static_cast<float>(static_cast<double>(numerator) / (denominator * 255.0));
      }
      texels.rgba[i][3] = 1.0f;   // BC1 without alpha: opaque
    }
  }
  return texels;
}

BlockTexels reference_decode_bc1_block(const std::uint8_t* bytes) { return reference_decode_s3tc_color(bytes, false); }

}  // namespace blocklab
