// mpsnr (SPECS.md 1b, fixed stops, astcenc normalisation): hand-computed values, options, quantised variant.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "metrics/metric.h"

namespace blocklab {
namespace {

constexpr double kTight = 1e-9;
const double kInvGamma = 1.0 / 2.2;

Image solid(int w, int h, float r, float g, float b) {
  Image image(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* t = image.texel(x, y);
      t[0] = r; t[1] = g; t[2] = b;
    }
  return image;
}

const Metric& mpsnr() { return find_metric("mpsnr"); }
const MetricOptions kStopZeroOnly = {{"start", "0"}, {"stop", "0"}};

TEST(MpsnrMetric, WhiteAgainstBlackAtStopZeroIsZeroDecibels) {
  // T = 255 vs 0 in all three channels: MSE = 3 * 255^2 -> 10 log10(1) = 0.
  EXPECT_NEAR(mpsnr().compute(solid(1, 1, 1, 1, 1), solid(1, 1, 0, 0, 0), kStopZeroOnly).value, 0.0, kTight);
}

TEST(MpsnrMetric, OneChannelAtHalfIntensityMatchesTheFormula) {
  const double d = 255.0 * (1.0 - std::pow(0.5, kInvGamma));
  const double expected = 10.0 * std::log10(3.0 * 255.0 * 255.0 / (d * d));
  EXPECT_NEAR(mpsnr().compute(solid(1, 1, 1, 1, 1), solid(1, 1, 0.5f, 1, 1), kStopZeroOnly).value, expected, kTight);
}

TEST(MpsnrMetric, AveragesTheSquaredErrorOverStopsAndPixels) {
  // Stops -1 and 0, two pixels, only pixel 1's red differs (0.25 vs 0.125).
  Image reference = solid(2, 1, 0.25f, 0.25f, 0.25f);
  Image test = reference;
  test.texel(1, 0)[0] = 0.125f;
  double sum = 0.0;
  for (int c = -1; c <= 0; ++c) {
    const double d = 255.0 * (std::pow(std::ldexp(0.25, c), kInvGamma) - std::pow(std::ldexp(0.125, c), kInvGamma));
    sum += d * d;
  }
  const double mse = sum / (2.0 * 2.0);
  const MetricResult r = mpsnr().compute(reference, test, {{"start", "-1"}, {"stop", "0"}});
  EXPECT_NEAR(r.value, 10.0 * std::log10(3.0 * 255.0 * 255.0 / mse), kTight);
  EXPECT_EQ(r.details.at("stop_count"), "2");
}

TEST(MpsnrMetric, SaturatedCodesAreClampedTo255) {
  // 4 and 8 are both above 1 at stop 0: both map to 255, no error.
  EXPECT_EQ(mpsnr().compute(solid(1, 1, 4, 4, 4), solid(1, 1, 8, 8, 8), kStopZeroOnly).value,
            std::numeric_limits<double>::infinity());
}

TEST(MpsnrMetric, NegativeAndNanValuesCountAsZero) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(mpsnr().compute(solid(1, 1, -5, nan, 0), solid(1, 1, 0, 0, -1), {}).value,
            std::numeric_limits<double>::infinity());
}

TEST(MpsnrMetric, IdenticalImagesGiveInfinity) {
  const Image image = solid(4, 3, 0.1f, 2.0f, 300.0f);
  EXPECT_EQ(mpsnr().compute(image, image, {}).value, std::numeric_limits<double>::infinity());
}

TEST(MpsnrMetric, DefaultsAreFixedStopsMinusTenToTenUnrounded) {
  const MetricResult r = mpsnr().compute(solid(1, 1, 1, 1, 1), solid(1, 1, 0.5f, 1, 1), {});
  EXPECT_EQ(r.details.at("variant"), "fixed");
  EXPECT_EQ(r.details.at("start"), "-10");
  EXPECT_EQ(r.details.at("stop"), "10");
  EXPECT_EQ(r.details.at("gamma"), "2.2");
  EXPECT_EQ(r.details.at("quantised"), "false");
  double sum = 0.0;
  for (int c = -10; c <= 10; ++c) {
    const double a = std::min(255.0, 255.0 * std::pow(std::ldexp(1.0, c), kInvGamma));
    const double b = std::min(255.0, 255.0 * std::pow(std::ldexp(0.5, c), kInvGamma));
    sum += (a - b) * (a - b);
  }
  EXPECT_NEAR(r.value, 10.0 * std::log10(3.0 * 255.0 * 255.0 / (sum / 21.0)), kTight);
}

TEST(MpsnrMetric, QuantiseOptionRoundsTheCodes) {
  // Red codes 100.4 vs 100.6 at stop 0: unrounded difference 0.2, rounded 100 vs 101.
  const float a = static_cast<float>(std::pow(100.4 / 255.0, 2.2));
  const float b = static_cast<float>(std::pow(100.6 / 255.0, 2.2));
  MetricOptions options = kStopZeroOnly;
  options["quantise"] = "true";
  const MetricResult rounded = mpsnr().compute(solid(1, 1, a, 0, 0), solid(1, 1, b, 0, 0), options);
  EXPECT_NEAR(rounded.value, 10.0 * std::log10(3.0 * 255.0 * 255.0 / 1.0), kTight);
  EXPECT_EQ(rounded.details.at("quantised"), "true");
  const MetricResult unrounded = mpsnr().compute(solid(1, 1, a, 0, 0), solid(1, 1, b, 0, 0), kStopZeroOnly);
  EXPECT_NEAR(unrounded.value, 10.0 * std::log10(3.0 * 255.0 * 255.0 / (0.2 * 0.2)), 1e-3);
}

TEST(MpsnrMetric, ErrorMapMeanIsTheMse) {
  Image reference = solid(3, 2, 0.5f, 0.1f, 2.0f);
  Image test = reference;
  test.texel(2, 1)[0] = 0.6f;
  test.texel(0, 0)[2] = 1.0f;
  const MetricResult r = mpsnr().compute(reference, test, {});
  const Image map = mpsnr().error_map(reference, test, {});
  double mean = 0.0;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) mean += map.texel(x, y)[0];
  mean /= 6.0;
  EXPECT_NEAR(mean, std::stod(r.details.at("mse")), 1e-5 * mean);
  EXPECT_EQ(map.texel(1, 0)[0], 0.0f);
}

TEST(MpsnrMetric, RejectsBadStopOptions) {
  const Image image = solid(1, 1, 1, 1, 1);
  const MetricOptions bad[] = {{{"start", "3"}, {"stop", "2"}}, {{"start", "x"}}, {{"stop", "1.5"}},
                               {{"start", "-5000"}}, {{"quantise", "maybe"}}};
  for (const MetricOptions& options : bad) {
    try {
      mpsnr().compute(image, image, options);
      FAIL() << "accepted " << options.begin()->first << "=" << options.begin()->second;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("mpsnr: option '", 0), 0u) << e.what();
    }
  }
  EXPECT_EQ(mpsnr().compute(image, image, {{"start", "+2"}, {"stop", "+2"}}).details.at("start"), "2");
}

TEST(MpsnrMetric, UnknownOptionListsTheValidOnes) {
  try {
    mpsnr().compute(Image(1, 1), Image(1, 1), {{"gamma", "2.4"}});
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "mpsnr: unknown option 'gamma' (valid options: start, stop, quantise)");
  }
}

TEST(MpsnrMetric, SizeMismatchNamesBothSizes) {
  EXPECT_THROW(mpsnr().compute(Image(10, 10), Image(10, 12), {}), Error);
}

}  // namespace
}  // namespace blocklab
