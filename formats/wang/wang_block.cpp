// Packing, unpacking and the float decoder of one `wang` block (formats/wang/wang_block.h).
#include "formats/wang/wang_block.h"

#include <cmath>

namespace blocklab {
namespace wang {

void pack_block(const BlockParams& params, std::uint8_t* bytes) {
  pack_bc4_block(params.tex0.alpha, bytes, "wang: tex0");
  pack_bc1_color_bits(params.tex0.color, bytes + kBc4BlockBytes);
  pack_bc4_block(params.tex1.alpha, bytes + kBc3BlockBytes, "wang: tex1");
  pack_bc1_color_bits(params.tex1.color, bytes + kBc3BlockBytes + kBc4BlockBytes);
}

BlockParams unpack_block(const std::uint8_t* bytes) {
  return {unpack_bc3_block(bytes), unpack_bc3_block(bytes + kBc3BlockBytes)};
}

void fetch_block_bytes(const std::uint8_t* bytes, BlockTexels halves[2]) {
  halves[0] = decode_bc3_params(unpack_bc3_block(bytes));
  halves[1] = decode_bc3_params(unpack_bc3_block(bytes + kBc3BlockBytes));
  for (int half = 0; half < 2; ++half)
    for (auto& texel : halves[half].rgba)
      for (float& value : texel) value = texture_unit_value(value);
}

BlockTexels decode_block_bytes(const DecodeSetup& setup, const std::uint8_t* bytes) {
  BlockTexels halves[2];
  fetch_block_bytes(bytes, halves);
  BlockTexels out;
  for (int texel = 0; texel < kBlockTexels; ++texel) {
    shade_texel(setup.constants, setup.space, setup.residual, halves[0].rgba[texel], halves[1].rgba[texel],
                out.rgba[texel]);
    out.rgba[texel][3] = 1.0f;
  }
  return out;
}

}  // namespace wang
}  // namespace blocklab
