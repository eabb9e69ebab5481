// CIE 1976 L*a*b* from linear Rec.709/sRGB RGB, D65 (CIE 15:2004; IEC 61966-2-1 primaries): the derived matrix
// against the standard's table, known Lab values of the primaries, white and black, continuity at epsilon, round
// trips over the fp16 range, float and ceres::Jet.
#include <gtest/gtest.h>

#include <cmath>

#include "core/color_spaces.h"
#include "core/scalar.h"
#include "test_color_common.h"

namespace blocklab {
namespace {

using color_testing::channels_near;
using color_testing::largest_channel;

// IEC 61966-2-1 prints the RGB -> XYZ matrix rounded to 4 decimals: the derived one must agree to half a unit of
// the last printed digit.
constexpr double kPrintedMatrixRounding = 0.5e-4;
// Published Lab of the sRGB primaries are computed from the rounded table and a rounded white (95.047, 100,
// 108.883); that rounding moves L*, a*, b* by up to ~0.01, so they are compared to 0.02.
constexpr double kPublishedLabTolerance = 0.02;
// Round trip, relative to the largest channel: a matrix product, cbrt then cube (relative error ~3 ulp), and the
// inverse matrix whose condition number is ~10: ~1e-14; 1e-12 is a 100x margin.
constexpr double kDoubleRoundTrip = 1e-12;
// The same in float: ~1e-6 * 10; 1e-4 leaves a 10x margin.
constexpr double kFloatRoundTrip = 1e-4;
// Dark colours (t = X/Xn etc. below epsilon) are held in the linear piece f = (kappa t + 16) / 116, i.e. on top of
// the constant 16/116, so t keeps only an absolute precision of ulp(16/116) * 116 / kappa / 2: 4e-18 in double,
// 1e-9 in float; the inverse matrix (condition ~10) scales that up (measured: 1.3e-17 and 8.4e-9). These
// absolute allowances add to the relative ones above; they are a property of CIE L*a*b*, not of the code.
constexpr double kDoubleDarkAbsolute = 1e-16;
constexpr double kFloatDarkAbsolute = 5e-8;

TEST(LabColorSpace, DerivedRec709MatrixMatchesTheSrgbStandardTable) {
  const double printed[3][3] = {{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(kRec709RgbToXyz.m[i][j], printed[i][j], kPrintedMatrixRounding) << i << j;
  // RGB (1, 1, 1) maps to the D65 white of the sRGB standard, xy = (0.3127, 0.3290), at Y = 1.
  EXPECT_NEAR(kD65WhiteY, 1.0, 1e-15);
  EXPECT_NEAR(kD65WhiteX, 0.3127 / 0.3290, 1e-15);
  EXPECT_NEAR(kD65WhiteZ, (1.0 - 0.3127 - 0.3290) / 0.3290, 1e-15);
  // (The often-quoted 0.95047, 1.08883 come from the CIE 1931 table of D65, xy = (0.31271, 0.32902): X is 1e-5
  // and Z 2.3e-4 away from the sRGB white, which is why published Lab values are only compared to 0.02 below.)
  EXPECT_NEAR(kD65WhiteX, 0.95047, 1e-4);
  EXPECT_NEAR(kD65WhiteZ, 1.08883, 3e-4);
}

TEST(LabColorSpace, InverseMatrixIsTheExactInverse) {
  const auto product = color_detail::multiply(kRec709RgbToXyz, kXyzToRec709Rgb);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(product.m[i][j], i == j ? 1.0 : 0.0, 1e-15) << i << j;
}

TEST(LabColorSpace, WhiteIsL100AndBlackIsL0WithZeroChroma) {
  const Lab<double> white = rec709_to_lab(Rgb<double>{1.0, 1.0, 1.0});
  EXPECT_NEAR(white.l, 100.0, 1e-12);
  EXPECT_NEAR(white.a, 0.0, 1e-12);
  EXPECT_NEAR(white.b, 0.0, 1e-12);
  const Lab<double> black = rec709_to_lab(Rgb<double>{0.0, 0.0, 0.0});
  EXPECT_EQ(black.l, 0.0);
  EXPECT_EQ(black.a, 0.0);
  EXPECT_EQ(black.b, 0.0);
}

TEST(LabColorSpace, PrimariesHaveTheirPublishedLabValues) {
  // sRGB primaries in CIE L*a*b* (D65), as tabulated by common colour calculators (e.g. EasyRGB / Lindbloom).
  struct Case {
    Rgb<double> rgb;
    double l, a, b;
  };
  const Case cases[] = {{{1, 0, 0}, 53.2408, 80.0925, 67.2032},
                        {{0, 1, 0}, 87.7347, -86.1827, 83.1793},
                        {{0, 0, 1}, 32.2970, 79.1875, -107.8602}};
  for (const Case& c : cases) {
    const Lab<double> lab = rec709_to_lab(c.rgb);
    EXPECT_NEAR(lab.l, c.l, kPublishedLabTolerance);
    EXPECT_NEAR(lab.a, c.a, kPublishedLabTolerance);
    EXPECT_NEAR(lab.b, c.b, kPublishedLabTolerance);
  }
}

TEST(LabColorSpace, GreyL50IsAt18PercentReflectanceAndTheDarkPieceIsLinear) {
  // L* = 50 <=> Y/Yn = ((50 + 16) / 116)^3 = 0.18419.
  const double y50 = std::pow(66.0 / 116.0, 3.0);
  EXPECT_NEAR(rec709_to_lab(Rgb<double>{y50, y50, y50}).l, 50.0, 1e-12);
  // Below epsilon, L* = kappa * Y / Yn.
  EXPECT_NEAR(rec709_to_lab(Rgb<double>{0.001, 0.001, 0.001}).l, kCieKappa * 0.001, 1e-12);
}

TEST(LabColorSpace, PiecewiseFunctionIsContinuousAtEpsilon) {
  // With the rational epsilon and kappa, both pieces give 6/29 at t = epsilon.
  const double below = std::nextafter(kCieEpsilon, 0.0);
  const double above = std::nextafter(kCieEpsilon, 1.0);
  EXPECT_NEAR(color_detail::cie_f(below), 6.0 / 29.0, 1e-15);
  EXPECT_NEAR(color_detail::cie_f(above), 6.0 / 29.0, 1e-15);
  EXPECT_NEAR(color_detail::cie_f_inverse(6.0 / 29.0), kCieEpsilon, 1e-17);
}

TEST(LabColorSpace, RoundTripsRandomHdrTexelsAndEdgeTexels) {
  color_testing::RgbSampler sampler(1976);
  for (int i = 0; i < 200000; ++i) {
    const Rgb<double> rgb = sampler.texel();
    if (largest_channel(rgb) == 0.0) continue;
    ASSERT_TRUE(channels_near(rgb, lab_to_rec709(rec709_to_lab(rgb)), kDoubleRoundTrip, largest_channel(rgb),
                              kDoubleDarkAbsolute))
        << "sample " << i;
  }
  for (const Rgb<double>& rgb : color_testing::edge_texels())
    EXPECT_TRUE(channels_near(rgb, lab_to_rec709(rec709_to_lab(rgb)), kDoubleRoundTrip, largest_channel(rgb),
                              kDoubleDarkAbsolute));
}

TEST(LabColorSpace, RoundTripsInFloat) {
  color_testing::RgbSampler sampler(15);
  for (int i = 0; i < 100000; ++i) {
    const Rgb<double> rgb = sampler.texel_within_stops(4.0);
    const Rgb<float> rgb_float{static_cast<float>(rgb.r), static_cast<float>(rgb.g), static_cast<float>(rgb.b)};
    const Rgb<float> back = lab_to_rec709(rec709_to_lab(rgb_float));
    const Rgb<double> input{rgb_float.r, rgb_float.g, rgb_float.b};
    ASSERT_TRUE(channels_near(input, Rgb<double>{back.r, back.g, back.b}, kFloatRoundTrip, largest_channel(input),
                              kFloatDarkAbsolute))
        << "sample " << i;
  }
}

TEST(LabColorSpace, JetDerivativeOfLightnessFollowsTheBranchTaken) {
  using Jet = ceres::Jet<double, 1>;
  // Grey, so Y/Yn = value: above epsilon dL*/dY = 116/3 Y^(-2/3); below it kappa.
  const double bright = 0.5, dark = 0.001;
  EXPECT_NEAR(rec709_to_lab(Rgb<Jet>{Jet(bright, 0), Jet(bright, 0), Jet(bright, 0)}).l.v[0],
              116.0 / 3.0 * std::pow(bright, -2.0 / 3.0), 1e-9);
  EXPECT_NEAR(rec709_to_lab(Rgb<Jet>{Jet(dark, 0), Jet(dark, 0), Jet(dark, 0)}).l.v[0], kCieKappa, 1e-9);
}

}  // namespace
}  // namespace blocklab
