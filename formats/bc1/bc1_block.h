// One BC1 (DXT1) block: the symbolic parameters, packing to / unpacking from the 8 bytes, the templated decoder
// used inside search errors, and the spec-literal reference decoder (the oracle, kept in its own file).
//
// Spec: Khronos Data Format Specification, S3TC chapter, BC1 (SPECS.md 2.1): bytes 0-1 color0 (RGB565, u16
// little-endian), bytes 2-3 color1, bytes 4-7 a 32-bit little-endian index word with texel i's 2-bit code in bits
// 2i+1..2i (texel i = x + 4y). Mode rule: color0 > color1 as PACKED u16 -> 4 colours; color0 <= color1 -> 3 colours
// + black (code 3). blocklab decodes BC1 as opaque RGB (code 3 of the 3-colour mode is opaque black; alpha = 1).
// Decoded values follow the reference decoding of formats/common/s3tc_common.h.
#pragma once

#include <array>
#include <cstdint>

#include "core/blocks.h"
#include "formats/common/s3tc_common.h"

namespace blocklab {

// The parameters of a BC1 colour block. A Params value is "consistent" when its mode agrees with the packed order
// of its endpoints (four_color <=> packed color0 > color1); unpack always gives a consistent value, and
// pack_bc1_block rejects an inconsistent one (canonicalise_bc1 fixes one up without changing the decoded texels).
struct Bc1Params {
  std::array<std::array<int, 3>, 2> endpoints{};   // endpoints[e] = {R5 0..31, G6 0..63, B5 0..31}
  std::array<std::uint8_t, 16> indices{};           // 2-bit codes, texel i = x + 4y
  Bc1Mode mode = Bc1Mode::four_color;
};

// Packed RGB565 word of endpoint e.
inline unsigned bc1_endpoint_word(const Bc1Params& params, int e) {
  return pack_rgb565(params.endpoints[e][0], params.endpoints[e][1], params.endpoints[e][2]);
}

// Writes the 8 bytes. Throws Error("bc1: ...") when a field is out of range or the mode disagrees with the packed
// endpoint order.
void pack_bc1_block(const Bc1Params& params, std::uint8_t* bytes);
// Reads the 8 bytes (never fails: every bit pattern is a valid BC1 block). pack(unpack(b)) == b for every b.
Bc1Params unpack_bc1_block(const std::uint8_t* bytes);

// Writes the colour half of a block whose colours are always decoded in 4-colour mode (BC3/DXT5): no order
// check; params.mode must be four_color (throws otherwise).
void pack_bc1_color_bits(const Bc1Params& params, std::uint8_t* bytes);
// Reads the colour half of a BC3 block: the fields as stored, mode four_color whatever the endpoint order.
Bc1Params unpack_bc3_color_bits(const std::uint8_t* bytes);

// Returns an equivalent consistent BC1 block (same decoded texels) for any endpoints/indices/mode:
//   four_color with color0 < color1: endpoints swapped, codes 0<->1 and 2<->3;
//   four_color with color0 == color1: all four colours are equal, so three_color with every code 0;
//   three_color with color0 > color1: endpoints swapped, codes 0<->1 (the midpoint and black stay).
Bc1Params canonicalise_bc1(Bc1Params params);
// The same for a BC3 colour block (always 4-colour): color0 > color1, or color0 == color1 with every code 0
// (SPECS.md 2.5 item 2: some GPUs honour the 3-colour mode in BC3, these two forms decode alike everywhere).
Bc1Params canonicalise_bc3_color(Bc1Params params);

// The search-time decoder: RGB in [0, 1] of the 16 texels from lattice endpoints given as scalars (double, Jet or
// Interval), the codes and the mode.
template <typename T>
void bc1_decode(const T endpoint0[3], const T endpoint1[3], Bc1Mode mode, const std::array<std::uint8_t, 16>& indices,
                T rgb[16][3]) {
  T palette[4][3];
  bc1_palette(endpoint0, endpoint1, mode, palette);
  for (int texel = 0; texel < 16; ++texel)
    for (int channel = 0; channel < 3; ++channel) rgb[texel][channel] = palette[indices[texel] & 3][channel];
}

// decode<double> of a Params, as float texels (alpha = 1): what Format::decode writes.
BlockTexels decode_bc1_params(const Bc1Params& params);

// The oracle: straight from the KDFS text, integer fields read bit by bit, exact fractions (alpha = 1).
BlockTexels reference_decode_bc1_block(const std::uint8_t* bytes);
// The oracle's colour half of an S3TC block (8 bytes), alpha 1: the BC1 mode rule, or the 4-colour palette for every
// endpoint order when `always_four_colors` (the colour half of BC3).
BlockTexels reference_decode_s3tc_color(const std::uint8_t* bytes, bool always_four_colors);

}  // namespace blocklab
