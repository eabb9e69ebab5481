// The metric registry and the behaviour every metric shares: names, validation messages, error maps,
// determinism, alpha ignored.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "core/error.h"
#include "metrics/metric.h"

namespace blocklab {
namespace {

// A deterministic HDR-ish test pair: smooth gradient over several decades plus a small perturbation.
Image gradient(int w, int h, double perturbation) {
  Image image(w, h, 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* t = image.texel(x, y);
      for (int c = 0; c < 3; ++c)
        t[c] = static_cast<float>(std::exp2(-6.0 + 9.0 * x / w + 0.5 * c) * (1.0 + perturbation * std::sin(x * 7 + y * 3 + c)));
      t[3] = static_cast<float>(0.5 + 0.5 * std::sin(x + y));
    }
  return image;
}

TEST(MetricRegistry, ListsEveryMetricInTableOrder) {
  std::string names;
  for (const Metric* m : all_metrics()) names += m->name() + " ";
  EXPECT_EQ(names, "log2rgb mpsnr mpsnr_auto psnr psnr_luma pu21_psnr ");
}

TEST(MetricRegistry, UnknownNameListsTheValidNames) {
  try {
    find_metric("ssim");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "unknown metric 'ssim'; valid metrics: log2rgb, mpsnr, mpsnr_auto, psnr, psnr_luma, pu21_psnr");
  }
}

TEST(MetricRegistry, EveryMetricDescribesItself) {
  for (const Metric* m : all_metrics()) {
    EXPECT_FALSE(m->description().empty()) << m->name();
    EXPECT_FALSE(m->unit().empty()) << m->name();
    EXPECT_EQ(&find_metric(m->name()), m);
  }
  EXPECT_FALSE(find_metric("log2rgb").higher_is_better());
  EXPECT_TRUE(find_metric("mpsnr").higher_is_better());
}

TEST(MetricRegistry, EveryMetricRejectsASizeMismatchNamingBothSizes) {
  for (const Metric* m : all_metrics()) {
    for (const bool map : {false, true}) {
      try {
        if (map) m->error_map(Image(10, 10), Image(12, 10), {});
        else m->compute(Image(10, 10), Image(12, 10), {});
        FAIL() << m->name();
      } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), m->name() + ": size mismatch 10x10 vs 12x10");
      }
    }
  }
}

TEST(MetricRegistry, EveryMetricRejectsEmptyImages) {
  for (const Metric* m : all_metrics()) EXPECT_THROW(m->compute(Image(0, 0), Image(0, 0), {}), Error) << m->name();
}

TEST(MetricRegistry, EveryMetricRejectsAnUnknownOptionListingTheValidOnes) {
  for (const Metric* m : all_metrics()) {
    try {
      m->compute(Image(2, 2), Image(2, 2), {{"no_such_option", "1"}});
      FAIL() << m->name();
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(m->name() + ": unknown option 'no_such_option' (", 0), 0u) << message;
      for (const std::string& valid : m->option_names()) EXPECT_NE(message.find(valid), std::string::npos) << message;
    }
  }
}

TEST(MetricRegistry, EveryErrorMapIsGreyAndImageSized) {
  const Image reference = gradient(9, 5, 0.0), test = gradient(9, 5, 0.05);
  for (const Metric* m : all_metrics()) {
    const Image map = m->error_map(reference, test, {});
    ASSERT_EQ(map.width, 9) << m->name();
    ASSERT_EQ(map.height, 5) << m->name();
    bool any_nonzero = false;
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 9; ++x) {
        const float* t = map.texel(x, y);
        EXPECT_EQ(t[0], t[1]);
        EXPECT_EQ(t[0], t[2]);
        EXPECT_GE(t[0], 0.0f) << m->name();
        any_nonzero |= t[0] > 0.0f;
      }
    EXPECT_TRUE(any_nonzero) << m->name();
  }
}

TEST(MetricRegistry, EveryMetricIsBitIdenticalAcrossRepeatedRunsOnLargeImages) {
  const Image reference = gradient(300, 200, 0.0), test = gradient(300, 200, 0.02);
  for (const Metric* m : all_metrics()) {
    const double first = m->compute(reference, test, {}).value;
    for (int run = 0; run < 3; ++run) {
      const double again = m->compute(reference, test, {}).value;
      EXPECT_EQ(std::memcmp(&first, &again, sizeof(double)), 0) << m->name();
    }
  }
}

TEST(MetricRegistry, EveryMetricIgnoresAlphaAndSaysSo) {
  const Image reference = gradient(6, 4, 0.0);
  Image test = gradient(6, 4, 0.1);
  Image test_other_alpha = test;
  for (std::size_t i = 3; i < test_other_alpha.pixels.size(); i += 4) test_other_alpha.pixels[i] = 0.25f;
  for (const Metric* m : all_metrics()) {
    const MetricResult r = m->compute(reference, test, {});
    EXPECT_EQ(r.value, m->compute(reference, test_other_alpha, {}).value) << m->name();
    EXPECT_EQ(r.details.at("channels"), "RGB (alpha ignored)") << m->name();
    EXPECT_TRUE(std::isfinite(r.value)) << m->name();
  }
}

}  // namespace
}  // namespace blocklab
