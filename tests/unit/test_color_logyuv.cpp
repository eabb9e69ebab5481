// logYuv (Munkberg et al. 2008, section 3.1, eq. 2) and its black-level rule (eq. 3): round trips over the fp16
// range, chrominance range, the documented floors, and the same template on float, ceres::Jet and Interval.
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

// Round-trip tolerance in double, relative to the texel's largest channel. log2 then exp2 turn the rounding of
// Ybar (|Ybar| <= 28, so an absolute error of ~28 * 2^-53) into a relative luminance error of ~28 ln2 ulp, and a
// channel absent from the texel is recovered through the cancellation 1 - u - v (an absolute error of a few ulp
// of Y / wg): both are a few 1e-15 of the largest channel (1.6e-15 measured over 300k samples); 1e-13 leaves a
// 50x margin.
constexpr double kDoubleRoundTrip = 1e-13;
// The same in float (ulp 2^-23 instead of 2^-52): ~28 ln2 * 6e-8 = 1.2e-6; 1e-5 leaves an 8x margin.
constexpr double kFloatRoundTrip = 1e-5;

Rgb<double> round_trip(const Rgb<double>& rgb) { return logyuv_to_rgb(rgb_to_logyuv(rgb)); }

TEST(LogYuvColorSpace, UsesTheRec601LumaWeightsThePaperCites) {
  // Munkberg 2008, section 3.1: "weights according to the Rec. 601 standard".
  EXPECT_EQ(kRec601WeightR, 0.299);
  EXPECT_EQ(kRec601WeightG, 0.587);
  EXPECT_EQ(kRec601WeightB, 0.114);
  EXPECT_NEAR(kRec601WeightR + kRec601WeightG + kRec601WeightB, 1.0, 1e-15);
}

TEST(LogYuvColorSpace, ForwardMatchesEquation2OnAKnownTexel) {
  const LogYuv<double> yuv = rgb_to_logyuv(Rgb<double>{2.0, 4.0, 8.0});
  const double luminance = 0.299 * 2.0 + 0.587 * 4.0 + 0.114 * 8.0;
  EXPECT_DOUBLE_EQ(yuv.log_luminance, std::log2(luminance));
  EXPECT_DOUBLE_EQ(yuv.u, 0.114 * 8.0 / luminance);
  EXPECT_DOUBLE_EQ(yuv.v, 0.299 * 2.0 / luminance);
}

TEST(LogYuvColorSpace, RoundTripsRandomHdrTexels) {
  EXPECT_TRUE(color_testing::round_trips_random_hdr_texels(round_trip, 20080601, kDoubleRoundTrip));
}

TEST(LogYuvColorSpace, RoundTripsPurePrimariesGreyAndExtremeTexels) {
  EXPECT_TRUE(color_testing::round_trips_edge_texels(round_trip, kDoubleRoundTrip));
}

TEST(LogYuvColorSpace, RoundTripsEveryPositiveHalfAsGreyAndAsEachPrimary) {
  // The luminance floor 2^-28 is below wb * 2^-24, so no non-black fp16 texel is floored.
  for (double value : color_testing::positive_half_values()) {
    for (const Rgb<double>& rgb : {Rgb<double>{value, 0, 0}, Rgb<double>{0, value, 0}, Rgb<double>{0, 0, value},
                                   Rgb<double>{value, value, value}}) {
      ASSERT_GT(rgb_to_logyuv(rgb).log_luminance, std::log2(kLogYuvLuminanceFloor)) << value;
      ASSERT_TRUE(channels_near(rgb, round_trip(rgb), kDoubleRoundTrip, value)) << value;
    }
  }
}

TEST(LogYuvColorSpace, ChrominanceStaysInTheUnitTriangle) {
  color_testing::RgbSampler sampler(7);
  for (int i = 0; i < 100000; ++i) {
    const LogYuv<double> yuv = rgb_to_logyuv(sampler.texel());
    // u, v and the implied green share 1 - u - v are each in [0, 1] (up to rounding of the division).
    ASSERT_GE(yuv.u, 0.0);
    ASSERT_GE(yuv.v, 0.0);
    ASSERT_LE(yuv.u, 1.0 + 1e-15);
    ASSERT_LE(yuv.v, 1.0 + 1e-15);
    ASSERT_GE(1.0 - yuv.u - yuv.v, -1e-15);
  }
}

TEST(LogYuvColorSpace, GreyHasChrominanceWbWrAtEveryLevel) {
  for (double value : {0.0, 0x1p-40, 0x1p-24, 1.0, 3.7, 65504.0}) {
    const LogYuv<double> yuv = rgb_to_logyuv(Rgb<double>{value, value, value});
    EXPECT_DOUBLE_EQ(yuv.u, kRec601WeightB) << value;
    EXPECT_DOUBLE_EQ(yuv.v, kRec601WeightR) << value;
  }
}

TEST(LogYuvColorSpace, BlackGetsTheFloorLuminanceAndGreyChrominance) {
  const LogYuv<double> yuv = rgb_to_logyuv(Rgb<double>{0.0, 0.0, 0.0});
  EXPECT_EQ(yuv.log_luminance, -28.0);
  EXPECT_DOUBLE_EQ(yuv.u, kRec601WeightB);
  EXPECT_DOUBLE_EQ(yuv.v, kRec601WeightR);
  // Without eq. (3), black decodes to grey at the floor luminance.
  const Rgb<double> decoded = logyuv_to_rgb(yuv);
  EXPECT_TRUE(channels_near(Rgb<double>{0x1p-28, 0x1p-28, 0x1p-28}, decoded, kDoubleRoundTrip, 0x1p-28));
}

