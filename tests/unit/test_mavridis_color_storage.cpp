// The 8-bit colour storage of `mavridis` (formats/mavridis/mavridis_color_storage.h, section 3.5): YCoCg-R chroma
// is exact where it spans at most 256 values and loses one bit otherwise; real-valued planes become 8-bit codes.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "formats/mavridis/mavridis_color_storage.h"

namespace blocklab {
namespace {

using mavridis::Plane;

Plane ramp(int low, int high) {
  Plane plane = Plane::zeros(high - low + 1, 1);
  for (int v = low; v <= high; ++v) plane.values[static_cast<std::size_t>(v - low)] = v;
  return plane;
}

TEST(MavridisColorStorage, YCoCgRChromaSpanningAtMost256ValuesIsStoredExactly) {
  for (const auto& range : {std::pair<int, int>{-255, 0}, {-100, 155}, {0, 255}}) {
    Plane plane = ramp(range.first, range.second);
    const Plane original = plane;
    mavridis::store_ycocg_r_chroma_unorm8(plane);
    EXPECT_EQ(plane.values, original.values) << range.first;
  }
}

TEST(MavridisColorStorage, YCoCgRChromaSpanningMoreLosesOneBitInto256Levels) {
  Plane plane = ramp(-255, 255);
  const Plane original = plane;
  mavridis::store_ycocg_r_chroma_unorm8(plane);
  std::set<double> levels(plane.values.begin(), plane.values.end());
  EXPECT_EQ(levels.size(), 256u);
  for (std::size_t i = 0; i < plane.values.size(); ++i) EXPECT_EQ(std::abs(plane.values[i] - original.values[i]), 0.5);
}

TEST(MavridisColorStorage, RealValuesBecomeRoundedClampedCodes) {
  Plane luma = Plane::zeros(4, 1);
  luma.values = {0.25, 127.5, 254.75, 300.0};
  mavridis::store_unorm8(luma, 0.0);
  EXPECT_EQ(luma.values, (std::vector<double>{0.0, 128.0, 255.0, 255.0}));
  Plane chroma = Plane::zeros(4, 1);
  chroma.values = {-127.75, -0.25, 0.5, 127.5};
  mavridis::store_unorm8(chroma, 128.0);
  EXPECT_EQ(chroma.values, (std::vector<double>{-128.0, 0.0, 1.0, 127.0}));
}

}  // namespace
}  // namespace blocklab
