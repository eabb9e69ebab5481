// The 128-bit block of the `compete` format (formats/compete/README.md is the normative text): one prefix-coded
// selector over three families of modes from two papers / specs,
//   (a) the shape modes of Munkberg et al. 2008 (section 5: shape II, shape I; formats/munkberg),
//   (b) its section 6 modes (extended S3TC, fixed-rate DCT, two-plane luminance; formats/munkberg),
//   (c) the two-region endpoint modes of BC6H (Khronos Data Format Specification, "BC6H", modes 0, 1, 2, 6, ..., 30;
//       formats/bc6h).
//
// FAMILY CODE (bits 0, 1, LSB-first as core/bits.h): BC6H's mode field starts with two bits whose value 0, 1 or 2
// (bit pattern 0,0 / 1,0 / 0,1) opens one of its ten two-region modes; the value 3 (bits 1,1) opens only its four
// one-region modes and the four reserved numbers. `compete` keeps BC6H's three quarters of the code space as they are
// and gives the quarter 1,1 to the Munkberg families:
//   bits 0,1 != 1,1   a BC6H block of a two-region mode, byte for byte (any BC6H UF16 decoder decodes it);
//   bits 0,1 == 1,1   a Munkberg block (munkberg_layout.h, its own prefix selector first) with two of its bits not
//                     stored: compete bits [2, 128) hold the Munkberg block's 128 bits minus the two "dropped" bits
//                     of its mode, in order.
// Kraft sum: BC6H 3/4 + Munkberg 1/4 = 1, so every 128-bit pattern is a block of exactly one mode.
//
// WHO PAYS: the BC6H family pays nothing (its own one-region modes are what it gives up). Each Munkberg mode pays
// two bits (dropped bits, MunkbergBudget below), restored on decode:
//   * an ANCHOR bit is restored as 0: shape II's texel 0 luminance index MSB (swapping Y0 <-> Y1 and l -> 15 - l
//     decodes to the same texels, the shape I anchor trick of munkberg_layout.h applied to shape II): lossless;
//   * a HALVED field loses its LSB, restored as a copy of the field's MSB (bit replication: stored s of w - 1 bits
//     decodes as the w-bit code (s << 1) | (s >> (w - 2)), so 0 and the maximum stay representable).
#pragma once

#include <array>
#include <cstdint>

#include "formats/munkberg/munkberg_layout.h"

namespace blocklab::compete {

constexpr int kBlockBits = 128;
constexpr int kBlockBytes = kBlockBits / 8;
constexpr int kFamilyCodeBits = 2;
constexpr unsigned kMunkbergFamilyCode = 0b11u;   // bits 0, 1 = 1, 1
static_assert(kBlockBytes == munkberg::kBlockBytes, "the Munkberg block is 128 bits");

enum class Family { shape = 0, section6 = 1, bc6h = 2 };
constexpr int kFamilyCount = 3;
constexpr const char* kFamilyNames[kFamilyCount] = {"shape", "section6", "bc6h"};

// Mode indices (Format::modes() order, the block_modes index): the Munkberg modes in munkberg::BlockMode order, then
// the ten BC6H two-region modes in bc6h_tables.h order (mode index 0..9: numbers 0, 1, 2, 6, ..., 30).
constexpr int kMunkbergModeCount = munkberg::kBlockModeCount;   // 5
constexpr int kBc6hModeCount = 10;
constexpr int kBc6hFirstMode = kMunkbergModeCount;
constexpr int kModeCount = kMunkbergModeCount + kBc6hModeCount;   // 15

constexpr Family family_of_mode(int mode) {
  return mode >= kBc6hFirstMode ? Family::bc6h
                                : (mode <= static_cast<int>(munkberg::BlockMode::shape_i) ? Family::shape
                                                                                          : Family::section6);
}

// A field of the Munkberg block: LSB position and width.
struct Field {
  int position = 0;
  int width = 0;
  constexpr int msb() const { return position + width - 1; }
};

// A bit of the Munkberg block that `compete` does not store: restored as 0 (copy_from < 0) or as a copy of bit
// copy_from (a halved field's MSB).
struct DroppedBit {
  int position = 0;
  int copy_from = -1;
};

constexpr int kDroppedBitsPerMode = 2;   // kFamilyCodeBits: the Munkberg block shifted by 2 must lose 2 bits
static_assert(kDroppedBitsPerMode == kFamilyCodeBits, "every Munkberg mode pays for the family code");

// How one Munkberg mode pays for the family code (the README's table).
struct MunkbergBudget {
  munkberg::BlockMode mode;
  bool luminance_anchor = false;               // shape II: texel 0's luminance index MSB implied 0 (lossless)
  std::array<Field, 2> halved{};               // fields whose LSB is replicated from the MSB
  int halved_count = 0;
  std::array<DroppedBit, kDroppedBitsPerMode> dropped{};   // ascending positions
};

// The budget of every Munkberg mode (munkberg::BlockMode order). The DCT mode's fields come from the compiled-in
// tables (its DC codes: Ybar and u), so the first call parses them.
const MunkbergBudget& munkberg_budget(munkberg::BlockMode mode);

// Shape II's luminance anchor (positions of munkberg_layout.h): texel 0's 4-bit index at 48, its MSB is bit 51.
constexpr int kShape2AnchorBit = munkberg::lum_index_position(munkberg::Mode::shape_ii) + munkberg::kShape2LumIndexBits - 1;

// True when bits 0, 1 are the Munkberg family code.
inline bool is_munkberg_family(const std::uint8_t* bytes) { return (bytes[0] & 3u) == kMunkbergFamilyCode; }

// The mode index of a compete block (every pattern is a block of some mode).
int block_mode_of(const std::uint8_t* bytes);

// Whether the Munkberg block `munkberg_bytes` satisfies its mode's dropped bits (anchor bit 0, halved LSB == MSB),
// i.e. whether `compete` can store it.
bool representable(const std::uint8_t* munkberg_bytes);
// Munkberg block -> compete block (family code 1,1 and the block without its mode's dropped bits). Error naming the
// bit unless representable().
void pack_munkberg_block(const std::uint8_t* munkberg_bytes, std::uint8_t* out);
// compete block of the Munkberg family -> the Munkberg block with the dropped bits restored. Error when bits 0, 1 are
// not the Munkberg family code.
void unpack_munkberg_block(const std::uint8_t* bytes, std::uint8_t* munkberg_out);

}  // namespace blocklab::compete
