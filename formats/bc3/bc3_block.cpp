// Packing, unpacking and the double decoder of one BC3 block (formats/bc3/bc3_block.h): the BC4 alpha half and the
// 4-colour BC1 colour half.
#include "formats/bc3/bc3_block.h"

namespace blocklab {

void pack_bc3_block(const Bc3Params& params, std::uint8_t* bytes) {
  pack_bc4_block(params.alpha, bytes, "bc3");
  pack_bc1_color_bits(params.color, bytes + kBc4BlockBytes);
}

Bc3Params unpack_bc3_block(const std::uint8_t* bytes) {
  Bc3Params params;
  params.alpha = unpack_bc4_block(bytes);
  params.color = unpack_bc3_color_bits(bytes + kBc4BlockBytes);
  return params;
}

BlockTexels decode_bc3_params(const Bc3Params& params) {
  BlockTexels texels = decode_bc1_params(params.color);   // mode four_color: always the 4-colour palette
  const std::array<float, 16> alpha = decode_bc4_params(params.alpha);
  for (int texel = 0; texel < 16; ++texel) texels.rgba[texel][3] = alpha[texel];
  return texels;
}

}  // namespace blocklab
