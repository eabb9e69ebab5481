// The input policy (core/input_policy.h): error / clamp / zero on NaN, +Inf, -Inf and negative values, the counts
// it reports, which channels it examines, the error message, and the policy names.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/input_policy.h"

namespace blocklab {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// 3 x 2 RGBA image: (0,0) clean; (1,0) R = NaN, G = -Inf; (2,0) B = +Inf; (0,1) G = -0.25, A = NaN;
// (1,1) clean with large finite 1e6 and -0.0; (2,1) R = +Inf, B = -3.
Image dirty_rgba() {
  Image image(3, 2, 4);
  for (float& v : image.pixels) v = 0.5f;
  image.texel(1, 0)[0] = kNaN;
  image.texel(1, 0)[1] = -kInf;
  image.texel(2, 0)[2] = kInf;
  image.texel(0, 1)[1] = -0.25f;
  image.texel(0, 1)[3] = kNaN;
  image.texel(1, 1)[0] = 1e6f;
  image.texel(1, 1)[1] = -0.0f;
  image.texel(2, 1)[0] = kInf;
  image.texel(2, 1)[2] = -3.0f;
  return image;
}

void expect_counts(const InputReport& report, std::size_t nan, std::size_t pos_inf, std::size_t neg_inf, std::size_t negative) {
  EXPECT_EQ(report.nan_count, nan);
  EXPECT_EQ(report.positive_inf_count, pos_inf);
  EXPECT_EQ(report.negative_inf_count, neg_inf);
  EXPECT_EQ(report.negative_count, negative);
  EXPECT_EQ(report.changed_count(), nan + pos_inf + neg_inf + negative);
}

TEST(InputPolicy, ClampMapsNanAndNegativesToZeroAndPositiveInfinityToLargestHalf) {
  Image image = dirty_rgba();
  const InputReport report = apply_input_policy(image, InputPolicy::clamp, "dirty.exr");
  expect_counts(report, 2, 2, 1, 2);
  EXPECT_EQ(image.texel(1, 0)[0], 0.0f);
  EXPECT_EQ(image.texel(1, 0)[1], 0.0f);
  EXPECT_EQ(image.texel(2, 0)[2], 65504.0f);
  EXPECT_EQ(image.texel(0, 1)[1], 0.0f);
  EXPECT_EQ(image.texel(0, 1)[3], 0.0f);  // alpha is treated like colour
  EXPECT_EQ(image.texel(2, 1)[0], 65504.0f);
  EXPECT_EQ(image.texel(2, 1)[2], 0.0f);
  // Finite values above the half range and -0.0 are not offending and stay untouched.
  EXPECT_EQ(image.texel(1, 1)[0], 1e6f);
  EXPECT_TRUE(std::signbit(image.texel(1, 1)[1]));
  EXPECT_EQ(image.texel(0, 0)[0], 0.5f);
}

TEST(InputPolicy, ZeroMapsEveryOffendingValueToZero) {
  Image image = dirty_rgba();
  const InputReport report = apply_input_policy(image, InputPolicy::zero, "dirty.exr");
  expect_counts(report, 2, 2, 1, 2);
  EXPECT_EQ(image.texel(2, 0)[2], 0.0f);
  EXPECT_EQ(image.texel(2, 1)[0], 0.0f);
  EXPECT_EQ(image.texel(1, 0)[1], 0.0f);
  for (float v : image.pixels) EXPECT_TRUE(std::isfinite(v) && !(v < 0.0f));
}

TEST(InputPolicy, ErrorNamesTheSourceThePixelAndTheChannelOfTheFirstOffence) {
  Image image = dirty_rgba();
  const Image before = image;
  try {
    apply_input_policy(image, InputPolicy::error, "shots/dirty.exr");
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    // Row-major scan: the first offence is (1, 0) channel R.
    EXPECT_EQ(std::string(e.what()), "shots/dirty.exr: pixel (1, 0) channel 0 (R) is NaN");
  }
  Image negative(2, 2, 3);
  negative.texel(1, 1)[2] = -0.125f;
  try {
    apply_input_policy(negative, InputPolicy::error, "neg.pfm");
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "neg.pfm: pixel (1, 1) channel 2 (B) is -0.125");
  }
  Image infinite(1, 1, 3);
  infinite.texel(0, 0)[1] = -kInf;
  try {
    apply_input_policy(infinite, InputPolicy::error, "inf.hdr");
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "inf.hdr: pixel (0, 0) channel 1 (G) is -Inf");
  }
}

TEST(InputPolicy, CleanImagePassesEveryPolicyUnchanged) {
  Image clean(4, 3, 4);
  for (std::size_t i = 0; i < clean.pixels.size(); ++i) clean.pixels[i] = static_cast<float>(i) * 0.25f;
  for (const InputPolicy policy : {InputPolicy::error, InputPolicy::clamp, InputPolicy::zero}) {
    Image copy = clean;
    const InputReport report = apply_input_policy(copy, policy, "clean");
    EXPECT_EQ(report.changed_count(), 0u);
    EXPECT_EQ(copy.pixels, clean.pixels);
  }
}

TEST(InputPolicy, LuminanceImageCountsEachTexelOnceAndKeepsRgbEqual) {
  Image grey(2, 1, 1);
  grey.texel(0, 0)[0] = grey.texel(0, 0)[1] = grey.texel(0, 0)[2] = kNaN;
  grey.texel(1, 0)[0] = grey.texel(1, 0)[1] = grey.texel(1, 0)[2] = kInf;
  const InputReport report = apply_input_policy(grey, InputPolicy::clamp, "grey.exr");
  expect_counts(report, 1, 1, 0, 0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(grey.texel(0, 0)[c], 0.0f);
    EXPECT_EQ(grey.texel(1, 0)[c], 65504.0f);
  }
}

TEST(InputPolicy, RgbImageIgnoresTheStoredAlpha) {
  Image rgb(1, 1, 3);
  rgb.texel(0, 0)[3] = kNaN;  // not a source value: an RGB image's alpha is storage only
  const InputReport report = apply_input_policy(rgb, InputPolicy::error, "rgb.hdr");
  EXPECT_EQ(report.changed_count(), 0u);
}

TEST(InputPolicy, NamesRoundTripAndUnknownNamesListTheValidOnes) {
  for (const InputPolicy policy : {InputPolicy::error, InputPolicy::clamp, InputPolicy::zero}) {
    EXPECT_EQ(input_policy_from_string(to_string(policy)), policy);
  }
  EXPECT_EQ(to_string(InputPolicy::clamp), "clamp");
  try {
    input_policy_from_string("Clamp");
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("\"Clamp\""), std::string::npos) << message;
    EXPECT_NE(message.find("error, clamp, zero"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace blocklab
