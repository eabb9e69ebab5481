// One BC4 (ATI1 / RGTC1 unsigned) block, also the alpha half of BC3 (DXT5): the symbolic parameters, packing to /
// unpacking from the 8 bytes, the templated decoder used inside search errors, and the spec-literal reference
// decoder (the oracle, in bc4_reference_decode.cpp).
//
// Spec: Khronos Data Format Specification, RGTC chapter "BC4 unsigned" and S3TC chapter "BC3" alpha (SPECS.md 2.2):
// byte 0 red0 (u8), byte 1 red1 (u8), bytes 2-7 a 48-bit little-endian index field with texel i's 3-bit code in
// bits 3i+2..3i. red0 > red1 -> 8 values (6 interpolated by sevenths); red0 <= red1 -> 6 values (4 interpolated by
// fifths) + code 6 = 0 and code 7 = 1.0. Decoded values follow formats/common/s3tc_common.h (exact fractions).
#pragma once

#include <array>
#include <cstdint>

#include "formats/common/s3tc_common.h"

namespace blocklab {

// A Params value is "consistent" when its mode agrees with the endpoint order (eight_value <=> red0 > red1).
struct Bc4Params {
  std::array<int, 2> endpoints{};          // red0, red1 in 0..255
  std::array<std::uint8_t, 16> indices{};  // 3-bit codes, texel i = x + 4y
  Bc4Mode mode = Bc4Mode::eight_value;
};

// Writes the 8 bytes; throws Error("<who>: ...") on out-of-range fields or a mode that disagrees with the order.
void pack_bc4_block(const Bc4Params& params, std::uint8_t* bytes, const char* who = "bc4");
// Reads the 8 bytes (every bit pattern is valid). pack(unpack(b)) == b for every b.
Bc4Params unpack_bc4_block(const std::uint8_t* bytes);

// An equivalent consistent block (same decoded values):
//   eight_value with red0 < red1: endpoints swapped and codes mirrored (0<->1, k<->9-k for k in 2..7);
//   eight_value with red0 == red1: every value equals red0, so six_value with every code 0;
//   six_value with red0 > red1: endpoints swapped, codes 0<->1 and k<->7-k for k in 2..5 (6 and 7 stay).
Bc4Params canonicalise_bc4(Bc4Params params);

// The search-time decoder: the 16 values in [0, 1] from endpoints given as scalars (double, Jet or Interval).
template <typename T>
void bc4_decode(const T& endpoint0, const T& endpoint1, Bc4Mode mode, const std::array<std::uint8_t, 16>& indices,
                T values[16]) {
  T palette[8];
  bc4_palette(endpoint0, endpoint1, mode, palette);
  for (int texel = 0; texel < 16; ++texel) values[texel] = palette[indices[texel] & 7];
}

// decode<double> of a Params, as float values in [0, 1].
std::array<float, 16> decode_bc4_params(const Bc4Params& params);

// The oracle: straight from the KDFS text, exact fractions.
std::array<float, 16> reference_decode_bc4_block(const std::uint8_t* bytes);

}  // namespace blocklab
