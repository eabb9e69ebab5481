// Shared arithmetic of the S3TC family (BC1, BC3, BC4): endpoint expansion and the palettes, written once as
// templates on the scalar type so that the same code is the search-time decoder (double, ceres::Jet,
// blocklab::Interval inside Problem errors, core/scalar.h) and the decoder behind Format::decode.
//
// Spec: Khronos Data Format Specification 1.3/1.4, chapter "S3TC Compressed Texture Image Formats" (BC1/BC3) and
// "RGTC Compressed Texture Image Formats" (BC4); SPECS.md sections 2.1, 2.2, 2.5.
//
// THE REFERENCE DECODING (one convention for every metric in blocklab, see formats/bc1/README.md)
//   * RGB565 endpoints are expanded to 8 bits by bit replication: R8 = (R5 << 3) | (R5 >> 2),
//     G8 = (G6 << 2) | (G6 >> 4) (what hardware does; SPECS.md 2.1).
//   * Interpolated palette entries are the EXACT fractions of those 8-bit values, not rounded to an integer:
//     value = (w0 * E0 + w1 * E1) / (d * 255) in [0, 1], computed in double (the numerator is an exact integer, so
//     the one division is correctly rounded) and stored as float. E.g. BC1 index 2 of a 4-colour block is
//     (2 E0 + E1) / 765. BC4/BC3-alpha endpoints are already 8-bit: value = (w0 a0 + w1 a1) / (d * 255).
//   * Relation to vendor decoders: every published vendor rule (D3D10 "ideal" truncation, D3D9/Compressonator
//     rounding, AMD's (43a+21b+32)>>6, NVIDIA's 5-bit formulas, Pillow's and NVTT's integer division) yields an
//     8-bit value within 1 LSB of this exact fraction (|vendor - 255 * value| < 1 for interpolated entries, and
//     equality for the endpoints themselves, black and the BC4 constants 0 and 255). Tests check this against
//     Pillow and nvdecompress.
#pragma once

#include <ceres/jet.h>

#include <array>
#include <cmath>
#include <cstdint>

#include "core/interval.h"
#include "core/scalar.h"

