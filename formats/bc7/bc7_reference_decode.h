// Spec-literal BC7 reference decoder (the oracle), written separately from the fast path (bc7_decode.h) and
// plainly from the KDFS "BPTC" decoding description: it reads the bits of the 128-bit block in order with its own
// bit reader, does not use Params, pack/unpack or the fast decoder. Only the constant tables are shared.
#pragma once

#include <cstdint>

namespace blocklab {
namespace bc7 {

// Decodes 16 bytes into out[texel][R, G, B, A], 8-bit values; reserved blocks (byte 0 == 0) give 0 everywhere.
void reference_decode(const std::uint8_t* bytes, std::uint8_t (&out)[16][4]);

}  // namespace bc7
}  // namespace blocklab
