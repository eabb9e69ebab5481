// Packing and unpacking of one `fp16` block: 16 texels x RGB as IEEE 754 binary16 (IEEE 754-2008 section 3.6,
// the OpenEXR "half" type), little-endian, texel order i = x + 4y (formats/fp16/fp16_format.h).
//
// Conversion float -> half is Imath::half's constructor: round to nearest, ties to even (Imath 3.1 half.h, both the
// F16C path and the portable path), including the half subnormal range down to 2^-24. Conversion half -> float is
// exact, so every finite half value survives a round trip bit for bit.
#include <Imath/half.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "formats/fp16/fp16_format.h"

namespace blocklab {

namespace {

constexpr float kLargestFiniteHalf = 65504.0f;   // (2 - 2^-10) * 2^15
constexpr const char* kChannelNames = "RGB";

}  // namespace

void pack_fp16_block(const BlockTexels& texels, std::uint8_t* packed) {
  for (int texel = 0; texel < kBlockTexels; ++texel) {
    for (int channel = 0; channel < 3; ++channel) {
      float value = texels.rgba[texel][channel];
      // NaN has no meaning as a colour; the input policy removes it before encoding, so this is a caller bug.
      if (std::isnan(value))
        fail("fp16", "texel " + std::to_string(texel) + " channel " + kChannelNames[channel] +
                         " is NaN (apply the input policy before encoding)");
      // Never write Inf: magnitudes above the largest finite half (including +-Inf) clamp to +-65504. Values in
      // (65504, 65520) would round to 65504 anyway; from 65520 up round-to-nearest would give Inf.
      if (value > kLargestFiniteHalf) value = kLargestFiniteHalf;
      if (value < -kLargestFiniteHalf) value = -kLargestFiniteHalf;
      // The input policy makes values non-negative; a negative value that still arrives keeps its sign (half is
      // signed), and -0 stays -0 (0x8000).
      const Imath::half half_value(value);   // round to nearest, ties to even
      const unsigned short bits = half_value.bits();
      const int offset = (3 * texel + channel) * 2;
      packed[offset + 0] = static_cast<std::uint8_t>(bits & 0xFFu);          // little-endian: low byte first
      packed[offset + 1] = static_cast<std::uint8_t>((bits >> 8) & 0xFFu);
    }
  }
}

BlockTexels unpack_fp16_block(const std::uint8_t* packed) {
  BlockTexels texels;
  for (int texel = 0; texel < kBlockTexels; ++texel) {
    for (int channel = 0; channel < 3; ++channel) {
      const int offset = (3 * texel + channel) * 2;
      const unsigned short bits =
          static_cast<unsigned short>(packed[offset] | (static_cast<unsigned>(packed[offset + 1]) << 8));
      // Exponent field all ones = Inf or NaN: the packer never writes them, so the block is corrupt.
      if (!fp16_bits_are_finite(bits))
        fail("fp16", "texel " + std::to_string(texel) + " channel " + kChannelNames[channel] +
                         " holds a non-finite half (bits " + std::to_string(bits) + ")");
      Imath::half half_value;
      half_value.setBits(bits);
      texels.rgba[texel][channel] = static_cast<float>(half_value);   // exact: every half is a float
    }
    texels.rgba[texel][3] = 1.0f;   // alpha is not stored
  }
  return texels;
}

}  // namespace blocklab
