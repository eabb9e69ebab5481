// One BC3 (DXT5) block: an 8-byte alpha block (the BC4 layout, formats/bc4/bc4_block.h) followed by an 8-byte BC1
// colour block whose codes are ALWAYS decoded with the 4-colour palette, whatever the endpoint order (Khronos Data
// Format Specification, S3TC chapter "BC3"; SPECS.md 2.2). The packer accepts any endpoint order so that
// pack(unpack(b)) == b for every block; blocklab's encoder always writes color0 > color1, or color0 == color1 with
// every code 0 (SPECS.md 2.5 item 2). The oracle is in bc3_reference_decode.cpp.
#pragma once

#include <cstdint>

#include "core/blocks.h"
#include "formats/bc1/bc1_block.h"
#include "formats/bc4/bc4_block.h"

namespace blocklab {

struct Bc3Params {
  Bc4Params alpha;   // bytes 0-7
  Bc1Params color;   // bytes 8-15, mode always four_color
};

// Writes the 16 bytes; throws Error("bc3: ...") on out-of-range fields, an alpha mode that disagrees with the
// alpha endpoint order, or a colour mode other than four_color.
void pack_bc3_block(const Bc3Params& params, std::uint8_t* bytes);
// Reads the 16 bytes (every bit pattern is valid).
Bc3Params unpack_bc3_block(const std::uint8_t* bytes);

// decode<double> of a Params as float RGBA texels in [0, 1].
BlockTexels decode_bc3_params(const Bc3Params& params);

// The oracle: straight from the KDFS text (exact fractions).
BlockTexels reference_decode_bc3_block(const std::uint8_t* bytes);

}  // namespace blocklab
