// Spec-literal BC6H reference decoder (the oracle), written separately from the fast path (bc6h_params.h,
// bc6h_pack.cpp, bc6h_decode.h): it reads the block bit by bit following its own text transcription of the KDFS
// table-bptcblockformat rows ("M[1..0], G2[4], ..."), interpreted at decode time, and does the sign extension,
// transform, unquantisation and interpolation from the KDFS pseudocode itself. Only the BC7 partition and anchor
// tables are shared.
#pragma once

#include <cstdint>

namespace blocklab {
namespace bc6h {

// Decodes 16 bytes into half-float bits out[texel][R, G, B]; reserved modes (19, 23, 27, 31) give 0 everywhere.
void reference_decode(const std::uint8_t* bytes, bool is_signed, std::uint16_t (&out)[16][3]);

}  // namespace bc6h
}  // namespace blocklab
