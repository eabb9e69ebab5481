// BC7 (BPTC unorm) constant tables: the mode table, partition tables, anchor tables, interpolation weights and the
// endpoint bit expansion. Source: Khronos Data Format Specification, chapter "BPTC" (bptc.adoc, tables
// table-bptcmodes, table-bptcmodebits, the partition and anchor tables), transcribed in /work/shared/docs/SPECS.md
// section 2.3 and cross-checked there and in tests/unit/test_bc7_tables.cpp (anchors lie in their subset, texel 0
// is in subset 0, every subset is non-empty, the 64 patterns are distinct).
//
// Note on 2-subset partition 35: KDFS 1.4 table 20.6 lists its anchor as texel 2 (KhronosGroup/DataFormat issue
// #28), the ARB_texture_compression_bptc text and Direct3D give 8. Texel 2 and 8 are both in subset 1; we follow
// ARB/D3D (8), the value hardware decoders use.
#pragma once

#include <cstdint>

namespace blocklab {
namespace bc7 {

constexpr int kBlockBytes = 16;
constexpr int kModeCount = 8;
constexpr int kTexels = 16;

// One row of the KDFS mode table (SPECS.md 2.3): NS, PB, RB, ISB, CB, AB, EPB, SPB, IB, IB2.
struct ModeInfo {
  int subset_count;            // NS
  int partition_bits;          // PB
  int rotation_bits;           // RB
  int index_selection_bits;    // ISB
  int color_bits;              // CB: stored bits per colour endpoint channel (without P-bit)
  int alpha_bits;              // AB: stored bits per alpha endpoint (0 = no alpha, decodes as 255)
  int endpoint_pbits;          // EPB: 1 = one P-bit per endpoint
  int shared_pbits;            // SPB: 1 = one P-bit per subset, shared by its two endpoints
  int index_bits;              // IB: primary index bits
  int index2_bits;             // IB2: secondary index bits (modes 4, 5; 0 otherwise)
};

const ModeInfo& mode_info(int mode);   // mode in 0..7

// Mode of a block: the number of trailing zero bits of byte 0; kReservedMode when byte 0 == 0.
constexpr int kReservedMode = 8;
int mode_of_first_byte(std::uint8_t first_byte);

// Subset (0..subset_count-1) of `texel` in `partition`; subset_count 1 always gives 0.
int subset_of_texel(int subset_count, int partition, int texel);
// Pointer to the 16 subset numbers of a partition (subset_count 1, 2 or 3; partition 0..63).
const std::uint8_t* partition_subsets(int subset_count, int partition);
// Anchor texel of `subset`: subset 0 is always texel 0, subsets 1 and 2 come from the anchor tables.
int anchor_texel(int subset_count, int partition, int subset);

// Interpolation weights (out of 64) of 2-, 3- and 4-bit indices.
const int* index_weights(int index_bits);

// The bit-exact BPTC interpolation ((64 - w) * E0 + w * E1 + 32) >> 6 on 8-bit expanded endpoints.
constexpr int interpolate(int endpoint0, int endpoint1, int weight) {
  return ((64 - weight) * endpoint0 + weight * endpoint1 + 32) >> 6;
}

// Expands a `total_bits`-bit endpoint code (stored bits followed by the P-bit, if any; 1..8 bits) to 8 bits: the
// code becomes the most significant bits, the low bits repeat the code's top bits (SPECS.md 2.3).
constexpr int expand_endpoint(int code, int total_bits) {
  if (total_bits >= 8) return code;   // 8-bit alpha of mode 5: stored as is
  int value = code << (8 - total_bits);
  // Fill the 8 - total_bits low bits by repeating the code from its top; repeat until all are filled (only
  // codes shorter than 4 bits need more than one pass, BC7 never has them but the rule stays general).
  for (int filled = total_bits; filled < 8; filled += total_bits) value |= value >> total_bits;
  return value & 0xFF;
}

}  // namespace bc7
}  // namespace blocklab
