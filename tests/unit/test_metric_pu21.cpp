// PU21 encoding (SPECS.md 1c test vectors) and the pu21_psnr metric.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "metrics/metric.h"
#include "metrics/pu21.h"

namespace blocklab {
namespace {

constexpr double kVectorTolerance = 5e-5;   // the SPECS vectors are given to 4 decimals

Image solid(int w, int h, float v) {
  Image image(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* t = image.texel(x, y);
      t[0] = t[1] = t[2] = v;
    }
  return image;
}

const Metric& pu21_psnr() { return find_metric("pu21_psnr"); }

TEST(Pu21Encoding, MatchesTheSpecTestVectors) {
  EXPECT_NEAR(pu21_encode(0.005), 0.0, 1e-6);
  EXPECT_NEAR(pu21_encode(1.0), 36.5439, kVectorTolerance);
  EXPECT_NEAR(pu21_encode(100.0), 256.3839, kVectorTolerance);
  EXPECT_NEAR(pu21_encode(10000.0), 595.3939, kVectorTolerance);
}

TEST(Pu21Encoding, ClampsLuminanceToTheEncoderRange) {
  EXPECT_EQ(pu21_encode(0.001), pu21_encode(0.005));
  EXPECT_EQ(pu21_encode(-7.0), pu21_encode(0.005));
  EXPECT_EQ(pu21_encode(std::numeric_limits<double>::quiet_NaN()), pu21_encode(0.005));
  EXPECT_EQ(pu21_encode(1e6), pu21_encode(10000.0));
  EXPECT_EQ(pu21_encode(std::numeric_limits<double>::infinity()), pu21_encode(10000.0));
}

TEST(Pu21Encoding, IsStrictlyIncreasingInsideTheRange) {
  double previous = pu21_encode(0.005);
  for (double y = 0.01; y <= 10000.0; y *= 1.5) {
    const double v = pu21_encode(y);
    EXPECT_GT(v, previous) << "at " << y;
    previous = v;
  }
}

TEST(Pu21Encoding, EveryParameterSetIsPublished) {
  EXPECT_EQ(pu21_parameters(Pu21Type::banding_glare)[6], 596.3148142);
  EXPECT_EQ(pu21_parameters(Pu21Type::banding)[0], 1.070275272);
  EXPECT_EQ(pu21_parameters(Pu21Type::peaks)[6], 384.9217577);
  EXPECT_EQ(pu21_parameters(Pu21Type::peaks_glare)[0], 816.885024);
  EXPECT_EQ(to_string(Pu21Type::peaks_glare), "peaks_glare");
}

TEST(Pu21PsnrMetric, HundredNitsAgainstOneNitMatchesTheVectors) {
  // Default scale 100 cd/m^2 per unit: 1.0 -> 100 nits, 0.01 -> 1 nit in every channel.
  const double d = pu21_encode(100.0) - pu21_encode(1.0);
  const MetricResult r = pu21_psnr().compute(solid(1, 1, 1.0f), solid(1, 1, 0.01f), {});
  EXPECT_NEAR(r.value, 20.0 * std::log10(256.0) - 10.0 * std::log10(d * d), 1e-6);
  EXPECT_NEAR(r.value, 20.0 * std::log10(256.0 / (256.3839 - 36.5439)), 1e-5);
  EXPECT_EQ(r.details.at("nits_per_unit"), "100");
  EXPECT_EQ(r.details.at("pu21_type"), "banding_glare");
}

TEST(Pu21PsnrMetric, NitsPerUnitOptionRescales) {
  // 4 cd/m^2 per unit: 25 -> 100 nits and 0.25 -> 1 nit, both exact in float.
  const MetricResult r = pu21_psnr().compute(solid(1, 1, 25.0f), solid(1, 1, 0.25f), {{"nits_per_unit", "4"}});
  const double d = pu21_encode(100.0) - pu21_encode(1.0);
  EXPECT_NEAR(r.value, 20.0 * std::log10(256.0) - 10.0 * std::log10(d * d), 1e-12);
  EXPECT_EQ(r.details.at("nits_per_unit"), "4");
}

TEST(Pu21PsnrMetric, IdenticalImagesGiveInfinity) {
  const Image image = solid(2, 2, 3.0f);
  EXPECT_EQ(pu21_psnr().compute(image, image, {}).value, std::numeric_limits<double>::infinity());
}

TEST(Pu21PsnrMetric, ErrorMapIsPerPixelMeanSquaredPuDifference) {
  Image reference = solid(2, 1, 1.0f), test = reference;
  test.texel(1, 0)[0] = 0.01f;
  const double d = pu21_encode(100.0) - pu21_encode(static_cast<double>(0.01f) * 100.0);
  const Image map = pu21_psnr().error_map(reference, test, {});
  EXPECT_EQ(map.texel(0, 0)[0], 0.0f);
  EXPECT_FLOAT_EQ(map.texel(1, 0)[0], static_cast<float>(d * d / 3.0));
}

TEST(Pu21PsnrMetric, RejectsNonPositiveScaleAndUnknownOptions) {
  const Image image = solid(1, 1, 1.0f);
  for (const char* bad : {"0", "-100", "lots"})
    EXPECT_THROW(pu21_psnr().compute(image, image, {{"nits_per_unit", bad}}), Error) << bad;
  try {
    pu21_psnr().compute(image, image, {{"nits", "100"}});
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "pu21_psnr: unknown option 'nits' (valid options: nits_per_unit)");
  }
}

}  // namespace
}  // namespace blocklab
