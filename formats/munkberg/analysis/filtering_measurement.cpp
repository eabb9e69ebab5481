// Filtering before the colour transform measured on an image (Munkberg et al. 2008, section 4); see
// filtering_measurement.h.
#include "formats/munkberg/analysis/filtering_measurement.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "metrics/zero_rule.h"

namespace blocklab::munkberg {

namespace {

constexpr int kMaxMagnification = 16;

// log2 with the zero rule of the log-domain metrics: values below 2^-24 (0, tiny negatives from rounding) are raised
// to the floor before the logarithm.
double floored_log2(double x) { return std::log2(std::max(x, kLogDomainDefaultFloor)); }

struct Accumulator {
  double sum_squared_log2 = 0.0, max_log2 = 0.0, sum_squared_relative_red = 0.0;
  std::size_t above_1_percent = 0, red_samples = 0;

  void add(const Rgb<double>& reference, const Rgb<double>& test) {
    const double d[3] = {floored_log2(reference.r) - floored_log2(test.r),
                         floored_log2(reference.g) - floored_log2(test.g),
                         floored_log2(reference.b) - floored_log2(test.b)};
    const double squared = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    sum_squared_log2 += squared;
    max_log2 = std::max(max_log2, std::sqrt(squared));
    static const double kOnePercent = std::log2(1.01);
    if (std::fabs(d[0]) > kOnePercent || std::fabs(d[1]) > kOnePercent || std::fabs(d[2]) > kOnePercent)
      ++above_1_percent;
    // Relative red error only where the reference red is non-zero (no division by 0).
    if (reference.r > 0.0) {
      const double relative = (test.r - reference.r) / reference.r;
      sum_squared_relative_red += relative * relative;
      ++red_samples;
    }
  }

  FilterErrorStatistics finish(std::size_t samples) const {
    FilterErrorStatistics s;
    const double n = static_cast<double>(samples);
    s.log2_rmse = std::sqrt(sum_squared_log2 / n);
    s.max_log2 = max_log2;
    s.fraction_above_1_percent = static_cast<double>(above_1_percent) / n;
    // No red samples at all (a red-free image): the relative red error is reported as 0.
    s.rms_relative_red = red_samples > 0 ? std::sqrt(sum_squared_relative_red / static_cast<double>(red_samples)) : 0.0;
    return s;
  }
};

}  // namespace

FilteringMeasurement measure_logyuv_filtering(const Image& image, int magnification, ShiftRule rule,
                                              ShiftReference reference) {
  const std::string owner = image.metadata.source_path.empty() ? "munkberg filtering" : image.metadata.source_path;
  if (image.width < 2 || image.height < 2)
    fail(owner, "bilinear filtering needs an image of at least 2x2 texels, got " + std::to_string(image.width) + "x" +
                    std::to_string(image.height));
  if (magnification < 1 || magnification > kMaxMagnification)
    fail(owner, "magnification must be in [1, " + std::to_string(kMaxMagnification) + "], got " +
                    std::to_string(magnification));
  // All texels converted once, row by row.
  std::vector<FilterTexel> texels(image.texel_count());
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.texel(x, y);
      texels[static_cast<std::size_t>(y) * image.width + x] = filter_texel_from_rgb(Rgb<double>{p[0], p[1], p[2]});
    }
  std::vector<double> fractions(static_cast<std::size_t>(magnification));
  for (int j = 0; j < magnification; ++j) fractions[j] = (j + 0.5) / magnification;

  Accumulator plain, normalised;
  FilteringMeasurement m;
  std::size_t ratio_quads = 0, non_black_quads = 0;
  for (int y = 0; y + 1 < image.height; ++y)
    for (int x = 0; x + 1 < image.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * image.width + x;
      const FilterTexel quad[4] = {texels[i], texels[i + 1], texels[i + image.width], texels[i + image.width + 1]};
      ++m.quads;
      double lo = quad[0].luminance, hi = quad[0].luminance;
      for (const FilterTexel& t : quad) {
        lo = std::min(lo, t.luminance);
        hi = std::max(hi, t.luminance);
      }
      // A quad with a black texel has an unbounded ratio; it counts as above 2 unless the whole quad is black.
      if (hi > 0.0) {
        ++non_black_quads;
        if (hi > 2.0 * lo) ++ratio_quads;
      }
      bool shifted = false;
      for (double t : fractions)
        for (double s : fractions) {
          const double weights[4] = {(1 - s) * (1 - t), s * (1 - t), (1 - s) * t, s * t};
          const Rgb<double> correct = filter_after_transform(quad, weights, 4);
          plain.add(correct, filter_before_transform(quad, weights, 4));
          int shifts[4];
          normalised.add(correct, filter_before_transform_normalised(quad, weights, 4, rule, reference, shifts));
          for (int k : shifts) shifted = shifted || k != 0;
          ++m.samples;
        }
      if (shifted) ++m.shifted_quads;
    }
  m.fraction_quads_ratio_above_2 =
      non_black_quads > 0 ? static_cast<double>(ratio_quads) / static_cast<double>(non_black_quads) : 0.0;
  m.plain = plain.finish(m.samples);
  m.normalised = normalised.finish(m.samples);
  return m;
}

}  // namespace blocklab::munkberg
