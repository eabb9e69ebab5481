// Munkberg et al. 2008 section 7.3, Figure 8: per-block log2-luminance ranges and their histogram
// (formats/munkberg/analysis/luminance_range_histogram.h).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/color_spaces.h"
#include "core/error.h"
#include "core/image.h"
#include "formats/munkberg/analysis/luminance_range_histogram.h"

namespace blocklab::munkberg {
namespace {

void set_grey(Image& image, int x, int y, float value) {
  float* p = image.texel(x, y);
  p[0] = p[1] = p[2] = value;   // grey: Y = value (the Rec. 601 weights sum to 1)
}

TEST(MunkbergHistogram, PrecisionLimitsAreThePapersAndFollowEq16) {
  EXPECT_EQ(range_for_precision_bits(10), 0.5);   // "10 bits precision or better ... (maximum difference 0.5)"
  EXPECT_EQ(range_for_precision_bits(8), 2.0);
  EXPECT_EQ(range_for_precision_bits(6), 8.0);
  for (int k = 1; k <= 30; ++k) {
    // Eq. 16 with k bits over the half range equals eq. 16 with the 4 index bits over the block range.
    const double half_error = 0.5 * kHalfLogLuminanceSpan / std::ldexp(1.0, k);
    const double block_error = 0.5 * range_for_precision_bits(k) / std::ldexp(1.0, kLuminanceIndexBits);
    EXPECT_EQ(half_error, block_error) << k;
  }
  EXPECT_THROW(range_for_precision_bits(0), Error);
  EXPECT_THROW(range_for_precision_bits(31), Error);
}

TEST(MunkbergHistogram, BlockRangeIsMaxMinusMinOfLog2LuminanceWithoutBlackTexels) {
  Image image(12, 4);   // three blocks; the constructor leaves every texel black
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) set_grey(image, x, y, x == 1 && y == 2 ? 4.0f : 1.0f);   // block 0: range 2
  set_grey(image, 9, 1, 0.5f);   // block 2: one non-black texel among black ones: range 0
  const BlockLuminanceRanges r = block_log_luminance_ranges(image);
  EXPECT_EQ(r.blocks, 3u);
  EXPECT_EQ(r.black_blocks, 1u);   // block 1
  EXPECT_EQ(r.black_texels, 16u + 15u);
  ASSERT_EQ(r.ranges.size(), 2u);
  EXPECT_DOUBLE_EQ(r.ranges[0], 2.0);
  EXPECT_EQ(r.ranges[1], 0.0);
}

TEST(MunkbergHistogram, RangeDependsOnLuminanceOnlyAndIgnoresExposureAndEdgePadding) {
  Image image(6, 5);   // 2 x 2 blocks, the right and bottom ones padded
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 6; ++x) {
      float* p = image.texel(x, y);
      const float s = 0.1f + 0.37f * static_cast<float>(x * 5 + y);
      p[0] = s * ((x + y) % 3 == 0 ? 2.0f : 0.2f);
      p[1] = s * 0.6f;
      p[2] = s * (x % 2 == 0 ? 0.1f : 1.5f);
    }
  const BlockLuminanceRanges r = block_log_luminance_ranges(image);
  ASSERT_EQ(r.ranges.size(), 4u);
  // Expected: max - min of log2 Y over the texels inside the image only.
  for (int by = 0; by < 2; ++by)
    for (int bx = 0; bx < 2; ++bx) {
      double lo = 1e300, hi = -1e300;
      for (int y = 4 * by; y < std::min(5, 4 * by + 4); ++y)
        for (int x = 4 * bx; x < std::min(6, 4 * bx + 4); ++x) {
          const float* p = image.texel(x, y);
          const double l = std::log2(kRec601WeightR * p[0] + kRec601WeightG * p[1] + kRec601WeightB * p[2]);
          lo = std::min(lo, l);
          hi = std::max(hi, l);
        }
      EXPECT_NEAR(r.ranges[static_cast<std::size_t>(by * 2 + bx)], hi - lo, 1e-12);
    }
  // Scaling the exposure by 2^5 changes no range (a log-luminance difference).
  Image brighter = image;
  for (float& v : brighter.pixels) v *= 32.0f;
  const BlockLuminanceRanges b = block_log_luminance_ranges(brighter);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(b.ranges[i], r.ranges[i], 1e-12);
}

TEST(MunkbergHistogram, HistogramBinsAreHalfOpenWithAnOverflowBin) {
  const std::vector<double> ranges = {0.0, 0.2499, 0.25, 0.5, 0.74, 0.75, 3.0, 100.0};
  const std::vector<std::uint64_t> counts = range_histogram(ranges, 0.25, 4);
  ASSERT_EQ(counts.size(), 4u);
  EXPECT_EQ(counts[0], 2u);   // [0, 0.25)
  EXPECT_EQ(counts[1], 1u);   // [0.25, 0.5)
  EXPECT_EQ(counts[2], 2u);   // [0.5, 0.75)
  EXPECT_EQ(counts[3], 3u);   // >= 0.75
  std::uint64_t total = 0;
  for (std::uint64_t c : counts) total += c;
  EXPECT_EQ(total, ranges.size());
  EXPECT_THROW(range_histogram(ranges, 0.0, 4), Error);
  EXPECT_THROW(range_histogram(ranges, 0.25, 0), Error);
  EXPECT_THROW(range_histogram({std::nan("")}, 0.25, 4), Error);
}

TEST(MunkbergHistogram, ShareWithinCountsTheLimitItself) {
  const std::vector<double> ranges = {0.1, 0.5, 0.50001, 2.0};
  EXPECT_EQ(fraction_within(ranges, 0.5), 0.5);
  EXPECT_EQ(fraction_within(ranges, 2.0), 1.0);
  EXPECT_EQ(fraction_within({}, 0.5), 0.0);
}

}  // namespace
}  // namespace blocklab::munkberg