TEST(LogYuvColorSpace, LuminanceBelowTheFloorIsRaisedButKeepsItsChromaticity) {
  const Rgb<double> dim{0x1p-32, 0x1p-31, 0x1p-33};
  const LogYuv<double> yuv = rgb_to_logyuv(dim);
  EXPECT_EQ(yuv.log_luminance, std::log2(kLogYuvLuminanceFloor));
  const Rgb<double> decoded = logyuv_to_rgb(yuv);
  const double luminance = kRec601WeightR * dim.r + kRec601WeightG * dim.g + kRec601WeightB * dim.b;
  const double scale = kLogYuvLuminanceFloor / luminance;
  EXPECT_TRUE(channels_near(Rgb<double>{dim.r * scale, dim.g * scale, dim.b * scale}, decoded, kDoubleRoundTrip,
                            dim.g * scale));
}

TEST(LogYuvColorSpace, MinimumLuminanceCodeDecodesToTrueBlack) {
  // Eq. (3): Y = 0 when the stored code is the minimum code, 2^Ybar otherwise.
  EXPECT_EQ(logyuv_luminance_from_code<double>(0, 0, -16.0), 0.0);
  EXPECT_EQ(logyuv_luminance_from_code<double>(1, 0, -15.9375), std::exp2(-15.9375));
  EXPECT_EQ(logyuv_luminance_from_code<double>(255, 0, 16.0), 65536.0);
  const Rgb<double> black = logyuv_to_rgb_from_luminance(logyuv_luminance_from_code<double>(0, 0, -16.0),
                                                         kRec601WeightB, kRec601WeightR);
  EXPECT_EQ(black.r, 0.0);
  EXPECT_EQ(black.g, 0.0);
  EXPECT_EQ(black.b, 0.0);
}

TEST(LogYuvColorSpace, RoundTripsInFloat) {
  const auto round_trip_float = [](const Rgb<float>& rgb) { return logyuv_to_rgb(rgb_to_logyuv(rgb)); };
  EXPECT_TRUE(color_testing::round_trips_in_float(round_trip_float, 99, kFloatRoundTrip,
                                                  color_testing::BlackTexels::skip));
}

TEST(LogYuvColorSpace, JetDerivativesMatchEquation2AndTheRoundTripJacobianIsIdentity) {
  using Jet = ceres::Jet<double, 3>;
  const Rgb<double> point{0.7, 0.2, 1.9};
  const Rgb<Jet> rgb{Jet(point.r, 0), Jet(point.g, 1), Jet(point.b, 2)};
  const LogYuv<Jet> yuv = rgb_to_logyuv(rgb);
  const double luminance = kRec601WeightR * point.r + kRec601WeightG * point.g + kRec601WeightB * point.b;
  // d log2(Y) / dc = w_c / (Y ln 2).
  EXPECT_NEAR(yuv.log_luminance.v[0], kRec601WeightR / (luminance * std::log(2.0)), 1e-14);
  EXPECT_NEAR(yuv.log_luminance.v[1], kRec601WeightG / (luminance * std::log(2.0)), 1e-14);
  EXPECT_NEAR(yuv.log_luminance.v[2], kRec601WeightB / (luminance * std::log(2.0)), 1e-14);
  // d v / dR = wr / Y - wr R wr / Y^2.
  EXPECT_NEAR(yuv.v.v[0], kRec601WeightR / luminance - kRec601WeightR * point.r * kRec601WeightR /
                                                           (luminance * luminance), 1e-14);
  const Rgb<Jet> back = logyuv_to_rgb(yuv);
  const Jet* channels[3] = {&back.r, &back.g, &back.b};
  for (int row = 0; row < 3; ++row)
    for (int column = 0; column < 3; ++column)
      EXPECT_NEAR(channels[row]->v[column], row == column ? 1.0 : 0.0, 1e-12) << row << "," << column;
}

TEST(LogYuvColorSpace, IntervalResultEnclosesEveryPointOfTheBox) {
  // Boxes including one that touches black (where the floor and the regulariser matter).
  const double boxes[][6] = {{0.5, 0.6, 0.1, 0.2, 0.0, 0.05}, {0.0, 1e-3, 0.0, 1e-3, 0.0, 1e-3},
                             {100.0, 65504.0, 1.0, 2.0, 3.0, 4.0}};
  for (const auto& box : boxes) {
    const LogYuv<Interval> enclosure = rgb_to_logyuv(color_testing::box_texel(box));
    EXPECT_TRUE(color_testing::box_encloses_its_points(box, 5, [&](const Rgb<double>& point) {
      const LogYuv<double> value = rgb_to_logyuv(point);
      return boost::numeric::in(value.log_luminance, enclosure.log_luminance) &&
             boost::numeric::in(value.u, enclosure.u) && boost::numeric::in(value.v, enclosure.v);
    }));
  }
}

}  // namespace
}  // namespace blocklab
