// BC7 constant tables (KDFS "BPTC" chapter; values transcribed in /work/shared/docs/SPECS.md section 2.3).
#include "formats/bc7/bc7_tables.h"

#include <array>
#include <string>

#include "core/error.h"

namespace blocklab {
namespace bc7 {

namespace {

// KDFS table-bptcmodes: NS, PB, RB, ISB, CB, AB, EPB, SPB, IB, IB2.
constexpr ModeInfo kModes[kModeCount] = {
    {3, 4, 0, 0, 4, 0, 1, 0, 3, 0},
    {2, 6, 0, 0, 6, 0, 0, 1, 3, 0},
    {3, 6, 0, 0, 5, 0, 0, 0, 2, 0},
    {2, 6, 0, 0, 7, 0, 1, 0, 2, 0},
    {1, 0, 2, 1, 5, 6, 0, 0, 2, 3},
    {1, 0, 2, 0, 7, 8, 0, 0, 2, 2},
    {1, 0, 0, 0, 7, 7, 1, 0, 4, 0},
    {2, 6, 0, 0, 5, 5, 1, 0, 2, 0},
};

// Two-subset partitions: bit i = subset of texel i.
constexpr std::uint16_t kTwoSubsetMasks[64] = {
    0xCCCC, 0x8888, 0xEEEE, 0xECC8, 0xC880, 0xFEEC, 0xFEC8, 0xEC80, 0xC800, 0xFFEC, 0xFE80, 0xE800, 0xFFE8,
    0xFF00, 0xFFF0, 0xF000, 0xF710, 0x008E, 0x7100, 0x08CE, 0x008C, 0x7310, 0x3100, 0x8CCE, 0x088C, 0x3110,
    0x6666, 0x366C, 0x17E8, 0x0FF0, 0x718E, 0x399C, 0xAAAA, 0xF0F0, 0x5A5A, 0x33CC, 0x3C3C, 0x55AA, 0x9696,
    0xA55A, 0x73CE, 0x13C8, 0x324C, 0x3BDC, 0x6996, 0xC33C, 0x9966, 0x0660, 0x0272, 0x04E4, 0x4E40, 0x2720,
    0xC936, 0x936C, 0x39C6, 0x639C, 0x9336, 0x9CC6, 0x817E, 0xE718, 0xCCF0, 0x0FCC, 0x7744, 0xEE22};

// Three-subset partitions: bits 2i+1..2i = subset of texel i.
constexpr std::uint32_t kThreeSubsetMasks[64] = {
    0xAA685050, 0x6A5A5040, 0x5A5A4200, 0x5450A0A8, 0xA5A50000, 0xA0A05050, 0x5555A0A0, 0x5A5A5050,
    0xAA550000, 0xAA555500, 0xAAAA5500, 0x90909090, 0x94949494, 0xA4A4A4A4, 0xA9A59450, 0x2A0A4250,
    0xA5945040, 0x0A425054, 0xA5A5A500, 0x55A0A0A0, 0xA8A85454, 0x6A6A4040, 0xA4A45000, 0x1A1A0500,
    0x0050A4A4, 0xAAA59090, 0x14696914, 0x69691400, 0xA08585A0, 0xAA821414, 0x50A4A450, 0x6A5A0200,
    0xA9A58000, 0x5090A0A8, 0xA8A09050, 0x24242424, 0x00AA5500, 0x24924924, 0x24499224, 0x50A50A50,
    0x500AA550, 0xAAAA4444, 0x66660000, 0xA5A0A5A0, 0x50A050A0, 0x69286928, 0x44AAAA44, 0x66666600,
    0xAA444444, 0x54A854A8, 0x95809580, 0x96969600, 0xA85454A8, 0x80959580, 0xAA141414, 0x96960000,
    0xAAAA1414, 0xA05050A0, 0xA0A5A5A0, 0x96000000, 0x40804080, 0xA9A8A9A8, 0xAAAAAA44, 0x2A4A5254};

// Anchor of subset 1 in the two-subset partitions.
constexpr std::uint8_t kTwoSubsetAnchor1[64] = {
    15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 2,  8,  2,  2,  8,
    8,  15, 2,  8,  2,  2,  8,  8,  2,  2,  15, 15, 6,  8,  2,  8,  15, 15, 2,  8,  2,  2,
    2,  15, 15, 6,  6,  2,  6,  8,  15, 15, 2,  2,  15, 15, 15, 15, 15, 2,  2,  15};
// Anchors of subsets 1 and 2 in the three-subset partitions.
constexpr std::uint8_t kThreeSubsetAnchor1[64] = {
    3, 3,  15, 15, 8, 3,  15, 15, 8,  8,  6,  6, 6,  5,  3,  3, 3, 3,  8,  15, 3,  3,
    6, 10, 5,  8,  8, 6,  8,  5,  15, 15, 8,  15, 3, 5,  6,  10, 8, 15, 15, 3,  15, 5,
    15, 15, 15, 15, 3, 15, 5, 5,  5,  8,  5,  10, 5, 10, 8,  13, 15, 12, 3,  3};
constexpr std::uint8_t kThreeSubsetAnchor2[64] = {
    15, 8,  8,  3,  15, 15, 3,  8,  15, 15, 15, 15, 15, 15, 15, 8, 15, 8, 15, 3,  15, 8,
    15, 8,  3,  15, 6,  10, 15, 15, 10, 8,  15, 3,  15, 10, 10, 8, 9,  10, 6,  15, 8,  15,
    3,  6,  6,  8,  15, 3,  15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 3,  15, 15, 8};

constexpr int kWeights2[4] = {0, 21, 43, 64};
constexpr int kWeights3[8] = {0, 9, 18, 27, 37, 46, 55, 64};
constexpr int kWeights4[16] = {0, 4, 9, 13, 17, 21, 26, 30, 34, 38, 43, 47, 51, 55, 60, 64};

// Subset number of every texel for 1, 2 and 3 subsets, unpacked once from the masks.
struct PartitionTable {
  std::uint8_t subsets[3][64][kTexels];
  PartitionTable() {
    for (int partition = 0; partition < 64; ++partition)
      for (int texel = 0; texel < kTexels; ++texel) {
        subsets[0][partition][texel] = 0;
        subsets[1][partition][texel] = static_cast<std::uint8_t>((kTwoSubsetMasks[partition] >> texel) & 1u);
        subsets[2][partition][texel] =
            static_cast<std::uint8_t>((kThreeSubsetMasks[partition] >> (2 * texel)) & 3u);
      }
  }
};

const PartitionTable& partition_table() {
  static const PartitionTable table;   // built on first use (thread-safe static)
  return table;
}

void check_subsets_and_partition(const char* who, int subset_count, int partition) {
  if (subset_count < 1 || subset_count > 3)
    fail(who, "subset count " + std::to_string(subset_count) + " is outside 1..3");
  if (partition < 0 || partition > 63) fail(who, "partition " + std::to_string(partition) + " is outside 0..63");
}

}  // namespace

const ModeInfo& mode_info(int mode) {
  if (mode < 0 || mode >= kModeCount) fail("bc7::mode_info", "mode " + std::to_string(mode) + " is outside 0..7");
  return kModes[mode];
}

int mode_of_first_byte(std::uint8_t first_byte) {
  // Byte 0 == 0 has no set bit: the reserved encoding (decoders return 0 in every channel).
  if (first_byte == 0) return kReservedMode;
  int mode = 0;
  while (((first_byte >> mode) & 1u) == 0) ++mode;
  return mode;
}

const std::uint8_t* partition_subsets(int subset_count, int partition) {
  check_subsets_and_partition("bc7::partition_subsets", subset_count, partition);
  return partition_table().subsets[subset_count - 1][partition];
}

int subset_of_texel(int subset_count, int partition, int texel) {
  if (texel < 0 || texel >= kTexels) fail("bc7::subset_of_texel", "texel " + std::to_string(texel) + " is outside 0..15");
  return partition_subsets(subset_count, partition)[texel];
}

int anchor_texel(int subset_count, int partition, int subset) {
  check_subsets_and_partition("bc7::anchor_texel", subset_count, partition);
  if (subset < 0 || subset >= subset_count)
    fail("bc7::anchor_texel", "subset " + std::to_string(subset) + " is outside 0.." + std::to_string(subset_count - 1));
  if (subset == 0) return 0;
  if (subset_count == 2) return kTwoSubsetAnchor1[partition];
  return subset == 1 ? kThreeSubsetAnchor1[partition] : kThreeSubsetAnchor2[partition];
}

const int* index_weights(int index_bits) {
  switch (index_bits) {
    case 2: return kWeights2;
    case 3: return kWeights3;
    case 4: return kWeights4;
    default: fail("bc7::index_weights", "index bit count " + std::to_string(index_bits) + " is not 2, 3 or 4");
  }
}

}  // namespace bc7
}  // namespace blocklab
