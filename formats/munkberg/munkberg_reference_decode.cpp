// The `munkberg` oracle: a deliberately plain transcription of the layout table (munkberg_layout.h file comment) and
// the decoding rules (munkberg_block.h file comment; Munkberg et al. 2008 eqs. 2 and 3, section 7.1). It reads the
// block one bit at a time from the bytes and shares no code with pack/unpack/decode_block on purpose: tests compare
// the two bit for bit on every block the encoder emits and on random blocks.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "formats/munkberg/munkberg_block.h"
#include "formats/munkberg/reference_decode_bits.h"

namespace blocklab::munkberg {

BlockTexels reference_decode_block(const std::uint8_t* bytes, const ShapeSet& shapes) {
  // Only shape blocks are this oracle's business (selector 0 or 1,0); callers dispatch the others.
  // Selector: bit 0 = 0 is shape II (4-bit luminance indices, 8 chroma indices for horizontal texel pairs);
  // bits 0,1 = 1,0 is shape I (3-bit luminance indices, texel 0's stored in 2 bits, 16 chroma indices).
  const bool shape_one = reference_field(bytes, 0, 1) == 1;
  const int h = shape_one ? 2 : 1;   // header start: after the selector
  // [h, h+3) shape index; then u0, v0, u1, v1 (7 bits each); then Y0, Y1 (8 bits each).
  const unsigned shape_index = reference_field(bytes, h, 3);
  const double u0 = reference_field(bytes, h + 3, 7) / 127.0;
  const double v0 = reference_field(bytes, h + 10, 7) / 127.0;
  const double u1 = reference_field(bytes, h + 17, 7) / 127.0;
  const double v1 = reference_field(bytes, h + 24, 7) / 127.0;
  const unsigned y0 = reference_field(bytes, h + 31, 8);
  const unsigned y1 = reference_field(bytes, h + 39, 8);
  const int index_bits = shape_one ? 3 : 4;
  const int n = shape_one ? 7 : 15;
  const int chroma_start = shape_one ? 96 : 112;

  const ShapeTemplate& shape = shapes.shapes[shape_index];
  double landmark_u[4], landmark_v[4];
  for (int k = 0; k < 4; ++k) {
    // L = B0 + a (B1 - B0) + b perp(B1 - B0), perp(d) = (-d_v, d_u); clamped to [0, 1].
    landmark_u[k] = std::min(1.0, std::max(0.0, (u0 + shape.along(k) * (u1 - u0)) - shape.across(k) * (v1 - v0)));
    landmark_v[k] = std::min(1.0, std::max(0.0, (v0 + shape.along(k) * (v1 - v0)) + shape.across(k) * (u1 - u0)));
  }

  BlockTexels texels;
  for (int i = 0; i < 16; ++i) {
    // Luminance indices start at h + 47; shape I's texel 0 has 2 bits (its MSB is 0), so later texels shift by -1.
    unsigned l = 0;
    if (shape_one)
      l = i == 0 ? reference_field(bytes, 49, 2) : reference_field(bytes, 51 + 3 * (i - 1), 3);
    else
      l = reference_field(bytes, 48 + index_bits * i, index_bits);
    const long q = static_cast<long>(n - static_cast<int>(l)) * y0 + static_cast<long>(l) * y1;
    // Eq. (3): the minimum log-luminance (q = 0) is true black; otherwise Y = 2^Ybar with Ybar in [-16, 16].
    double luminance = 0.0;
    if (q != 0) luminance = std::exp2(-16.0 + (32.0 * static_cast<double>(q)) / (255.0 * n));
    const int group = shape_one ? i : i / 2;
    const unsigned k = reference_field(bytes, chroma_start + 2 * group, 2);
    const double u = landmark_u[k], v = landmark_v[k];
    // Eq. (2) with Rec. 601 weights; green's factor never below 0.
    const double green_factor = std::max(0.0, 1.0 - u - v);
    texels.rgba[i][0] = static_cast<float>((v * luminance) / 0.299);
    texels.rgba[i][1] = static_cast<float>((green_factor * luminance) / 0.587);
    texels.rgba[i][2] = static_cast<float>((u * luminance) / 0.114);
    texels.rgba[i][3] = 1.0f;
  }
  return texels;
}

}  // namespace blocklab::munkberg
