// The extended-S3TC oracle (Munkberg et al. 2008, section 6.1; layout and decoding rules: ext_s3tc_block.h file
// comment), transcribed from the table with bits read one at a time; it shares no code with pack/unpack/decode on
// purpose, tests compare the two bit for bit.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "formats/munkberg/ext_s3tc_block.h"
#include "formats/munkberg/reference_decode_bits.h"

namespace blocklab::munkberg {

BlockTexels reference_decode_ext_s3tc(const std::uint8_t* bytes, ExtS3tcSpace space) {
  // [3, 26) endpoint 0: 8, 8, 7 bits; [26, 49) endpoint 1.
  const unsigned a[3] = {reference_field(bytes, 3, 8), reference_field(bytes, 11, 8), reference_field(bytes, 19, 7)};
  const unsigned b[3] = {reference_field(bytes, 26, 8), reference_field(bytes, 34, 8), reference_field(bytes, 42, 7)};
  const int maxcode[3] = {255, 255, 127};
  BlockTexels texels;
  for (int i = 0; i < 16; ++i) {
    // Texel 0: 4 bits at 49 (anchor, MSB 0); texel i >= 1: 5 bits at 53 + 5 (i - 1).
    const int l =
        static_cast<int>(i == 0 ? reference_field(bytes, 49, 4) : reference_field(bytes, 53 + 5 * (i - 1), 5));
    const double w0 = 31 - l, w1 = l;
    if (space == ExtS3tcSpace::rgb) {
      for (int c = 0; c < 3; ++c) {
        // Code 0 is 0; otherwise 2^(-16 + 32 code / maxcode).
        const double va = a[c] == 0 ? 0.0 : std::exp2(-16.0 + (32.0 * a[c]) / maxcode[c]);
        const double vb = b[c] == 0 ? 0.0 : std::exp2(-16.0 + (32.0 * b[c]) / maxcode[c]);
        texels.rgba[i][c] = static_cast<float>((w0 * va + w1 * vb) / 31.0);
      }
    } else {
      const long q = static_cast<long>(31 - l) * a[0] + static_cast<long>(l) * b[0];
      // Eq. (3): q == 0 is true black.
      const double y = q == 0 ? 0.0 : std::exp2(-16.0 + (32.0 * static_cast<double>(q)) / (255.0 * 31.0));
      const double u = (w0 * (a[1] / 255.0) + w1 * (b[1] / 255.0)) / 31.0;
      const double v = (w0 * (a[2] / 127.0) + w1 * (b[2] / 127.0)) / 31.0;
      texels.rgba[i][0] = static_cast<float>((v * y) / 0.299);
      texels.rgba[i][1] = static_cast<float>((std::max(0.0, 1.0 - u - v) * y) / 0.587);
      texels.rgba[i][2] = static_cast<float>((u * y) / 0.114);
    }
    texels.rgba[i][3] = 1.0f;
  }
  return texels;
}

}  // namespace blocklab::munkberg
