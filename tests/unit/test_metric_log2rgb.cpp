// log2rgb (SPECS.md 1a): hand-computed values on tiny images, the zero rule, the floor option, the error map.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "metrics/metric.h"
#include "metrics/zero_rule.h"

namespace blocklab {
namespace {

constexpr double kTight = 1e-12;

Image solid(int w, int h, float r, float g, float b) {
  Image image(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* t = image.texel(x, y);
      t[0] = r; t[1] = g; t[2] = b;
    }
  return image;
}

const Metric& log2rgb() { return find_metric("log2rgb"); }

TEST(Log2RgbMetric, OneStopDifferenceInEveryChannelGivesSqrtThree) {
  const MetricResult r = log2rgb().compute(solid(1, 1, 1.0f, 2.0f, 4.0f), solid(1, 1, 2.0f, 4.0f, 8.0f), {});
  EXPECT_NEAR(r.value, std::sqrt(3.0), kTight);
}

TEST(Log2RgbMetric, DividesByThePixelCountNotTheSampleCount) {
  // Two pixels, one channel of one pixel is one stop off: sqrt(1 / 2 pixels), not sqrt(1 / 6 samples).
  Image reference = solid(2, 1, 0.5f, 0.5f, 0.5f);
  Image test = reference;
  test.texel(1, 0)[1] = 1.0f;
  EXPECT_NEAR(log2rgb().compute(reference, test, {}).value, std::sqrt(0.5), kTight);
}

TEST(Log2RgbMetric, IdenticalImagesGiveZero) {
  const Image image = solid(3, 2, 0.25f, 7.0f, 1000.0f);
  EXPECT_EQ(log2rgb().compute(image, image, {}).value, 0.0);
}

TEST(Log2RgbMetric, ZeroIsRaisedToTheSmallestHalfAndCounted) {
  // Red: 0 vs 1 -> log2(2^-24) - log2(1) = -24; green, blue identical.
  const MetricResult r = log2rgb().compute(solid(1, 1, 0.0f, 1.0f, 1.0f), solid(1, 1, 1.0f, 1.0f, 1.0f), {});
  EXPECT_NEAR(r.value, 24.0, kTight);
  EXPECT_EQ(r.details.at("clamped_reference_samples"), "1");
  EXPECT_EQ(r.details.at("clamped_test_samples"), "0");
  EXPECT_EQ(r.details.at("floor"), "5.960464477539063e-08");
  EXPECT_NE(r.details.at("zero_rule").find("max(x, floor)"), std::string::npos);
}

TEST(Log2RgbMetric, NegativeNanAndTinyValuesAllMapToTheFloor) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const MetricResult r = log2rgb().compute(solid(1, 1, -3.0f, nan, 1e-9f),
                                           solid(1, 1, 0.0f, static_cast<float>(kLogDomainDefaultFloor), -0.0f), {});
  EXPECT_EQ(r.value, 0.0);
  EXPECT_EQ(r.details.at("clamped_reference_samples"), "3");
  EXPECT_EQ(r.details.at("clamped_test_samples"), "2");   // exactly the floor is not "clamped"
}

TEST(Log2RgbMetric, FloorOptionOverridesTheRuleAndIsReported) {
  const MetricResult r =
      log2rgb().compute(solid(1, 1, 0.5f, 0.25f, 2.0f), solid(1, 1, 0.25f, 0.5f, 4.0f), {{"floor", "1"}});
  EXPECT_NEAR(r.value, 1.0, kTight);   // red and green both raised to 1; blue one stop off
  EXPECT_EQ(r.details.at("floor"), "1");
  EXPECT_EQ(r.details.at("clamped_reference_samples"), "2");
}

TEST(Log2RgbMetric, RejectsANonPositiveOrUnparsableFloor) {
  const Image image = solid(1, 1, 1, 1, 1);
  for (const char* bad : {"0", "-1", "abc", "1e-3x", "nan", ""}) {
    try {
      log2rgb().compute(image, image, {{"floor", bad}});
      FAIL() << "floor=" << bad << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("log2rgb: option 'floor'"), std::string::npos) << e.what();
    }
  }
}

TEST(Log2RgbMetric, IgnoresAlpha) {
  Image reference(1, 1, 4), test(1, 1, 4);
  reference.texel(0, 0)[3] = 0.0f;
  test.texel(0, 0)[3] = 1.0f;
  EXPECT_EQ(log2rgb().compute(reference, test, {}).value, 0.0);
}