namespace blocklab {

constexpr int kBc1BlockBytes = 8;
constexpr int kBc4BlockBytes = 8;
constexpr int kBc3BlockBytes = 16;

// ---- bit replication (integers) ---------------------------------------------------------------------------------
constexpr int expand_5bit(int value) { return (value << 3) | (value >> 2); }
constexpr int expand_6bit(int value) { return (value << 2) | (value >> 4); }
// Expansion of channel `channel` (0 = R, 1 = G, 2 = B) of an RGB565 endpoint.
constexpr int expand_565_channel(int value, int channel) {
  return channel == 1 ? expand_6bit(value) : expand_5bit(value);
}
constexpr int rgb565_channel_max(int channel) { return channel == 1 ? 63 : 31; }

// RGB565 word: R in bits 15..11, G in 10..5, B in 4..0.
constexpr unsigned pack_rgb565(int r5, int g6, int b5) {
  return (static_cast<unsigned>(r5) << 11) | (static_cast<unsigned>(g6) << 5) | static_cast<unsigned>(b5);
}
inline std::array<int, 3> unpack_rgb565(unsigned word) {
  return {static_cast<int>((word >> 11) & 31u), static_cast<int>((word >> 5) & 63u), static_cast<int>(word & 31u)};
}

// ---- floor for every scalar type (the only non-arithmetic step of the expansion) -------------------------------
inline double floor_scalar(double x) { return std::floor(x); }
inline float floor_scalar(float x) { return std::floor(x); }
// Jet: ceres::floor keeps the value's floor and a zero derivative (floor is piecewise constant).
template <typename T, int N>
ceres::Jet<T, N> floor_scalar(const ceres::Jet<T, N>& x) { return ceres::floor(x); }
// Interval: floor is monotone and exact on doubles, so [floor lo, floor hi] encloses floor over the interval.
inline Interval floor_scalar(const Interval& x) {
  if (is_empty(x)) return x;   // no information stays no information
  return Interval(std::floor(x.lower()), std::floor(x.upper()));
}

// Bit replication on a scalar holding a lattice value (exact at integer points: 8 v + floor(v / 4) equals
// (v << 3) | (v >> 2) for v in 0..31, and 4 v + floor(v / 16) equals (v << 2) | (v >> 4) for v in 0..63).
template <typename T>
T expand_565_scalar(const T& value, int channel) {
  if (channel == 1) return T(4.0) * value + floor_scalar(value / T(16.0));
  return T(8.0) * value + floor_scalar(value / T(4.0));
}

// ---- palettes ---------------------------------------------------------------------------------------------------
enum class Bc1Mode : std::uint8_t { four_color = 0, three_color = 1 };
enum class Bc4Mode : std::uint8_t { eight_value = 0, six_value = 1 };

// Palette entry k as (w0, w1, d): value = (w0 * E0 + w1 * E1) / d; d = 0 marks a constant entry (w0 / 255).
struct PaletteWeights {
  int w0, w1, d;
};

// KDFS S3TC: 4-colour {C0, C1, (2C0+C1)/3, (C0+2C1)/3}; 3-colour {C0, C1, (C0+C1)/2, black}.
constexpr PaletteWeights bc1_palette_weights(Bc1Mode mode, int index) {
  if (mode == Bc1Mode::four_color) {
    return index == 0 ? PaletteWeights{1, 0, 1}
         : index == 1 ? PaletteWeights{0, 1, 1}
         : index == 2 ? PaletteWeights{2, 1, 3}
                      : PaletteWeights{1, 2, 3};
  }
  return index == 0 ? PaletteWeights{1, 0, 1}
       : index == 1 ? PaletteWeights{0, 1, 1}
       : index == 2 ? PaletteWeights{1, 1, 2}
                    : PaletteWeights{0, 0, 0};   // code 3 of the 3-colour mode: black (constant 0)
}

// KDFS RGTC: 8-value {a0, a1, ((7-k) a0 + k a1)/7 for codes 2..7 with k = code - 1}; 6-value {a0, a1,
// ((5-k) a0 + k a1)/5 for codes 2..5 with k = code - 1, code 6 = 0, code 7 = 255 (1.0)}.
constexpr PaletteWeights bc4_palette_weights(Bc4Mode mode, int index) {
  if (index == 0) return {1, 0, 1};
  if (index == 1) return {0, 1, 1};
  if (mode == Bc4Mode::eight_value) return {8 - index, index - 1, 7};
  if (index <= 5) return {6 - index, index - 1, 5};
  return index == 6 ? PaletteWeights{0, 0, 0} : PaletteWeights{255, 0, 0};   // constants 0 and 255 (w0 / 255)
}

// One palette value in [0, 1] from 8-bit endpoint values E0, E1 (any scalar type), the reference decoding above.
template <typename T>
T palette_value(const PaletteWeights& weights, const T& e0, const T& e1) {
  // Constant entries (BC1 black, BC4 0 and 255) do not depend on the endpoints.
  if (weights.d == 0) return T(weights.w0 / 255.0);
  return (T(static_cast<double>(weights.w0)) * e0 + T(static_cast<double>(weights.w1)) * e1) /
         T(static_cast<double>(weights.d) * 255.0);
}

// BC1 palette (4 entries x RGB, in [0, 1]) from RGB565 lattice endpoints given as scalars (integers for decoding,
// points or boxes of the lattice for searches).
template <typename T>
void bc1_palette(const T endpoint0[3], const T endpoint1[3], Bc1Mode mode, T palette[4][3]) {
  T expanded0[3], expanded1[3];
  for (int channel = 0; channel < 3; ++channel) {
    expanded0[channel] = expand_565_scalar(endpoint0[channel], channel);
    expanded1[channel] = expand_565_scalar(endpoint1[channel], channel);
  }
  for (int index = 0; index < 4; ++index)
    for (int channel = 0; channel < 3; ++channel)
      palette[index][channel] =
          palette_value(bc1_palette_weights(mode, index), expanded0[channel], expanded1[channel]);
}

// BC4 palette (8 entries in [0, 1]) from 8-bit endpoints given as scalars.
template <typename T>
void bc4_palette(const T& endpoint0, const T& endpoint1, Bc4Mode mode, T palette[8]) {
  for (int index = 0; index < 8; ++index)
    palette[index] = palette_value(bc4_palette_weights(mode, index), endpoint0, endpoint1);
}

}  // namespace blocklab
