// Ward's RGBE texel encoding and decoding (G. Ward, "Real Pixels", Graphics Gems II, 1991, pp. 80-83; the pixel of
// the Radiance .hdr format) and the packing of 16 texels into one 64-byte block.
//
// Exactness: for m = max(R, G, B) = f * 2^e, Ward's scale f * 256 / m equals 2^(8 - e) exactly, so
// byte_c = floor(c * 2^(8 - e)) is computed here with ldexp (a power-of-two scaling, exact in double) and matches
// the float arithmetic of Ward's code bit for bit without depending on how a compiler evaluates f * 256 / m.
// Decoding byte * 2^(E - 136) is exact in float for every byte and E in [1, 255] (the smallest result,
// 1 * 2^-135, is a float subnormal; with the 0.5 offset, (2 * byte + 1) * 2^-136 is too).
//
// Error bound (decode_offset "none"): every channel is truncated by less than one unit 2^(e - 8), so
// 0 <= c - decoded < 2^(e - 8) <= 2^-7 * m; with "half" the error is at most half a unit, <= 2^-8 * m (in both cases
// below 2^-8 of 2^e, the power of two just above m).
#include <algorithm>
#include <cfloat>
#include <cmath>

#include "formats/rgbe/rgbe_format.h"

namespace blocklab {

namespace {

constexpr int kExponentBias = 128;       // E = e + 128
constexpr int kMantissaBits = 8;         // bytes are the top 8 bits of the mantissa: c * 2^(8 - e)
constexpr int kLargestExponent = 127;    // E = 255, the largest byte

// Maps a channel outside the precondition to the nearest storable value.
float storable_channel(float value) {
  if (!(value > 0.0f)) return 0.0f;         // NaN and negatives (and -0) cannot be stored: 0
  if (value > FLT_MAX) return FLT_MAX;      // +Inf: saturates like any value >= 2^127 below
  return value;
}

std::uint8_t mantissa_byte(float channel, int exponent) {
  const double scaled = std::ldexp(static_cast<double>(channel), kMantissaBits - exponent);   // exact
  // floor as in Ward's (unsigned char) cast of a non-negative value; the max channel gives f * 256 in [128, 256).
  // Only when the exponent was clamped (m >= 2^127) can `scaled` reach 256 or more: saturate at 255.
  return static_cast<std::uint8_t>(std::min(255.0, std::floor(scaled)));
}

}  // namespace

void encode_rgbe_texel(float red, float green, float blue, std::uint8_t rgbe[4]) {
  red = storable_channel(red);
  green = storable_channel(green);
  blue = storable_channel(blue);
  const float largest = std::max(red, std::max(green, blue));
  // Ward's threshold (compared in double, as his float-vs-double-literal comparison does): too small to store, and
  // E = 0 is reserved for zero. Above it, e >= -106, so E >= 22 and a stored texel never has E == 0.
  if (static_cast<double>(largest) < kRgbeZeroThreshold) {
    rgbe[0] = rgbe[1] = rgbe[2] = rgbe[3] = 0;
    return;
  }
  int exponent = 0;
  std::frexp(static_cast<double>(largest), &exponent);   // largest = f * 2^exponent, f in [0.5, 1)
  // Exponent range: floats below 2^127 give exponent <= 127 (E <= 255). Floats in [2^127, FLT_MAX] would need
  // E = 256, which does not fit a byte: clamp to E = 255 and saturate the bytes, i.e. such values are stored as
  // at most 255 * 2^119 (~1.7e38) per channel. Only float sources (EXR float, PFM) can reach this.
  exponent = std::min(exponent, kLargestExponent);
  rgbe[0] = mantissa_byte(red, exponent);
  rgbe[1] = mantissa_byte(green, exponent);
  rgbe[2] = mantissa_byte(blue, exponent);
  rgbe[3] = static_cast<std::uint8_t>(exponent + kExponentBias);
}

void decode_rgbe_texel(const std::uint8_t rgbe[4], RgbeDecodeOffset offset, float rgb[3]) {
  // E == 0 means zero whatever the mantissa bytes hold (Ward); so every 4-byte pattern decodes to a finite value.
  if (rgbe[3] == 0) {
    rgb[0] = rgb[1] = rgb[2] = 0.0f;
    return;
  }
  const int unit_exponent = static_cast<int>(rgbe[3]) - (kExponentBias + kMantissaBits);   // E - 136
  // "none": byte * 2^(E-136), the common rgbe.c reader (no centring: decoded <= original).
  // "half": (byte + 0.5) * 2^(E-136), Radiance's colr_color (centred in the truncation interval).
  const float centre = offset == RgbeDecodeOffset::half ? 0.5f : 0.0f;
  for (int channel = 0; channel < 3; ++channel)
    rgb[channel] = std::ldexp(static_cast<float>(rgbe[channel]) + centre, unit_exponent);   // exact (see header)
}

void pack_rgbe_block(const BlockTexels& texels, std::uint8_t* packed) {
  for (int texel = 0; texel < kBlockTexels; ++texel)
    encode_rgbe_texel(texels.rgba[texel][0], texels.rgba[texel][1], texels.rgba[texel][2], packed + 4 * texel);
}

BlockTexels unpack_rgbe_block(const std::uint8_t* packed, RgbeDecodeOffset offset) {
  BlockTexels texels;
  for (int texel = 0; texel < kBlockTexels; ++texel) {
    decode_rgbe_texel(packed + 4 * texel, offset, texels.rgba[texel]);
    texels.rgba[texel][3] = 1.0f;   // alpha is not stored
  }
  return texels;
}

}  // namespace blocklab
