// mpsnr_auto (SPECS.md 1b, HDR_Toolbox automatic stops, rounded T, per-stop MSEs averaged): hand-computed cases.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "metrics/metric.h"

namespace blocklab {
namespace {

constexpr double kTight = 1e-9;

Image solid(int w, int h, float v) {
  Image image(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* t = image.texel(x, y);
      t[0] = t[1] = t[2] = v;
    }
  return image;
}

const Metric& mpsnr_auto() { return find_metric("mpsnr_auto"); }

TEST(MpsnrAutoMetric, SingleFstopRangeIsWidenedAndOnlyMidGreyStopsAreKept) {
  // Luminances 0.25 and 0.2 both round to f-stop -2 -> candidates 2..2, widened to 1..3. At stop 1 the reference
  // code is round(255 * 0.5^(1/2.2)) = 186 (mean 0.73, kept); stops 2 and 3 saturate at 255 (mean 1, dropped).
  // Test code at stop 1: round(255 * 0.4^(1/2.2)) = round(168.1) = 168. MSE = 18^2.
  const MetricResult r = mpsnr_auto().compute(solid(1, 1, 0.25f), solid(1, 1, 0.2f), {});
  EXPECT_NEAR(r.value, 10.0 * std::log10(255.0 * 255.0 / 324.0), kTight);
  EXPECT_EQ(r.details.at("candidate_start"), "1");
  EXPECT_EQ(r.details.at("candidate_stop"), "3");
  EXPECT_EQ(r.details.at("stops"), "1");
}

TEST(MpsnrAutoMetric, AveragesThePerStopMsesInsteadOfSummingThem) {
  // Pixels of luminance 1 and 1/16 (reference) vs 1 and 1/8 (test): candidates 0..4, stops 0..3 kept.
  // Per-stop codes of the dark pixel: ref 72, 99, 136, 186; test 99, 136, 186, 255 -> MSE_c = d^2 * 3 / 6:
  // 364.5, 684.5, 1250, 2380.5; mean 1169.875 (the toolbox would sum them to 4679.5).
  Image reference = solid(2, 1, 1.0f);
  Image test = reference;
  for (int c = 0; c < 3; ++c) {
    reference.texel(1, 0)[c] = 1.0f / 16.0f;
    test.texel(1, 0)[c] = 1.0f / 8.0f;
  }
  const MetricResult r = mpsnr_auto().compute(reference, test, {});
  EXPECT_EQ(r.details.at("candidate_start"), "0");
  EXPECT_EQ(r.details.at("candidate_stop"), "4");
  EXPECT_EQ(r.details.at("stops"), "0,1,2,3");
  EXPECT_NEAR(r.value, 10.0 * std::log10(255.0 * 255.0 / 1169.875), kTight);
  EXPECT_NE(r.details.at("averaging").find("mean"), std::string::npos);
}

TEST(MpsnrAutoMetric, AllBlackImagesGiveNanWithAReason) {
  const MetricResult r = mpsnr_auto().compute(solid(2, 2, 0.0f), solid(2, 2, -1.0f), {});
  EXPECT_TRUE(std::isnan(r.value));
  EXPECT_NE(r.details.at("reason").find("positive luminance"), std::string::npos);
}

TEST(MpsnrAutoMetric, ZeroLuminancePixelsDoNotSetTheRange) {
  // The black pixel is skipped by the L > 0 rule; the range comes from the 0.25 pixels alone (same as above).
  Image reference = solid(2, 1, 0.25f), test = solid(2, 1, 0.25f);
  for (int c = 0; c < 3; ++c) reference.texel(0, 0)[c] = test.texel(0, 0)[c] = 0.0f;
  const MetricResult r = mpsnr_auto().compute(reference, test, {});
  EXPECT_EQ(r.details.at("candidate_start"), "1");
  EXPECT_EQ(r.details.at("candidate_stop"), "3");
  EXPECT_EQ(r.value, std::numeric_limits<double>::infinity());
}

TEST(MpsnrAutoMetric, UsesRec709LuminanceWeights) {
  // Pure blue 1.0: L = 0.0722, log2 = -3.79 -> f-stop -4, widened candidates 3..5.
  Image image(1, 1, 3);
  image.texel(0, 0)[2] = 1.0f;
  const MetricResult r = mpsnr_auto().compute(image, image, {});
  EXPECT_EQ(r.details.at("candidate_start"), "3");
  EXPECT_EQ(r.details.at("candidate_stop"), "5");
  EXPECT_NE(r.details.at("luminance_weights").find("0.2126"), std::string::npos);
}

TEST(MpsnrAutoMetric, ErrorMapIsZeroWhereImagesAgree) {
  Image reference = solid(2, 1, 1.0f), test = reference;
  for (int c = 0; c < 3; ++c) {
    reference.texel(1, 0)[c] = 1.0f / 16.0f;
    test.texel(1, 0)[c] = 1.0f / 8.0f;
  }
  const Image map = mpsnr_auto().error_map(reference, test, {});
  EXPECT_EQ(map.texel(0, 0)[0], 0.0f);
  // Mean over kept stops of 3 d^2: (729 + 1369 + 2500 + 4761) * 3 / 4.
  EXPECT_FLOAT_EQ(map.texel(1, 0)[0], static_cast<float>((729.0 + 1369.0 + 2500.0 + 4761.0) * 3.0 / 4.0));
}

TEST(MpsnrAutoMetric, TakesNoOptions) {
  try {
    mpsnr_auto().compute(Image(1, 1), Image(1, 1), {{"start", "0"}});
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "mpsnr_auto: unknown option 'start' (this metric takes no options)");
  }
}

}  // namespace
}  // namespace blocklab
