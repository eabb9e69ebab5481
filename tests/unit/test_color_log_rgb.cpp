// log[RGB] (Munkberg et al. 2008, section 3.4, eq. 6; Xu et al. 2005): per-channel log2 with the 2^-24 floor,
// round trips of every positive half, and the same template on float, ceres::Jet and Interval.
#include <gtest/gtest.h>

#include <cmath>

#include "core/color_spaces.h"
#include "core/interval.h"
#include "core/scalar.h"
#include "test_color_common.h"

namespace blocklab {
namespace {

// Relative round-trip tolerance per channel in double: log2 rounds |log2 c| <= 24 to ~24 * 2^-53 absolute, which
// exp2 turns into a relative error of ~24 ln2 * 2^-53 = 2e-15, plus glibc's < 1 ulp in each call; 1e-13 is a 50x
// margin.
constexpr double kDoubleRoundTrip = 1e-13;
// The same in float: ~24 ln2 * 2^-24 = 1e-6; 1e-5 is a 10x margin.
constexpr double kFloatRoundTrip = 1e-5;

TEST(LogRgbColorSpace, IsPerChannelLog2) {
  const LogRgb<double> log_rgb = rgb_to_log_rgb(Rgb<double>{1.0, 8.0, 0.125});
  EXPECT_EQ(log_rgb.log_r, 0.0);
  EXPECT_EQ(log_rgb.log_g, 3.0);
  EXPECT_EQ(log_rgb.log_b, -3.0);
}

TEST(LogRgbColorSpace, RoundTripsEveryPositiveHalfInDoubleAndFloat) {
  for (double value : color_testing::positive_half_values()) {
    const Rgb<double> back = log_rgb_to_rgb(rgb_to_log_rgb(Rgb<double>{value, value, value}));
    ASSERT_NEAR(back.r, value, kDoubleRoundTrip * value) << value;
    const float value_float = static_cast<float>(value);   // every half is exactly a float
    const Rgb<float> back_float = log_rgb_to_rgb(rgb_to_log_rgb(Rgb<float>{value_float, value_float, value_float}));
    ASSERT_NEAR(back_float.g, value_float, kFloatRoundTrip * value) << value;
  }
}

TEST(LogRgbColorSpace, ZeroAndValuesBelowTheSmallestHalfAreFlooredToIt) {
  const LogRgb<double> log_rgb = rgb_to_log_rgb(Rgb<double>{0.0, 0x1p-30, 0x1p-24});
  EXPECT_EQ(log_rgb.log_r, -24.0);
  EXPECT_EQ(log_rgb.log_g, -24.0);
  EXPECT_EQ(log_rgb.log_b, -24.0);
  const Rgb<double> back = log_rgb_to_rgb(log_rgb);
  EXPECT_EQ(back.r, kLogRgbFloor);
}

TEST(LogRgbColorSpace, LargestHalfRoundTrips) {
  const Rgb<double> back = log_rgb_to_rgb(rgb_to_log_rgb(Rgb<double>{65504.0, 65504.0, 65504.0}));
  EXPECT_NEAR(back.b, 65504.0, kDoubleRoundTrip * 65504.0);
}

TEST(LogRgbColorSpace, JetDerivativeIsOneOverCLn2AboveTheFloorAndZeroBelowIt) {
  using Jet = ceres::Jet<double, 1>;
  const LogRgb<Jet> log_rgb = rgb_to_log_rgb(Rgb<Jet>{Jet(4.0, 0), Jet(0.0, 0), Jet(1e-9, 0)});
  EXPECT_NEAR(log_rgb.log_r.v[0], 1.0 / (4.0 * std::log(2.0)), 1e-15);
  // Below the floor the constant floor is chosen: the derivative is that of a constant.
  EXPECT_EQ(log_rgb.log_g.v[0], 0.0);
  EXPECT_EQ(log_rgb.log_b.v[0], 0.0);
}

TEST(LogRgbColorSpace, IntervalThatTouchesZeroIsBoundedBelowByTheFloor) {
  const LogRgb<Interval> log_rgb =
      rgb_to_log_rgb(Rgb<Interval>{Interval(0.0, 1.0), Interval(2.0, 4.0), Interval(0.0, 0.0)});
  EXPECT_LE(log_rgb.log_r.lower(), -24.0);
  EXPECT_GT(log_rgb.log_r.lower(), -24.0 - 1e-12);   // only the outward rounding of log2 below -24
  EXPECT_GE(log_rgb.log_r.upper(), 0.0);
  EXPECT_LE(log_rgb.log_g.lower(), 1.0);
  EXPECT_GE(log_rgb.log_g.upper(), 2.0);
  EXPECT_TRUE(boost::numeric::in(-24.0, log_rgb.log_b));
}

}  // namespace
}  // namespace blocklab
