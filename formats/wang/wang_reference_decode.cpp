// The `wang` oracle: Wang et al. 2007 decoding written straight from the paper and the DXT5 text, sharing no code
// with wang_block.h / wang_shader.h (tests compare the two bit for bit).
//
//   * DXT5 (KDFS S3TC chapter "BC3"): per half, byte 0 alpha0, byte 1 alpha1, bytes 2-7 48 bits of 3-bit alpha codes
//     (texel i in bits 3i..3i+2, little-endian), bytes 8-9 color0 and 10-11 color1 (RGB565 little-endian, R in the top
//     5 bits), bytes 12-15 32 bits of 2-bit colour codes; colour always the 4-colour palette {c0, c1, (2c0 + c1)/3,
//     (c0 + 2c1)/3} of bit-replicated 8-bit endpoints; alpha0 > alpha1: {a0, a1, ((7-k) a0 + k a1)/7, k = 1..6},
//     otherwise {a0, a1, ((5-k) a0 + k a1)/5, k = 1..4, 0, 255}.
//   * The texture unit: each interpolant rounded to the nearest 8-bit integer (integer arithmetic: (2n + d) / 2d),
//     returned as q / 255 in float.
//   * The shader (section 3.4 Table 1, eq. 7, eq. 8, eq. 4, eq. 11) in float with constants rounded once from double.
#include <cmath>
#include <cstdint>

#include "formats/wang/wang_block.h"

namespace blocklab {
namespace wang {

namespace {

unsigned read_bits(const std::uint8_t* bytes, int first_bit, int count) {
  unsigned value = 0;
  for (int k = 0; k < count; ++k) {
    const int bit = first_bit + k;
    value |= static_cast<unsigned>((bytes[bit / 8] >> (bit % 8)) & 1u) << k;
  }
  return value;
}

int round_fraction(int numerator, int denominator) { return (2 * numerator + denominator) / (2 * denominator); }

// The 16 fetched RGBA texels of one DXT5 block, as 8-bit integers.
void fetch_dxt5(const std::uint8_t* block, int texels[16][4]) {
  const int a0 = static_cast<int>(read_bits(block, 0, 8));
  const int a1 = static_cast<int>(read_bits(block, 8, 8));
  int alpha[8];
  alpha[0] = a0;
  alpha[1] = a1;
  if (a0 > a1) {
    for (int k = 1; k <= 6; ++k) alpha[k + 1] = round_fraction((7 - k) * a0 + k * a1, 7);
  } else {
    for (int k = 1; k <= 4; ++k) alpha[k + 1] = round_fraction((5 - k) * a0 + k * a1, 5);
    alpha[6] = 0;
    alpha[7] = 255;
  }
  const unsigned c0 = read_bits(block, 64, 16);
  const unsigned c1 = read_bits(block, 80, 16);
  int endpoint[2][3];
  const unsigned words[2] = {c0, c1};
  for (int e = 0; e < 2; ++e) {
    const int r5 = static_cast<int>((words[e] >> 11) & 31u);
    const int g6 = static_cast<int>((words[e] >> 5) & 63u);
    const int b5 = static_cast<int>(words[e] & 31u);
    endpoint[e][0] = (r5 << 3) | (r5 >> 2);
    endpoint[e][1] = (g6 << 2) | (g6 >> 4);
    endpoint[e][2] = (b5 << 3) | (b5 >> 2);
  }
  int color[4][3];
  for (int channel = 0; channel < 3; ++channel) {
    color[0][channel] = endpoint[0][channel];
    color[1][channel] = endpoint[1][channel];
    color[2][channel] = round_fraction(2 * endpoint[0][channel] + endpoint[1][channel], 3);
    color[3][channel] = round_fraction(endpoint[0][channel] + 2 * endpoint[1][channel], 3);
  }
  for (int i = 0; i < 16; ++i) {
    const int alpha_code = static_cast<int>(read_bits(block, 16 + 3 * i, 3));
    const int color_code = static_cast<int>(read_bits(block, 96 + 2 * i, 2));
    for (int channel = 0; channel < 3; ++channel) texels[i][channel] = color[color_code][channel];
    texels[i][3] = alpha[alpha_code];
  }
}

}  // namespace

BlockTexels reference_decode_block(const Zones& zones, LuminanceSplit split, ColorSpace space, Residual residual,
                                   const std::uint8_t* bytes) {
  int tex0[16][4], tex1[16][4];
  fetch_dxt5(bytes, tex0);
  fetch_dxt5(bytes + 16, tex1);

  // g_LRangeLowHigh = (low, high): the ranges of eq. 4 (2x6), or the 12-bit code's weights (1x12).
  float range_low, range_high;
  if (split == LuminanceSplit::two_zones) {
    range_low = static_cast<float>(zones.t1 - zones.tmin);
    range_high = static_cast<float>(zones.tmax - zones.t1);
  } else {
    range_low = static_cast<float>((zones.tmax - zones.tmin) * (63.0 / 4095.0));
    range_high = static_cast<float>((zones.tmax - zones.tmin) * (64.0 * 63.0 / 4095.0));
  }
  const bool has_residual = residual != Residual::none;
  const float r_low = has_residual ? static_cast<float>(zones.s1 - zones.smin) : 0.0f;
  const float r_mid = has_residual ? static_cast<float>(zones.s2 - zones.s1) : 0.0f;
  const float r_high = has_residual ? static_cast<float>(zones.smax - zones.s2) : 0.0f;
  const float l_min = static_cast<float>(zones.tmin);
  const float r_min = has_residual ? static_cast<float>(zones.smin) : 0.0f;
  const float l_min_plus_r_min = has_residual ? static_cast<float>(zones.tmin + zones.smin) : 0.0f;

  BlockTexels out;
  for (int i = 0; i < 16; ++i) {
    float t0[4], t1[4];
    for (int channel = 0; channel < 4; ++channel) {
      t0[channel] = static_cast<float>(tex0[i][channel]) / 255.0f;
      t1[channel] = static_cast<float>(tex1[i][channel]) / 255.0f;
    }
    const float dot = t1[0] * r_low + t1[1] * r_mid + t1[2] * r_high;
    float L;
    if (residual == Residual::s) {
      L = t0[3] * range_high + t1[3] * range_low + l_min_plus_r_min + dot;   // eq. 7 as in Table 1
    } else if (residual == Residual::ratio) {
      const float l_prime = t0[3] * range_high + t1[3] * range_low + l_min;   // eq. 4
      L = l_prime + l_prime * (dot + r_min);                                  // L' + L' T (eq. 11)
    } else {
      L = t0[3] * range_high + t1[3] * range_low + l_min;                     // eq. 4
    }
    if (L < 0.0f) L = 0.0f;
    if (space == ColorSpace::luvw) {
      out.rgba[i][0] = t0[0] * L;   // eq. 8
      out.rgba[i][1] = t0[1] * L;
      out.rgba[i][2] = t0[2] * L;
    } else {
      out.rgba[i][0] = t0[0] * L;   // eq. 10 inverted: R = U L, G = V L / 2, B = L - R - 2 G = (1 - U - V) L
      out.rgba[i][1] = t0[1] * L * 0.5f;
      float w = 1.0f - t0[0] - t0[1];
      if (w < 0.0f) w = 0.0f;
      out.rgba[i][2] = w * L;
    }
    out.rgba[i][3] = 1.0f;
  }
  return out;
}

}  // namespace wang
}  // namespace blocklab
