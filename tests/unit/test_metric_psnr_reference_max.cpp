// psnr with peak=reference_max (metrics/psnr.cpp): the HDR PSNR of Wang et al. 2007 Table 2 ("PSNR via the metric in
// [Li et al. 2005] across all color channels"): linear values, no clamp, peak = largest reference value of the chosen
// channels, 10 log10(peak^2 / MSE).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "metrics/metric.h"

namespace blocklab {
namespace {

const Metric& psnr() { return find_metric("psnr"); }
const MetricOptions kReferenceMax = {{"peak", "reference_max"}};

TEST(PsnrReferenceMax, PeakIsTheLargestReferenceChannelValueAndValuesAreNotClamped) {
  // 2x1 HDR reference with peak 200 (a green value); the test is 2 off on one of 6 samples above 1.
  Image reference(2, 1, 3), test(2, 1, 3);
  const float values[6] = {3.0f, 200.0f, 0.5f, 40.0f, 7.0f, 0.25f};
  for (int i = 0; i < 6; ++i) reference.pixels[(i / 3) * 4 + i % 3] = test.pixels[(i / 3) * 4 + i % 3] = values[i];
  test.texel(1, 0)[0] = 42.0f;
  const MetricResult r = psnr().compute(reference, test, kReferenceMax);
  EXPECT_NEAR(r.value, 10.0 * std::log10(200.0 * 200.0 / (4.0 / 6.0)), 1e-9);
  EXPECT_EQ(r.details.at("peak"), "200");
  // The code-value variant clamps both 40 and 42 to 1: no error at all.
  EXPECT_EQ(psnr().compute(reference, test, {}).value, std::numeric_limits<double>::infinity());
  // Scaling both images scales the peak and the error alike: the same dB.
  Image reference_scaled = reference, test_scaled = test;
  for (float& v : reference_scaled.pixels) v *= 8.0f;
  for (float& v : test_scaled.pixels) v *= 8.0f;
  EXPECT_NEAR(psnr().compute(reference_scaled, test_scaled, kReferenceMax).value, r.value, 1e-9);
}

TEST(PsnrReferenceMax, ChannelsPickThePeakAndTheSamplesAndAlphaIsIgnoredByDefault) {
  Image reference(1, 1, 4), test(1, 1, 4);
  float* t = reference.texel(0, 0);
  t[0] = 10.0f; t[1] = 2.0f; t[2] = 1.0f; t[3] = 1000.0f;
  test = reference;
  test.texel(0, 0)[1] = 3.0f;
  EXPECT_NEAR(psnr().compute(reference, test, kReferenceMax).value, 10.0 * std::log10(100.0 / (1.0 / 3.0)), 1e-9);
  const MetricOptions green = {{"peak", "reference_max"}, {"channels", "g"}};
  EXPECT_NEAR(psnr().compute(reference, test, green).value, 10.0 * std::log10(4.0 / 1.0), 1e-9);
  EXPECT_FLOAT_EQ(psnr().error_map(reference, test, kReferenceMax).texel(0, 0)[0], 1.0f / 3.0f);
  EXPECT_EQ(psnr().compute(reference, reference, kReferenceMax).value, std::numeric_limits<double>::infinity());
}

TEST(PsnrReferenceMax, AnUnknownPeakIsAnErrorNamingTheOption) {
  const Image image(2, 2, 3);
  try {
    psnr().compute(image, image, {{"peak", "255"}});
    FAIL() << "accepted peak=255";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("psnr: option 'peak'"), std::string::npos) << error.what();
  }
  EXPECT_EQ(psnr().compute(image, image, {{"peak", "1"}}).value, std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace blocklab
