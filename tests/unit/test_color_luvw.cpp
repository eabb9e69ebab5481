// LUVW (Munkberg et al. 2008, section 3.3, eq. 5; Wang et al. 2007, eq. 1): round trips, unit-length UVW, the
// L = 0 rule, and the same template on float, ceres::Jet and Interval.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "formats/munkberg/munkberg_color_spaces.h"
#include "core/interval.h"
#include "core/scalar.h"
#include "test_color_common.h"

namespace blocklab {
namespace {

using color_testing::channels_near;
using color_testing::largest_channel;

// Round-trip tolerance in double, relative to the largest channel: sqrt, one division and one multiplication per
// channel, each within half an ulp: ~1e-15; 1e-13 is a 100x margin.
constexpr double kDoubleRoundTrip = 1e-13;
// The same in float: ~4e-7; 5e-6 is a 10x margin.
constexpr double kFloatRoundTrip = 5e-6;

Rgb<double> round_trip(const Rgb<double>& rgb) { return luvw_to_rgb(rgb_to_luvw(rgb)); }

TEST(LuvwColorSpace, ForwardMatchesEquation5OnAKnownTexel) {
  const Luvw<double> luvw = rgb_to_luvw(Rgb<double>{2.0, 3.0, 6.0});   // |(2, 3, 6)| = 7
  EXPECT_EQ(luvw.l, 7.0);
  EXPECT_DOUBLE_EQ(luvw.u, 2.0 / 7.0);
  EXPECT_DOUBLE_EQ(luvw.v, 3.0 / 7.0);
  EXPECT_DOUBLE_EQ(luvw.w, 6.0 / 7.0);
}

TEST(LuvwColorSpace, RoundTripsRandomHdrTexels) {
  EXPECT_TRUE(color_testing::round_trips_random_hdr_texels(round_trip, 2007, kDoubleRoundTrip));
}

TEST(LuvwColorSpace, RoundTripsPurePrimariesGreyAndExtremeTexels) {
  EXPECT_TRUE(color_testing::round_trips_edge_texels(round_trip, kDoubleRoundTrip));
}

TEST(LuvwColorSpace, RoundTripsEveryPositiveHalfAsEachPrimary) {
  for (double value : color_testing::positive_half_values())
    for (const Rgb<double>& rgb : {Rgb<double>{value, 0, 0}, Rgb<double>{0, value, 0}, Rgb<double>{0, 0, value}})
      ASSERT_TRUE(channels_near(rgb, round_trip(rgb), kDoubleRoundTrip, value)) << value;
}

TEST(LuvwColorSpace, DirectionIsAUnitVectorWithComponentsInTheUnitInterval) {
  color_testing::RgbSampler sampler(13);
  for (int i = 0; i < 100000; ++i) {
    const Rgb<double> rgb = sampler.texel();
    if (largest_channel(rgb) == 0.0) continue;
    const Luvw<double> luvw = rgb_to_luvw(rgb);
    ASSERT_NEAR(luvw.u * luvw.u + luvw.v * luvw.v + luvw.w * luvw.w, 1.0, 1e-14);
    for (double component : {luvw.u, luvw.v, luvw.w}) {
      ASSERT_GE(component, 0.0);
      ASSERT_LE(component, 1.0);
    }
  }
}

TEST(LuvwColorSpace, BlackHasAGreyDirectionAndDecodesToExactBlack) {
  const Luvw<double> luvw = rgb_to_luvw(Rgb<double>{0.0, 0.0, 0.0});
  EXPECT_EQ(luvw.l, 0.0);
  EXPECT_DOUBLE_EQ(luvw.u, 1.0 / std::sqrt(3.0));
  EXPECT_DOUBLE_EQ(luvw.v, 1.0 / std::sqrt(3.0));
  EXPECT_DOUBLE_EQ(luvw.w, 1.0 / std::sqrt(3.0));
  const Rgb<double> decoded = luvw_to_rgb(luvw);
  EXPECT_EQ(decoded.r, 0.0);
  EXPECT_EQ(decoded.g, 0.0);
  EXPECT_EQ(decoded.b, 0.0);
}

TEST(LuvwColorSpace, RoundTripsInFloat) {
  const auto round_trip_float = [](const Rgb<float>& rgb) { return luvw_to_rgb(rgb_to_luvw(rgb)); };
  EXPECT_TRUE(color_testing::round_trips_in_float(round_trip_float, 14, kFloatRoundTrip,
                                                  color_testing::BlackTexels::include));
}

TEST(LuvwColorSpace, JetDerivativeOfLengthIsTheDirection) {
  using Jet = ceres::Jet<double, 3>;
  const Luvw<Jet> luvw = rgb_to_luvw(Rgb<Jet>{Jet(2.0, 0), Jet(3.0, 1), Jet(6.0, 2)});
  // dL/dc = c / L.
  EXPECT_NEAR(luvw.l.v[0], 2.0 / 7.0, 1e-15);
  EXPECT_NEAR(luvw.l.v[1], 3.0 / 7.0, 1e-15);
  EXPECT_NEAR(luvw.l.v[2], 6.0 / 7.0, 1e-15);
  const Rgb<Jet> back = luvw_to_rgb(luvw);
  const Jet* channels[3] = {&back.r, &back.g, &back.b};
  for (int row = 0; row < 3; ++row)
    for (int column = 0; column < 3; ++column)
      EXPECT_NEAR(channels[row]->v[column], row == column ? 1.0 : 0.0, 1e-12) << row << "," << column;
}

TEST(LuvwColorSpace, IntervalResultEnclosesEveryPointOfTheBox) {
  const double boxes[][6] = {{0.5, 0.6, 0.1, 0.2, 0.0, 0.05}, {0.0, 1e-3, 0.0, 1e-3, 0.0, 1e-3}};
  for (const auto& box : boxes) {
    const Luvw<Interval> enclosure = rgb_to_luvw(color_testing::box_texel(box));
    EXPECT_TRUE(color_testing::box_encloses_its_points(box, 7, [&](const Rgb<double>& point) {
      const Luvw<double> value = rgb_to_luvw(point);
      return boost::numeric::in(value.l, enclosure.l) && boost::numeric::in(value.u, enclosure.u) &&
             boost::numeric::in(value.v, enclosure.v) && boost::numeric::in(value.w, enclosure.w);
    }));
  }
}

}  // namespace
}  // namespace blocklab
