// psnr and psnr_luma (SPECS.md 1d): LDR PSNR on [0,1] code values, clamping, BT.601 luma.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "metrics/metric.h"

namespace blocklab {
namespace {

constexpr double kTight = 1e-9;

Image solid(int w, int h, float r, float g, float b) {
  Image image(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* t = image.texel(x, y);
      t[0] = r; t[1] = g; t[2] = b;
    }
  return image;
}

const Metric& psnr() { return find_metric("psnr"); }
const Metric& psnr_luma() { return find_metric("psnr_luma"); }

TEST(PsnrMetric, OneCodeValueOffEverywhereIs48Decibels) {
  // Every sample one 8-bit step apart: 10 log10(255^2 / 1).
  const MetricResult r = psnr().compute(solid(2, 2, 10 / 255.f, 20 / 255.f, 30 / 255.f),
                                        solid(2, 2, 11 / 255.f, 21 / 255.f, 29 / 255.f), {});
  EXPECT_NEAR(r.value, 20.0 * std::log10(255.0), 1e-5);
}

TEST(PsnrMetric, AveragesOverAllRgbSamples) {
  // One sample of 2 pixels x 3 channels is 0.1 off: MSE = 0.01 / 6.
  Image reference = solid(2, 1, 0.5f, 0.5f, 0.5f), test = reference;
  test.texel(1, 0)[2] = 0.5f + 0.1f;
  const double d = static_cast<double>(0.5f + 0.1f) - 0.5;
  EXPECT_NEAR(psnr().compute(reference, test, {}).value, 10.0 * std::log10(6.0 / (d * d)), kTight);
}

TEST(PsnrMetric, WhiteAgainstBlackIsZeroDecibels) {
  EXPECT_NEAR(psnr().compute(solid(1, 1, 1, 1, 1), solid(1, 1, 0, 0, 0), {}).value, 0.0, kTight);
}

TEST(PsnrMetric, ClampsToTheUnitRangeAndCountsIt) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const MetricResult r = psnr().compute(solid(1, 1, 1.5f, -0.5f, nan), solid(1, 1, 1.0f, 0.0f, 0.0f), {});
  EXPECT_EQ(r.value, std::numeric_limits<double>::infinity());
  EXPECT_EQ(r.details.at("clamped_reference_samples"), "3");
  EXPECT_EQ(r.details.at("clamped_test_samples"), "0");
}

TEST(PsnrMetric, IdenticalImagesGiveInfinityAndAlphaIsIgnored) {
  Image a(3, 3, 4), b(3, 3, 4);
  a.texel(1, 1)[3] = 0.0f;
  EXPECT_EQ(psnr().compute(a, b, {}).value, std::numeric_limits<double>::infinity());
}

TEST(PsnrMetric, ErrorMapIsPerPixelMeanSquaredError) {
  Image reference = solid(2, 1, 0.0f, 0.0f, 0.0f), test = reference;
  test.texel(0, 0)[0] = 0.75f;
  const Image map = psnr().error_map(reference, test, {});
  EXPECT_FLOAT_EQ(map.texel(0, 0)[1], static_cast<float>(0.75 * 0.75 / 3.0));
  EXPECT_EQ(map.texel(1, 0)[0], 0.0f);
}

TEST(PsnrMetric, ChannelsOptionAveragesOnlyTheNamedChannels) {
  Image reference(2, 1, 4), test(2, 1, 4);
  test.texel(0, 0)[0] = 0.2f;   // R differs
  test.texel(1, 0)[3] = 0.5f;   // alpha differs (reference alpha is 1)
  const double r_error = static_cast<double>(0.2f) * 0.2f;
  // "r": one channel, two samples.
  EXPECT_NEAR(psnr().compute(reference, test, {{"channels", "r"}}).value, 10.0 * std::log10(2.0 / r_error), kTight);
  // "a": the alpha PSNR (BC3/BC7), blind to the R difference.
  EXPECT_NEAR(psnr().compute(reference, test, {{"channels", "a"}}).value, 10.0 * std::log10(2.0 / 0.25), kTight);
  // "rgba": eight samples.
  EXPECT_NEAR(psnr().compute(reference, test, {{"channels", "rgba"}}).value,
              10.0 * std::log10(8.0 / (r_error + 0.25)), kTight);
  EXPECT_EQ(psnr().compute(reference, test, {{"channels", "a"}}).details.at("channels"), "A");
  // The error map averages the same channels.
  EXPECT_FLOAT_EQ(psnr().error_map(reference, test, {{"channels", "r"}}).texel(0, 0)[0], static_cast<float>(r_error));
}

TEST(PsnrMetric, BadChannelsOptionIsRejectedWithTheOptionNamed) {
  const Image image(1, 1, 3);
  for (const char* bad : {"x", "rr", ""}) {
    try {
      psnr().compute(image, image, {{"channels", bad}});
      ADD_FAILURE() << "accepted channels='" << bad << "'";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("psnr: option 'channels'"), std::string::npos) << error.what();
    }
  }
}

TEST(PsnrLumaMetric, UsesBt601LumaWeights) {
  // Red 1 vs 0: luma difference 0.299 -> -20 log10(0.299).
  const MetricResult r = psnr_luma().compute(solid(1, 1, 1, 0, 0), solid(1, 1, 0, 0, 0), {});
  EXPECT_NEAR(r.value, -20.0 * std::log10(0.299), kTight);
  EXPECT_NE(r.details.at("luma").find("0.299"), std::string::npos);
}

TEST(PsnrLumaMetric, IgnoresChromaOnlyDifferences) {
  // 0.587 red and 0.299 green have the same luma (0.587 * 0.299 = 0.299 * 0.587).
  const MetricResult r = psnr_luma().compute(solid(1, 1, 0.5f, 0, 0), solid(1, 1, 0, 0.5f * 0.299f / 0.587f, 0), {});
  EXPECT_GT(r.value, 130.0);
}

TEST(PsnrLumaMetric, ClampsBeforeTheLuma) {
  EXPECT_EQ(psnr_luma().compute(solid(1, 1, 2, 2, 2), solid(1, 1, 1, 1, 1), {}).value,
            std::numeric_limits<double>::infinity());
}

TEST(PsnrLumaMetric, ErrorMapIsSquaredLumaDifference) {
  const Image map = psnr_luma().error_map(solid(1, 1, 0, 1, 0), solid(1, 1, 0, 0, 0), {});
  EXPECT_FLOAT_EQ(map.texel(0, 0)[2], static_cast<float>(0.587 * 0.587));
}

TEST(PsnrMetric, BothRejectOptionsAndMismatchedSizes) {
  for (const Metric* m : {&psnr(), &psnr_luma()}) {
    EXPECT_THROW(m->compute(Image(1, 1), Image(1, 1), {{"gain", "1"}}), Error);
    EXPECT_THROW(m->compute(Image(2, 1), Image(1, 2), {}), Error);
  }
}

}  // namespace
}  // namespace blocklab
