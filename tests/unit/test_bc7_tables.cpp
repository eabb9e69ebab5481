// BC7 constant tables (formats/bc7/bc7_tables): independent properties of the transcribed partition and anchor
// tables (every subset non-empty, texel 0 in subset 0, anchors inside their subset, 64 distinct patterns per
// subset count), the mode table's bit budget (every mode fills exactly 128 bits) and the endpoint expansion.
#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc7 {
namespace {

TEST(Bc7Tables, EveryPartitionHasNonEmptySubsetsAndAnchorsInsideTheirSubset) {
  for (int subsets = 2; subsets <= 3; ++subsets) {
    std::set<std::vector<int>> distinct;
    for (int partition = 0; partition < 64; ++partition) {
      std::vector<int> pattern(16);
      int counts[3] = {};
      for (int texel = 0; texel < 16; ++texel) {
        pattern[texel] = subset_of_texel(subsets, partition, texel);
        ASSERT_LT(pattern[texel], subsets);
        ++counts[pattern[texel]];
      }
      EXPECT_EQ(pattern[0], 0) << "partition " << partition;
      for (int s = 0; s < subsets; ++s) {
        EXPECT_GT(counts[s], 0) << subsets << " subsets, partition " << partition << ", subset " << s;
        EXPECT_EQ(pattern[anchor_texel(subsets, partition, s)], s) << subsets << "/" << partition << "/" << s;
      }
      distinct.insert(pattern);
    }
    EXPECT_EQ(distinct.size(), 64u);
  }
}

TEST(Bc7Tables, KnownRowsMatchTheSpecification) {
  // KDFS / D3D: 3-subset partition 0 = 0,0,1,1, 0,0,1,1, 0,2,2,1, 2,2,2,2; 2-subset partition 0 = columns 2,3.
  const int three0[16] = {0, 0, 1, 1, 0, 0, 1, 1, 0, 2, 2, 1, 2, 2, 2, 2};
  for (int texel = 0; texel < 16; ++texel) {
    EXPECT_EQ(subset_of_texel(3, 0, texel), three0[texel]);
    EXPECT_EQ(subset_of_texel(2, 0, texel), (texel % 4) >= 2 ? 1 : 0);
  }
  // 2-subset partition 35: ARB/D3D anchor 8 (KDFS 1.4 table 20.6 says 2; KhronosGroup/DataFormat issue #28).
  EXPECT_EQ(anchor_texel(2, 35, 1), 8);
  EXPECT_EQ(anchor_texel(3, 0, 1), 3);
  EXPECT_EQ(anchor_texel(3, 0, 2), 15);
}

TEST(Bc7Tables, EveryModeFillsExactly128Bits) {
  for (int mode = 0; mode < kModeCount; ++mode) {
    const ModeInfo& m = mode_info(mode);
    const int endpoints = 2 * m.subset_count;
    const int bits = (mode + 1) + m.partition_bits + m.rotation_bits + m.index_selection_bits +
                     endpoints * (3 * m.color_bits + m.alpha_bits) + endpoints * m.endpoint_pbits +
                     m.subset_count * m.shared_pbits + (16 * m.index_bits - m.subset_count) +
                     (m.index2_bits ? 16 * m.index2_bits - 1 : 0);
    EXPECT_EQ(bits, 128) << "mode " << mode;
  }
}

TEST(Bc7Tables, ModeIsTheNumberOfTrailingZeroBitsOfByteZero) {
  EXPECT_EQ(mode_of_first_byte(0x00), kReservedMode);
  EXPECT_EQ(mode_of_first_byte(0x01), 0);
  EXPECT_EQ(mode_of_first_byte(0xFF), 0);
  EXPECT_EQ(mode_of_first_byte(0x40), 6);
  EXPECT_EQ(mode_of_first_byte(0xC0), 6);
  EXPECT_EQ(mode_of_first_byte(0x80), 7);
}

TEST(Bc7Tables, EndpointExpansionReplicatesTheTopBits) {
  EXPECT_EQ(expand_endpoint(0b11111, 5), 255);
  EXPECT_EQ(expand_endpoint(0b10000, 5), 0b10000100);
  EXPECT_EQ(expand_endpoint(0b1010101, 7), 0b10101011);   // mode 1: 6 bits + P -> bit 7 copied into bit 0
  EXPECT_EQ(expand_endpoint(200, 8), 200);
  for (int bits = 4; bits <= 8; ++bits) {
    EXPECT_EQ(expand_endpoint(0, bits), 0);
    EXPECT_EQ(expand_endpoint((1 << bits) - 1, bits), 255);
    for (int code = 1; code < (1 << bits); ++code)
      EXPECT_GT(expand_endpoint(code, bits), expand_endpoint(code - 1, bits));   // monotonic
  }
}

}  // namespace
}  // namespace bc7
}  // namespace blocklab
