// `fp16`: uncompressed IEEE 754 binary16 RGB, 48 bpp -- the "FP16" baseline of Wang et al. 2007 (Table 2) and the
// half-float storage OpenEXR uses (Imath::half).
//
// Block layout (96 bytes): 16 texels in the BCn order i = x + 4y, each R, G, B as one half, little-endian:
//   byte offset of channel c of texel i = (3 * i + c) * 2.
// Alpha is not stored (decoders return alpha = 1).
#pragma once

#include <cstdint>

#include "core/blocks.h"
#include "formats/format.h"

namespace blocklab {

constexpr int kFp16BlockBytes = kBlockTexels * 3 * 2;   // 16 texels x RGB x 2 bytes = 96

// The registry entry.
const Format& fp16_format();

// Packs the RGB of one block into kFp16BlockBytes bytes (round to nearest even; magnitudes above 65504 clamp to
// 65504, so Inf is never written). Throws Error on NaN.
void pack_fp16_block(const BlockTexels& texels, std::uint8_t* packed);
// Unpacks one block (alpha = 1). Throws Error when a stored half is Inf or NaN (the packer never writes them).
BlockTexels unpack_fp16_block(const std::uint8_t* packed);

// False for the Inf and NaN encodings (exponent field all ones).
constexpr bool fp16_bits_are_finite(unsigned bits) { return (bits & 0x7C00u) != 0x7C00u; }

}  // namespace blocklab
