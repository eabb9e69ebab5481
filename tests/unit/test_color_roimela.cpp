// Roimela et al. Yuv (Munkberg et al. 2008, section 3.2, eq. 4): round trips, the Y~ = 0 rule, chrominance range,
// and the same template on float, ceres::Jet and Interval.
#include <gtest/gtest.h>

#include <random>

#include "formats/munkberg/munkberg_color_spaces.h"
#include "core/interval.h"
#include "core/scalar.h"
#include "test_color_common.h"

namespace blocklab {
namespace {

using color_testing::channels_near;
using color_testing::largest_channel;

// Round-trip tolerance in double, relative to the largest channel: one division forward, two multiplications
// back, and green recovered through the cancellation 1 - u - v (a few ulp of Y~): ~1e-15; 1e-13 is a 100x margin.
constexpr double kDoubleRoundTrip = 1e-13;
// The same in float (ulp 2^-23): ~5e-7; 5e-6 is a 10x margin.
constexpr double kFloatRoundTrip = 5e-6;

Rgb<double> round_trip(const Rgb<double>& rgb) { return roimela_yuv_to_rgb(rgb_to_roimela_yuv(rgb)); }

TEST(RoimelaYuvColorSpace, ForwardMatchesEquation4OnAKnownTexel) {
  const RoimelaYuv<double> yuv = rgb_to_roimela_yuv(Rgb<double>{2.0, 4.0, 8.0});
  EXPECT_EQ(yuv.luminance, (2.0 + 8.0 + 8.0) / 4.0);
  EXPECT_DOUBLE_EQ(yuv.u, 2.0 / 18.0);
  EXPECT_DOUBLE_EQ(yuv.v, 8.0 / 18.0);
}

TEST(RoimelaYuvColorSpace, RoundTripsRandomHdrTexels) {
  EXPECT_TRUE(color_testing::round_trips_random_hdr_texels(round_trip, 2006, kDoubleRoundTrip));
}

TEST(RoimelaYuvColorSpace, RoundTripsPurePrimariesGreyAndExtremeTexels) {
  EXPECT_TRUE(color_testing::round_trips_edge_texels(round_trip, kDoubleRoundTrip));
}

TEST(RoimelaYuvColorSpace, RoundTripsEveryPositiveHalfAsEachPrimary) {
  for (double value : color_testing::positive_half_values())
    for (const Rgb<double>& rgb : {Rgb<double>{value, 0, 0}, Rgb<double>{0, value, 0}, Rgb<double>{0, 0, value}})
      ASSERT_TRUE(channels_near(rgb, round_trip(rgb), kDoubleRoundTrip, value)) << value;
}

TEST(RoimelaYuvColorSpace, BlackHasGreyChrominanceAndDecodesToExactBlack) {
  const RoimelaYuv<double> yuv = rgb_to_roimela_yuv(Rgb<double>{0.0, 0.0, 0.0});
  EXPECT_EQ(yuv.luminance, 0.0);
  EXPECT_DOUBLE_EQ(yuv.u, 0.25);
  EXPECT_DOUBLE_EQ(yuv.v, 0.25);
  const Rgb<double> decoded = roimela_yuv_to_rgb(yuv);
  EXPECT_EQ(decoded.r, 0.0);
  EXPECT_EQ(decoded.g, 0.0);
  EXPECT_EQ(decoded.b, 0.0);
}

TEST(RoimelaYuvColorSpace, GreyHasChrominanceOneQuarterAtEveryLevel) {
  for (double value : {0x1p-40, 0x1p-24, 1.0, 65504.0}) {
    const RoimelaYuv<double> yuv = rgb_to_roimela_yuv(Rgb<double>{value, value, value});
    EXPECT_DOUBLE_EQ(yuv.u, 0.25) << value;
    EXPECT_DOUBLE_EQ(yuv.v, 0.25) << value;
    EXPECT_DOUBLE_EQ(yuv.luminance, value);
  }
}

TEST(RoimelaYuvColorSpace, ChrominanceStaysInTheUnitTriangle) {
  color_testing::RgbSampler sampler(11);
  for (int i = 0; i < 100000; ++i) {
    const RoimelaYuv<double> yuv = rgb_to_roimela_yuv(sampler.texel());
    ASSERT_GE(yuv.u, 0.0);
    ASSERT_GE(yuv.v, 0.0);
    ASSERT_GE(1.0 - yuv.u - yuv.v, -1e-15);
  }
}

TEST(RoimelaYuvColorSpace, RoundTripsInFloat) {
  const auto round_trip_float = [](const Rgb<float>& rgb) { return roimela_yuv_to_rgb(rgb_to_roimela_yuv(rgb)); };
  EXPECT_TRUE(color_testing::round_trips_in_float(round_trip_float, 12, kFloatRoundTrip,
                                                  color_testing::BlackTexels::include));
}

TEST(RoimelaYuvColorSpace, JetRoundTripJacobianIsIdentity) {
  using Jet = ceres::Jet<double, 3>;
  const Rgb<Jet> rgb{Jet(0.3, 0), Jet(5.0, 1), Jet(0.01, 2)};
  const Rgb<Jet> back = roimela_yuv_to_rgb(rgb_to_roimela_yuv(rgb));
  const Jet* channels[3] = {&back.r, &back.g, &back.b};
  for (int row = 0; row < 3; ++row)
    for (int column = 0; column < 3; ++column)
      EXPECT_NEAR(channels[row]->v[column], row == column ? 1.0 : 0.0, 1e-12) << row << "," << column;
}

TEST(RoimelaYuvColorSpace, IntervalResultEnclosesEveryPointOfTheBox) {
  const double boxes[][6] = {{0.5, 0.6, 0.1, 0.2, 0.0, 0.05}, {0.0, 1e-3, 0.0, 1e-3, 0.0, 1e-3}};
  for (const auto& box : boxes) {
    const RoimelaYuv<Interval> enclosure = rgb_to_roimela_yuv(color_testing::box_texel(box));
    EXPECT_TRUE(color_testing::box_encloses_its_points(box, 6, [&](const Rgb<double>& point) {
      const RoimelaYuv<double> value = rgb_to_roimela_yuv(point);
      return boost::numeric::in(value.luminance, enclosure.luminance) && boost::numeric::in(value.u, enclosure.u) &&
             boost::numeric::in(value.v, enclosure.v);
    }));
  }
}

}  // namespace
}  // namespace blocklab
