// A BC6H block in symbolic form (the fields of KDFS table-bptcblockformat as stored) and its packing to and from the
// 16 bytes (bc6h_pack.cpp): mode, partition, the twelve stored endpoint components and the 16 indices.
#pragma once

#include <cstdint>

#include "formats/bc6h/bc6h_tables.h"

namespace blocklab {
namespace bc6h {

struct Params {
  int mode_index = kReservedModeIndex;   // 0..13 (bc6h_tables.h), or kReservedModeIndex
  int partition = 0;                     // 0..31 for two-subset modes, 0 otherwise
  // Stored endpoint components, field 3 e + c (endpoint e, channel c), as the block holds them: endpoint 0 in its
  // EPB bits, the others in their delta bits (two's complement) or EPB bits; each masked to its width.
  int fields[12] = {};
  std::uint8_t indices[kTexels] = {};    // 0..7 (two subsets) or 0..15; an anchor's top bit is 0
};

// Bits of stored field `field` (0..11) in `mode`.
int field_bits(const ModeInfo& mode, int field);
// Whether `texel` is an anchor (its index stored with one bit less): texel 0, and in two-subset modes the
// second subset's anchor of the partition.
bool is_anchor(int subset_count, int partition, int texel);

void pack(const Params& params, std::uint8_t* out);        // writes 16 bytes; a reserved mode writes number 19
Params unpack(const std::uint8_t* bytes);

}  // namespace bc6h
}  // namespace blocklab
