// `rgbe`: Greg Ward's shared-exponent RGBE pixels, 32 bpp (G. Ward, "Real Pixels", Graphics Gems II, 1991; the
// Radiance .hdr pixel). Baseline of Banterle et al. 2008 (Table 1) and Wang et al. 2007 (Table 2).
//
// Block layout (64 bytes): 16 texels in the BCn order i = x + 4y, each 4 bytes R, G, B, E at offset 4 * i.
// Texel encode (m = max(R, G, B)):
//   m < 1e-32 (Ward's threshold)  -> (0, 0, 0, 0)
//   otherwise m = f * 2^e with f in [0.5, 1) (frexp); byte_c = floor(c * 256 / 2^e); E = e + 128.
// Texel decode: E == 0 -> 0, else c = (byte_c + offset) * 2^(E - 136) with offset 0 (option decode_offset "none",
// the default, as in the common rgbe.c reader) or 0.5 ("half", as Radiance's own colr_color does).
#pragma once

#include <cstdint>

#include "core/blocks.h"
#include "formats/format.h"

namespace blocklab {

constexpr int kRgbeBlockBytes = kBlockTexels * 4;   // 16 texels x (R, G, B, E) = 64

// Ward's zero threshold: a texel whose largest channel is below it is stored as (0, 0, 0, 0).
constexpr double kRgbeZeroThreshold = 1e-32;

// Reconstruction offset added to each stored mantissa byte by the decoder.
enum class RgbeDecodeOffset { none, half };

// The registry entry.
const Format& rgbe_format();

// One texel. Precondition: channels finite and non-negative (the input policy); anything else is mapped to the
// nearest storable value (NaN and negatives -> 0, +Inf -> saturated) so the function never has undefined behaviour.
void encode_rgbe_texel(float red, float green, float blue, std::uint8_t rgbe[4]);
void decode_rgbe_texel(const std::uint8_t rgbe[4], RgbeDecodeOffset offset, float rgb[3]);

void pack_rgbe_block(const BlockTexels& texels, std::uint8_t* packed);
BlockTexels unpack_rgbe_block(const std::uint8_t* packed, RgbeDecodeOffset offset);   // alpha = 1

}  // namespace blocklab
