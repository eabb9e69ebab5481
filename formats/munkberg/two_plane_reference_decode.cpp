// The two-plane oracle (Munkberg et al. 2008, section 6.3; layout and decoding rules: two_plane_block.h file
// comment), bits read one at a time; no code shared with pack/unpack/decode_two_plane, tests compare them bit for bit.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "formats/munkberg/two_plane_block.h"
#include "formats/munkberg/reference_decode_bits.h"

namespace blocklab::munkberg {

namespace {

// A 7-bit two's complement field.
int signed7(unsigned raw) { return raw >= 64u ? static_cast<int>(raw) - 128 : static_cast<int>(raw); }

}  // namespace

BlockTexels reference_decode_two_plane(const std::uint8_t* bytes, const ShapeSet& shapes) {
  // Plane p at 4 + 23p: offset (9 bits), dx (7, signed), dy (7, signed).
  int offset[2], dx[2], dy[2];
  for (int p = 0; p < 2; ++p) {
    offset[p] = static_cast<int>(reference_field(bytes, 4 + 23 * p, 9));
    dx[p] = signed7(reference_field(bytes, 4 + 23 * p + 9, 7));
    dy[p] = signed7(reference_field(bytes, 4 + 23 * p + 16, 7));
  }
  // Chroma as shape I: shape index at 65, u0, v0, u1, v1 at 68, 75, 82, 89; indices at 96 + 2i.
  const ShapeTemplate& shape = shapes.shapes[reference_field(bytes, 65, 3)];
  const double u0 = reference_field(bytes, 68, 7) / 127.0, v0 = reference_field(bytes, 75, 7) / 127.0;
  const double u1 = reference_field(bytes, 82, 7) / 127.0, v1 = reference_field(bytes, 89, 7) / 127.0;
  double lu[4], lv[4];
  for (int k = 0; k < 4; ++k) {
    lu[k] = std::min(1.0, std::max(0.0, (u0 + shape.along(k) * (u1 - u0)) - shape.across(k) * (v1 - v0)));
    lv[k] = std::min(1.0, std::max(0.0, (v0 + shape.along(k) * (v1 - v0)) + shape.across(k) * (u1 - u0)));
  }
  BlockTexels texels;
  for (int i = 0; i < 16; ++i) {
    const int x = i % 4, y = i / 4;
    // Mask bit of texel i >= 1 at 49 + i; texel 0 is the anchor and always takes plane 0.
    const int p = i == 0 ? 0 : static_cast<int>(reference_field(bytes, 49 + i, 1));
    double luminance = 0.0;   // offset code 0: a true-black plane
    if (offset[p] != 0) {
      double ybar = -16.0 + (32.0 * offset[p]) / 511.0 + static_cast<double>(dx[p] * (2 * x - 3) + dy[p] * (2 * y - 3)) / 32.0;
      ybar = std::min(16.0, std::max(-16.0, ybar));   // clamp to the half range
      luminance = std::exp2(ybar);
    }
    const unsigned k = reference_field(bytes, 96 + 2 * i, 2);
    texels.rgba[i][0] = static_cast<float>((lv[k] * luminance) / 0.299);
    texels.rgba[i][1] = static_cast<float>((std::max(0.0, 1.0 - lu[k] - lv[k]) * luminance) / 0.587);
    texels.rgba[i][2] = static_cast<float>((lu[k] * luminance) / 0.114);
    texels.rgba[i][3] = 1.0f;
  }
  return texels;
}

}  // namespace blocklab::munkberg
