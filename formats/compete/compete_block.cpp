// `compete` block decoding (compete_block.h).
#include "formats/compete/compete_block.h"

#include "formats/bc6h/bc6h_decode.h"
#include "formats/bc6h/bc6h_half.h"
#include "formats/compete/compete_layout.h"

namespace blocklab::compete {

BlockTexels decode_block(const std::uint8_t* bytes, const munkberg::ModeContext& context) {
  if (is_munkberg_family(bytes)) {
    std::uint8_t munkberg_block[kBlockBytes];
    unpack_munkberg_block(bytes, munkberg_block);
    return munkberg::decode_any_block(munkberg_block, context);
  }
  std::uint16_t halves[bc6h::kTexels][3];
  bc6h::decode<false>(bc6h::unpack(bytes), halves);
  BlockTexels block;
  for (int i = 0; i < bc6h::kTexels; ++i) {
    for (int c = 0; c < 3; ++c) block.rgba[i][c] = bc6h::half_bits_to_float(halves[i][c]);
    block.rgba[i][3] = 1.0f;
  }
  return block;
}

}  // namespace blocklab::compete
