// Munkberg et al. 2008 section 4 (eqs. 7-10, Figure 1): filtering logYuv texels before the colour transform, with
// and without the luminance normalisation (formats/munkberg/analysis/logyuv_filtering.h, filtering_measurement.h).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/color_spaces.h"
#include "core/error.h"
#include "core/image.h"
#include "formats/munkberg/analysis/filtering_measurement.h"
#include "formats/munkberg/analysis/logyuv_filtering.h"

namespace blocklab::munkberg {
namespace {

constexpr ShiftRule kRules[] = {ShiftRule::nearest, ShiftRule::exponent, ShiftRule::truncate};

TEST(MunkbergFiltering, Figure1CurveHasThePapersEndPointsAndMatchesEq10) {
  const Figure1Setup setup;   // v1 0.25, v2 0.1, Y1 1, Y2 0.1..10, alpha 0.5
  const std::vector<Figure1Point> curve = figure1_curve(setup);
  ASSERT_EQ(curve.size(), 991u);
  EXPECT_EQ(curve.front().y2, 0.1);
  EXPECT_EQ(curve.back().y2, 10.0);
  // "grows from roughly -0.1 to over 1.1 as the luminance Y2 increases"
  EXPECT_GT(curve.front().plain_error, -0.15);
  EXPECT_LT(curve.front().plain_error, -0.05);
  EXPECT_GT(curve.back().plain_error, 1.1);
  for (std::size_t i = 1; i < curve.size(); ++i) EXPECT_GT(curve[i].plain_error, curve[i - 1].plain_error);
  for (const Figure1Point& p : curve) {
    // Direct evaluation of eq. 9 - eq. 8 agrees with the closed form eq. 10, for both filters.
    EXPECT_NEAR(p.plain_error, p.plain_closed_form, 1e-13) << "Y2 = " << p.y2;
    EXPECT_NEAR(p.normalised_error, p.normalised_closed_form, 1e-13) << "Y2 = " << p.y2;
    EXPECT_EQ(p.shift1, 0);   // texel 1 is the reference (the paper shifts Y2)
  }
}

TEST(MunkbergFiltering, NormalisedErrorIsSmallerThanThePlainOneOverTheFigure1Range) {
  for (ShiftRule rule : kRules) {
    Figure1Setup setup;
    setup.rule = rule;
    double plain_max = 0.0, normalised_max = 0.0, plain_squares = 0.0, normalised_squares = 0.0;
    for (const Figure1Point& p : figure1_curve(setup)) {
      if (p.shift2 == 0) {
        EXPECT_EQ(p.normalised_red, p.plain_red) << "no shift must mean the plain filter, Y2 = " << p.y2;
      } else if (p.y2 > setup.y1) {
        // Shifting a brighter Y2 down (c > 1) always helps here. Below Y1 it may not: c < 1 shrinks v2 and so
        // widens v2' - v1 (eq. 10 is a product), e.g. nearest at Y2 in [0.64, 0.70]; the README reports it.
        EXPECT_LT(std::fabs(p.normalised_error), std::fabs(p.plain_error)) << to_string(rule) << " Y2 = " << p.y2;
      }
      plain_max = std::max(plain_max, std::fabs(p.plain_error));
      normalised_max = std::max(normalised_max, std::fabs(p.normalised_error));
      plain_squares += p.plain_error * p.plain_error;
      normalised_squares += p.normalised_error * p.normalised_error;
    }
    // "With our luminance normalization, the error is much smaller": the peak at most a quarter of the plain one,
    // and the RMS over the range below a fifth.
    EXPECT_LT(normalised_max, 0.25 * plain_max) << to_string(rule);
    EXPECT_LT(normalised_squares, 0.04 * plain_squares) << to_string(rule);
  }
}

TEST(MunkbergFiltering, ErrorIsZeroWhenTheLuminancesAreEqual) {
  for (double y : {0.125, 1.0, 4.0, 1024.0}) {   // powers of two: every product is exact, so the error is exactly 0
    const FilterTexel texels[2] = {{y, 0.2, 0.25}, {y, 0.05, 0.1}};
    for (double alpha : {0.0, 0.25, 0.5, 0.875, 1.0}) {
      const double w[2] = {1.0 - alpha, alpha};
      const Rgb<double> correct = filter_after_transform(texels, w, 2);
      const Rgb<double> plain = filter_before_transform(texels, w, 2);
      const Rgb<double> normalised = filter_before_transform_normalised(texels, w, 2, ShiftRule::nearest,
                                                                        ShiftReference::first);
      EXPECT_EQ(plain.r - correct.r, 0.0);
      EXPECT_EQ(normalised.r - correct.r, 0.0);
      EXPECT_EQ(red_error_closed_form(0.25, 0.1, y, y, alpha), 0.0);
    }
  }
  // Any luminance: eq. 10 is exactly 0 and the direct evaluation is 0 up to rounding.
  for (double y : {0.3, 1.7, 77.7}) {
    const FilterTexel texels[2] = {{y, 0.2, 0.25}, {y, 0.05, 0.1}};
    const double w[2] = {0.5, 0.5};
    EXPECT_EQ(red_error_closed_form(0.25, 0.1, y, y, 0.5), 0.0);
    EXPECT_NEAR(filter_before_transform(texels, w, 2).r, filter_after_transform(texels, w, 2).r, 1e-15 * y);
  }
}

TEST(MunkbergFiltering, PlainFilterIsExactWhenAllTexelsShareTheirChrominance) {
  // Eq. 10 is proportional to v2 - v1 (and likewise for u): equal chrominance, any luminances, no error.
  const FilterTexel quad[4] = {{0.01, 0.3, 0.2}, {5.0, 0.3, 0.2}, {300.0, 0.3, 0.2}, {0.7, 0.3, 0.2}};
  const double w[4] = {0.1, 0.2, 0.3, 0.4};
  const Rgb<double> correct = filter_after_transform(quad, w, 4);
  const Rgb<double> plain = filter_before_transform(quad, w, 4);
  EXPECT_NEAR(plain.r, correct.r, 1e-12 * correct.r);
  EXPECT_NEAR(plain.g, correct.g, 1e-12 * correct.g);
  EXPECT_NEAR(plain.b, correct.b, 1e-12 * correct.b);
}

TEST(MunkbergFiltering, NormalisationToEqualLuminanceIsExactInEveryChannelIncludingGreen) {
  // Y2 = 8 Y1: k = 3 under every rule, Y2' = Y1, so the normalised filter is exact; green needs the interpolated
  // c (G = (c - u' - v') Y' / wg), which this checks, while the plain filter is off in all three channels.
  const FilterTexel texels[2] = {{0.5, 0.1, 0.3}, {4.0, 0.4, 0.05}};
  const double w[2] = {0.375, 0.625};
  const Rgb<double> correct = filter_after_transform(texels, w, 2);
  for (ShiftRule rule : kRules) {
    int shifts[2];
    const Rgb<double> n = filter_before_transform_normalised(texels, w, 2, rule, ShiftReference::first, shifts);
    EXPECT_EQ(shifts[0], 0);
    EXPECT_EQ(shifts[1], 3) << to_string(rule);
    EXPECT_NEAR(n.r, correct.r, 1e-15);
    EXPECT_NEAR(n.g, correct.g, 1e-15);
    EXPECT_NEAR(n.b, correct.b, 1e-15);
  }
  const Rgb<double> plain = filter_before_transform(texels, w, 2);
  EXPECT_GT(std::fabs(plain.r - correct.r), 0.1);
  EXPECT_GT(std::fabs(plain.g - correct.g), 0.05);
  EXPECT_GT(std::fabs(plain.b - correct.b), 0.1);
}

TEST(MunkbergFiltering, OneTexelFootprintReproducesTheTexelUnderEveryFilter) {
  const Rgb<double> rgb{3.0, 0.5, 0.25};
  const FilterTexel texel = filter_texel_from_rgb(rgb);
  const double w[1] = {1.0};
  for (const Rgb<double>& out :
       {filter_after_transform(&texel, w, 1), filter_before_transform(&texel, w, 1),
        filter_before_transform_normalised(&texel, w, 1, ShiftRule::nearest, ShiftReference::brightest)}) {
    EXPECT_NEAR(out.r, rgb.r, 1e-14);
    EXPECT_NEAR(out.g, rgb.g, 1e-14);
    EXPECT_NEAR(out.b, rgb.b, 1e-14);
  }
  // Black is the eq. 3 black level: luminance 0, decodes to exact black.
  const FilterTexel black = filter_texel_from_rgb(Rgb<double>{0.0, 0.0, 0.0});
  EXPECT_EQ(black.luminance, 0.0);
  const Rgb<double> decoded = rgb_from_filter_texel(black);
  EXPECT_EQ(decoded.r, 0.0);
  EXPECT_EQ(decoded.g, 0.0);
  EXPECT_EQ(decoded.b, 0.0);
}

TEST(MunkbergFiltering, ShiftRulesCompareMagnitudesAsDocumented) {
  // 3 = 2^1.58: nearest rounds to 2, truncate keeps 1; exponents of 3 (0.75 * 2^2) and 1 (0.5 * 2^1) differ by 1.
  EXPECT_EQ(normalisation_shift(3.0, 1.0, ShiftRule::nearest), 2);
  EXPECT_EQ(normalisation_shift(3.0, 1.0, ShiftRule::truncate), 1);
  EXPECT_EQ(normalisation_shift(3.0, 1.0, ShiftRule::exponent), 1);
  EXPECT_EQ(normalisation_shift(1.0 / 3.0, 1.0, ShiftRule::nearest), -2);
  EXPECT_EQ(normalisation_shift(1.0 / 3.0, 1.0, ShiftRule::truncate), -1);
  // Within a factor sqrt(2) nearest does not shift; the exponent rule shifts across a power of two.
  EXPECT_EQ(normalisation_shift(1.3, 1.0, ShiftRule::nearest), 0);
  EXPECT_EQ(normalisation_shift(1.01, 0.99, ShiftRule::exponent), 1);
  for (ShiftRule rule : kRules) {
    EXPECT_EQ(normalisation_shift(0.0, 1.0, rule), 0);   // black texel
    EXPECT_EQ(normalisation_shift(1.0, 0.0, rule), 0);   // black reference
    EXPECT_EQ(normalisation_shift(1e300, 1e-300, rule), kMaxShift);
    EXPECT_EQ(normalisation_shift(1e-300, 1e300, rule), -kMaxShift);
    EXPECT_EQ(normalisation_shift(std::numeric_limits<double>::infinity(), 1.0, rule), 0);
  }
  const FilterTexel quad[4] = {{0.0, 0.1, 0.3}, {2.0, 0.1, 0.3}, {9.0, 0.1, 0.3}, {9.0, 0.1, 0.3}};
  EXPECT_EQ(normalisation_reference(quad, 4, ShiftReference::first), 2u);      // texel 0 is black
  EXPECT_EQ(normalisation_reference(quad + 1, 3, ShiftReference::first), 0u);
  EXPECT_EQ(normalisation_reference(quad + 1, 3, ShiftReference::brightest), 1u);   // first of the tie
  EXPECT_THROW(shift_rule_from_string("round"), Error);
  EXPECT_THROW(shift_reference_from_string("darkest"), Error);
}

Image image_from(int width, int height, const std::vector<Rgb<float>>& texels) {
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Rgb<float>& c = texels[static_cast<std::size_t>(y) * width + x];
      float* p = image.texel(x, y);
      p[0] = c.r;
      p[1] = c.g;
      p[2] = c.b;
    }
  return image;
}

TEST(MunkbergFiltering, ImageOfOneChromaticityHasNoPlainFilteringError) {
  std::vector<Rgb<float>> texels;
  for (int i = 0; i < 5 * 4; ++i) {
    const float scale = std::ldexp(1.0f, i % 7 - 3) * (1.0f + 0.1f * static_cast<float>(i));
    texels.push_back({0.5f * scale, 0.25f * scale, 0.125f * scale});
  }
  const FilteringMeasurement m =
      measure_logyuv_filtering(image_from(5, 4, texels), 2, ShiftRule::nearest, ShiftReference::first);
  EXPECT_EQ(m.quads, 4u * 3u);
  EXPECT_EQ(m.samples, 4u * 4u * 3u);
  EXPECT_LT(m.plain.log2_rmse, 1e-12);
  EXPECT_EQ(m.plain.fraction_above_1_percent, 0.0);
}

TEST(MunkbergFiltering, SharpColourEdgeIsFilteredBetterWithNormalisation) {
  // Figure 2's worst case: a red texel next to a bright blue one (ratio 100 in luminance), in stripes.
  std::vector<Rgb<float>> texels;
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x) texels.push_back(x % 2 == 0 ? Rgb<float>{1.0f, 0.0f, 0.0f} : Rgb<float>{0, 0, 300.0f});
  const Image image = image_from(6, 6, texels);
  for (ShiftRule rule : kRules)
    for (int m : {1, 2, 3}) {
      const FilteringMeasurement f = measure_logyuv_filtering(image, m, rule, ShiftReference::first);
      EXPECT_EQ(f.samples, static_cast<std::size_t>(m * m * 25));
      EXPECT_EQ(f.shifted_quads, 25u);
      EXPECT_EQ(f.fraction_quads_ratio_above_2, 1.0);
      EXPECT_GT(f.plain.log2_rmse, 1.0) << to_string(rule) << " m " << m;
      EXPECT_LT(f.normalised.log2_rmse, 0.5 * f.plain.log2_rmse) << to_string(rule) << " m " << m;
    }
}

TEST(MunkbergFiltering, BadInputIsAnErrorNamingTheProblem) {
  const Image tiny(1, 5);
  EXPECT_THROW(measure_logyuv_filtering(tiny, 2, ShiftRule::nearest, ShiftReference::first), Error);
  const Image ok(2, 2);
  EXPECT_THROW(measure_logyuv_filtering(ok, 0, ShiftRule::nearest, ShiftReference::first), Error);
  EXPECT_THROW(measure_logyuv_filtering(ok, 17, ShiftRule::nearest, ShiftReference::first), Error);
  Figure1Setup setup;
  setup.samples = 1;
  EXPECT_THROW(figure1_curve(setup), Error);
  setup = Figure1Setup{};
  setup.alpha = 1.5;
  EXPECT_THROW(figure1_curve(setup), Error);
  setup = Figure1Setup{};
  setup.y2_first = 0.0;
  setup.geometric = true;
  EXPECT_THROW(figure1_curve(setup), Error);
  setup = Figure1Setup{};
  setup.v1 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(figure1_curve(setup), Error);
}

}  // namespace
}  // namespace blocklab::munkberg
