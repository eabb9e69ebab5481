// BC7 second-stage partition estimate (formats/bc7/bc7_partition_palette_estimate.h): it is the line error plus the
// along-axis palette error, so it is exact (zero) for subsets with two colours, never below the line error, larger
// for palettes with fewer entries on spread-out subsets, and it prefers the partition whose subsets the mode's
// palette can resolve when the line error cannot tell two partitions apart.
#include <gtest/gtest.h>

#include "formats/bc7/bc7_partition_estimate.h"
#include "formats/bc7/bc7_partition_palette_estimate.h"
#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace {

constexpr float kRgb[4] = {1.0f, 1.0f, 1.0f, 0.0f};

TEST(Bc7PartitionPaletteEstimate, TwoColoursPerSubsetCostNothing) {
  float texels[16][4];
  const std::uint8_t* subsets = bc7::partition_subsets(2, 13);
  for (int i = 0; i < 16; ++i) {
    const float value = subsets[i] == 0 ? (i % 2 ? 10.0f : 90.0f) : (i % 2 ? 200.0f : 130.0f);
    texels[i][0] = value, texels[i][1] = 255.0f - value, texels[i][2] = 0.5f * value, texels[i][3] = 255.0f;
  }
  const bc7::PartitionProjection projection = bc7::project_partition(texels, kRgb, 2, 13);
  EXPECT_NEAR(projection.line_error, 0.0f, 1e-2f);
  EXPECT_NEAR(bc7::palette_line_estimate(projection, 2), 0.0f, 1e-2f);
  EXPECT_NEAR(bc7::palette_line_estimate(projection, 3), 0.0f, 1e-2f);
}

TEST(Bc7PartitionPaletteEstimate, SpreadSubsetsCostMoreWithFewerPaletteEntries) {
  // Every texel on one grey line at 16 distinct levels, plus a small off-line wobble.
  float texels[16][4];
  for (int i = 0; i < 16; ++i) {
    const float level = 16.0f * i;
    texels[i][0] = level + (i % 3), texels[i][1] = level, texels[i][2] = level - (i % 2), texels[i][3] = 255.0f;
  }
  for (int partition : {0, 17, 40}) {
    const bc7::PartitionProjection projection = bc7::project_partition(texels, kRgb, 2, partition);
    const float two_bits = bc7::palette_line_estimate(projection, 2);
    const float three_bits = bc7::palette_line_estimate(projection, 3);
    const float four_bits = bc7::palette_line_estimate(projection, 4);
    EXPECT_GE(four_bits, projection.line_error) << partition;
    EXPECT_GT(two_bits, three_bits) << partition;
    EXPECT_GT(three_bits, four_bits) << partition;
    // The line error agrees with the first-stage estimate (same quantity, computed independently).
    EXPECT_NEAR(projection.line_error, bc7::estimate_partition_error(texels, kRgb, 2, partition),
                1e-2f * (1.0f + projection.line_error))
        << partition;
  }
}

TEST(Bc7PartitionPaletteEstimate, PrefersThePartitionWhosePaletteResolvesItsSubsets) {
  // Partition 0's two subsets each hold 4 evenly spaced levels on their own line: a 2-bit palette (weights 0, 21,
  // 43, 64) fits them up to the weights' rounding. Partition 13 mixes the two lines.
  float texels[16][4];
  const std::uint8_t* subsets = bc7::partition_subsets(2, 0);
  int seen[2] = {0, 0};
  for (int i = 0; i < 16; ++i) {
    const int subset = subsets[i], level = seen[subset]++ % 4;
    const float value = (subset == 0 ? 20.0f : 100.0f) + 40.0f * level;
    texels[i][0] = value, texels[i][1] = subset == 0 ? value : 255.0f - value, texels[i][2] = value;
    texels[i][3] = 255.0f;
  }
  const float resolved = bc7::palette_line_estimate(bc7::project_partition(texels, kRgb, 2, 0), 2);
  const float mixed = bc7::palette_line_estimate(bc7::project_partition(texels, kRgb, 2, 13), 2);
  EXPECT_LT(resolved, 16.0f);
  EXPECT_GT(mixed, 10.0f * resolved);
}

}  // namespace
}  // namespace blocklab
