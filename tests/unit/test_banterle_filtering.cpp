// Banterle et al. 2008 section 4.5 (formats/banterle/filtering_error.h): eq. 7 through g equals the paper's closed
// form, vanishes at the interval end points, has the sign of g's convexity; the bilinear image measurement is 0 on
// a constant image and equals eq. 7 at x = 1/4, 3/4 on two-valued stripes; bad input is an Error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "formats/banterle/filtering_error.h"
#include "formats/banterle/reinhard_operator.h"

namespace blocklab {
namespace {

ReinhardParameters parameters(double alpha, double l_white, double mean) {
  ReinhardParameters p;
  p.alpha = alpha;
  p.l_white = l_white;
  p.mean = mean;
  return p;
}

TEST(BanterleFiltering, Eq7ThroughTheInverseEqualsThePapersClosedFormAndVanishesAtTheEndPoints) {
  for (const ReinhardParameters& p : {parameters(0.18, 12.0, 0.05), parameters(0.75, 77.3, 0.62),
                                      parameters(0.3, 1.5, 3.0), parameters(0.5, 0.6, 1.0)}) {
    for (const auto& [a, b] : {std::pair{0.3, 0.6}, std::pair{0.0, 1.0}, std::pair{0.1, 0.15}}) {
      const auto curve = filtering_error_curve(p, a, b, 41);
      ASSERT_EQ(curve.size(), 41u);
      EXPECT_EQ(curve.front().x, 0.0);
      EXPECT_EQ(curve.back().x, 1.0);
      EXPECT_EQ(curve.front().error, 0.0) << "x = 0 is b itself";
      EXPECT_EQ(curve.back().error, 0.0) << "x = 1 is a itself";
      EXPECT_EQ(curve.front().tone_mapped, b);
      EXPECT_EQ(curve.back().tone_mapped, a);
      const double peak = std::max_element(curve.begin(), curve.end(), [](const auto& l, const auto& r) {
                            return l.error < r.error;
                          })->error;
      EXPECT_GT(peak, 0.0);
      for (const FilteringCurvePoint& point : curve) {
        EXPECT_NEAR(point.closed_form_error, point.error, 1e-9 * peak) << "x " << point.x;
        // Lwhite > 1: f is concave, g convex, so the tone-mapped filter never exceeds the HDR filter (Jensen).
        if (p.l_white > 1.0) {
          EXPECT_GE(point.hdr_filtered, point.tone_mapped_filtered - 1e-12 * peak);
        } else {   // Lwhite < 1: f convex, g concave, the opposite order
          EXPECT_LE(point.hdr_filtered, point.tone_mapped_filtered + 1e-12 * peak);
        }
      }
    }
  }
}

TEST(BanterleFiltering, WorstCaseIntervalHasTheLargerError) {
  const ReinhardParameters p = parameters(0.18, 12.0, 0.05);
  const auto peak = [&](double a, double b) {
    double best = 0.0;
    for (const auto& point : filtering_error_curve(p, a, b, 201)) best = std::max(best, point.error);
    return best;
  };
  EXPECT_GT(peak(0.0, 1.0), 10.0 * peak(0.3, 0.6));
}

Image stripes(double l0, double l1, int width, int height) {
  Image image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) image.texel(x, y)[c] = static_cast<float>(x % 2 == 0 ? l0 : l1);
  return image;
}

TEST(BanterleFiltering, ConstantImageHasNoFilteringError) {
  const FilteringMeasurement m = measure_bilinear_filtering_error(stripes(2.5, 2.5, 6, 5), parameters(0.18, 12.0, 0.5));
  EXPECT_EQ(m.samples, 4u * 5u * 4u);
  EXPECT_EQ(m.max_error, 0.0);
  EXPECT_EQ(m.mean_interval, 0.0);
  EXPECT_EQ(m.max_log2_error, 0.0);
}

TEST(BanterleFiltering, StripesMeasureEq7AtTheBilinearMagnificationWeights) {
  const ReinhardParameters p = parameters(0.18, 12.0, 0.5);
  const Image image = stripes(0.25, 40.0, 8, 3);
  // The texels' tone-mapped luminances, as the measurement computes them (luminance in float, eq. 1 in double).
  const auto tone = [&](int x) {
    const double l = static_cast<double>(banterle_luminance(image.texel(x, 0)));
    return std::min(reinhard_forward_scaled(p.alpha / p.mean * l, p.l_white), 1.0);
  };
  const double a = tone(0), b = tone(1);
  const FilteringMeasurement m = measure_bilinear_filtering_error(image, p);
  // Every quad holds one dark and one bright column: weights 3/4 and 1/4 on either side, so the errors are
  // eq. 7 at x = 1/4 and x = 3/4 on [a, b], half of the samples each.
  const double e1 = filtering_error_closed_form(p, a, b, 0.25), e3 = filtering_error_closed_form(p, a, b, 0.75);
  EXPECT_NEAR(m.max_error, std::max(e1, e3), 1e-9 * std::max(e1, e3));
  EXPECT_NEAR(m.rms_error, std::sqrt((e1 * e1 + e3 * e3) / 2.0), 1e-9 * std::max(e1, e3));
  EXPECT_NEAR(m.mean_interval, b - a, 1e-12);
  EXPECT_GT(m.mean_signed_error, 0.0) << "Lwhite > 1: the tone-mapped filter darkens";
}

TEST(BanterleFiltering, BadInputIsAnErrorNamingTheProblem) {
  const ReinhardParameters p = parameters(0.18, 12.0, 0.5);
  const auto message = [](auto&& call) -> std::string {
    try {
      call();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message([&] { filtering_error_curve(p, 0.6, 1.5, 11); }).find("[0.600000, 1.500000]"), std::string::npos);
  EXPECT_NE(message([&] { filtering_error_curve(p, 0.0, 1.0, 1); }).find("at least 2 samples"), std::string::npos);
  EXPECT_NE(message([&] { filtering_error_curve(parameters(0.18, NAN, 0.5), 0.0, 1.0, 11); }).find("l_white nan"),
            std::string::npos);
  EXPECT_NE(message([&] { measure_bilinear_filtering_error(Image(1, 7), p); }).find("2x2"), std::string::npos);
}

}  // namespace
}  // namespace blocklab