TEST(Log2RgbMetric, ErrorMapHoldsEachPixelsDistanceAndItsRmsIsTheMetric) {
  Image reference = solid(2, 1, 1.0f, 1.0f, 1.0f);
  Image test = reference;
  test.texel(0, 0)[0] = 2.0f;                       // pixel 0: one stop in red -> 1
  test.texel(1, 0)[1] = 4.0f;                       // pixel 1: two stops in green, one in blue -> sqrt(5)
  test.texel(1, 0)[2] = 0.5f;
  const Image map = log2rgb().error_map(reference, test, {});
  ASSERT_EQ(map.width, 2);
  ASSERT_EQ(map.height, 1);
  EXPECT_FLOAT_EQ(map.texel(0, 0)[0], 1.0f);
  EXPECT_FLOAT_EQ(map.texel(1, 0)[0], static_cast<float>(std::sqrt(5.0)));
  EXPECT_EQ(map.texel(1, 0)[0], map.texel(1, 0)[1]);
  EXPECT_EQ(map.texel(1, 0)[0], map.texel(1, 0)[2]);
  EXPECT_NEAR(log2rgb().compute(reference, test, {}).value, std::sqrt((1.0 + 5.0) / 2.0), kTight);
}

TEST(Log2RgbMetric, SizeMismatchNamesBothSizes) {
  try {
    log2rgb().compute(Image(10, 10), Image(12, 10), {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "log2rgb: size mismatch 10x10 vs 12x10");
  }
}

TEST(Log2RgbMetric, UnknownOptionListsTheValidOnes) {
  try {
    log2rgb().compute(Image(1, 1), Image(1, 1), {{"flor", "1"}});
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "log2rgb: unknown option 'flor' (valid options: zero_rule, floor)");
  }
}

TEST(Log2RgbMetric, SkipRuleLeavesOutPairsWithAZeroAndNormalisesByCountedValuesOverThree) {
  // Pixel 0: red 0 in the test (left out), green one stop off, blue equal. Pixel 1: every channel one stop off.
  // Counted values: 2 + 3 = 5, so the "pixel count" is 5/3 and the sum is 1 + 3 = 4: sqrt(4 / (5/3)) = sqrt(2.4).
  Image reference = solid(2, 1, 1.0f, 1.0f, 1.0f);
  Image test = solid(2, 1, 2.0f, 2.0f, 2.0f);
  test.texel(0, 0)[0] = 0.0f;
  test.texel(0, 0)[2] = 1.0f;
  const MetricResult r = log2rgb().compute(reference, test, {{"zero_rule", "skip"}});
  EXPECT_NEAR(r.value, std::sqrt(2.4), kTight);
  EXPECT_EQ(r.details.at("skipped_samples"), "1");
  EXPECT_NE(r.details.at("zero_rule").find("piccante"), std::string::npos);
  // The default floor rule charges the same zero (log2(2^-24) - log2(1))^2 = 576.
  EXPECT_NEAR(log2rgb().compute(reference, test, {}).value, std::sqrt((576.0 + 1.0 + 3.0) / 2.0), kTight);
}

TEST(Log2RgbMetric, SkipRuleEqualsTheFloorRuleOnImagesWithoutZeros) {
  Image reference = solid(3, 2, 0.25f, 7.0f, 1000.0f);
  Image test = solid(3, 2, 0.3f, 6.0f, 900.0f);
  test.texel(2, 1)[1] = 0.001f;
  EXPECT_NEAR(log2rgb().compute(reference, test, {{"zero_rule", "skip"}}).value,
              log2rgb().compute(reference, test, {}).value, kTight);
}

TEST(Log2RgbMetric, SkipRuleLeavesOutNegativeAndNanOnEitherSideAndIsNanWhenNothingIsCounted) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const MetricResult r = log2rgb().compute(solid(1, 1, -1.0f, nan, 0.0f), solid(1, 1, 1.0f, 1.0f, 1.0f),
                                           {{"zero_rule", "skip"}});
  EXPECT_TRUE(std::isnan(r.value));
  EXPECT_EQ(r.details.at("skipped_samples"), "3");
}

TEST(Log2RgbMetric, UnknownZeroRuleAndAFloorUnderSkipAreRejected) {
  const Image image = solid(1, 1, 1, 1, 1);
  try {
    log2rgb().compute(image, image, {{"zero_rule", "clip"}});
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "log2rgb: option 'zero_rule': unknown zero rule 'clip'; valid zero rules: floor, skip");
  }
  try {
    log2rgb().compute(image, image, {{"zero_rule", "skip"}, {"floor", "1e-3"}});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("applies to zero_rule=floor only"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace blocklab
