// The symbolic form of one BC7 block (`Params`) and its exact conversion to and from the 16 packed bytes.
// Bit layout: KDFS "BPTC" chapter, field order mode, partition, rotation, index selection, colour endpoints
// (R of every subset/endpoint, then G, B), alpha endpoints, per-endpoint P-bits, shared P-bits, primary indices,
// secondary indices; anchor indices store one bit less (SPECS.md 2.3).
#pragma once

#include <cstdint>

#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc7 {

struct Params {
  int mode = kReservedMode;     // 0..7, or kReservedMode (byte 0 == 0; decodes to 0 in all channels)
  int partition = 0;            // < 2^PB
  int rotation = 0;             // modes 4, 5: 0 none, 1 swap(A,R), 2 swap(A,G), 3 swap(A,B)
  int index_selection = 0;      // mode 4: 1 = colour uses the 3-bit secondary indices, alpha the 2-bit primary
  // Stored endpoint codes WITHOUT the P-bit: [subset][endpoint][R, G, B, A]. Channels the mode does not store
  // (alpha of modes 0-3) are 0.
  std::uint8_t endpoints[3][2][4] = {};
  // P-bit of each endpoint. Shared-P-bit mode 1 keeps the subset's one bit in both entries; modes without P-bits
  // keep 0.
  std::uint8_t pbits[3][2] = {};
  std::uint8_t indices[kTexels] = {};    // primary indices, texel i = x + 4y
  std::uint8_t indices2[kTexels] = {};   // secondary indices (modes 4, 5), 0 otherwise
};

bool operator==(const Params& a, const Params& b);
inline bool operator!=(const Params& a, const Params& b) { return !(a == b); }

// Writes the 16 bytes of `params`. Throws Error (naming the field) when a value does not fit its field, an anchor
// index has its most significant bit set, the two shared P-bits of a mode-1 subset differ, or the mode is
// reserved (the encoder never writes it).
void pack(const Params& params, std::uint8_t* bytes);
// Reads 16 bytes. Every bit pattern is accepted: byte 0 == 0 gives mode == kReservedMode and all other fields 0.
Params unpack(const std::uint8_t* bytes);

// The 8-bit value of endpoint `endpoint` of `subset`, channel `channel` (0..3), after P-bit append and bit
// replication; 255 for the alpha of modes without alpha bits.
int expanded_endpoint(const Params& params, int subset, int endpoint, int channel);

}  // namespace bc7
}  // namespace blocklab
