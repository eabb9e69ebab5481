// BC6H (BPTC float) constant tables and the integer steps of its decoder: the mode table, each mode's bit layout,
// endpoint unquantisation and the final unquantisation to half-float bits. Source: Khronos Data Format Specification,
// chapter "BPTC", section "BC6H" (bptc.adoc: table-bptcblockmodes, table-bptcblockformat and the unquantisation
// pseudocode) and Microsoft's "BC6H format" page (learn.microsoft.com direct3d11/bc6h-format); SPECS.md 2.4.
// The two-subset partitions, the second-subset anchors and the 3-/4-bit interpolation weights are BC7's tables (the
// spec says "the first half of bptcP2subset" and reuses BPTCInterpolation), so they come from formats/bc7/bc7_tables.h.
//
// Mode numbering: the spec's mode number M (the low 2 bits if they are 0 or 1, else the low 5 bits): 0, 1, 2, 6, 10,
// 14, 18, 22, 26, 30 (two subsets) and 3, 7, 11, 15 (one subset); 19, 23, 27 and 31 are reserved and decode to 0.
// A mode *index* 0..13 is a row of the table below, in the spec's table order.
#pragma once

#include <cstdint>

namespace blocklab {
namespace bc6h {

constexpr int kBlockBytes = 16;
constexpr int kModeCount = 14;
constexpr int kTexels = 16;
constexpr int kReservedModeIndex = -1;

// Stored endpoint components: endpoint e (0..3) and channel c (0 R, 1 G, 2 B) is field 3 e + c; 12 is the partition.
constexpr int kPartitionField = 12;

// One run of a mode's bit layout, read LSB first: `count` consecutive block bits go to field `field`, the first one to
// bit `first_bit` and the next ones to first_bit + 1, + 2, ... (or first_bit - 1, - 2, ... when `reversed`).
struct LayoutRun {
  std::uint8_t field;
  std::uint8_t first_bit;
  std::uint8_t count;
  bool reversed;
};

// One row of table-bptcblockmodes.
struct ModeInfo {
  int mode_number;            // M as stored in the block (0, 1, 2, 6, ..., 15)
  int mode_bits;              // 2 (modes 0 and 1) or 5
  int subset_count;           // 1 or 2 (two-subset modes have 5 partition bits)
  bool transformed;           // endpoints 1..3 are deltas from endpoint 0
  int endpoint_bits;          // EPB: bits of endpoint 0 (and of every endpoint when not transformed)
  int delta_bits[3];          // bits of the R, G, B deltas (= endpoint_bits when not transformed)
  const LayoutRun* runs;      // the endpoint and partition fields after the mode bits, in block order
  int run_count;
};

const ModeInfo& mode_info(int mode_index);   // 0..13
// Mode index of a block's first byte(s): kReservedModeIndex for the reserved mode numbers 19, 23, 27, 31.
int mode_index_of_block(const std::uint8_t* bytes);
// Mode index of a spec mode number, or kReservedModeIndex.
int mode_index_of_number(int mode_number);

// First index bit: 65 for one subset, 82 for two.
constexpr int index_start_bit(int subset_count) { return subset_count == 1 ? 65 : 82; }
// Index bits per texel: 4 for one subset, 3 for two.
constexpr int index_bits(int subset_count) { return subset_count == 1 ? 4 : 3; }

// Sign extension of a `bits`-bit two's complement value.
constexpr int sign_extend(int value, int bits) {
  const int sign = 1 << (bits - 1);
  value &= (1 << bits) - 1;
  return (value ^ sign) - sign;
}

// Endpoint unquantisation of a (sign-extended when signed) `bits`-bit value to the 16-bit interpolation domain
// (KDFS pseudocode): unsigned 0..0xFFFF, signed -0x7FFF..0x7FFF. Inline, like finish_unquantize: the encoder's inner
// loops call both per palette entry.
inline int unquantize(int value, int bits, bool is_signed) {
  if (!is_signed) {
    if (bits >= 15) return value;
    if (value == 0) return 0;
    if (value == (1 << bits) - 1) return 0xFFFF;
    return ((value << 15) + 0x4000) >> (bits - 1);
  }
  if (bits >= 16) return value;
  const bool negative = value < 0;
  const int magnitude = negative ? -value : value;
  int result;
  if (magnitude == 0)
    result = 0;
  else if (magnitude >= (1 << (bits - 1)) - 1)
    result = 0x7FFF;
  else
    result = ((magnitude << 15) + 0x4000) >> (bits - 1);
  return negative ? -result : result;
}

// The final unquantisation of an interpolated value to half-float bits (unsigned: (i * 31) >> 6; signed: the
// magnitude times 31 / 32 with the sign bit restored).
inline std::uint16_t finish_unquantize(int interpolated, bool is_signed) {
  if (!is_signed) return static_cast<std::uint16_t>((interpolated * 31) >> 6);
  if (interpolated < 0) return static_cast<std::uint16_t>((((-interpolated) * 31) >> 5) | 0x8000);
  return static_cast<std::uint16_t>((interpolated * 31) >> 5);
}

}  // namespace bc6h
}  // namespace blocklab
