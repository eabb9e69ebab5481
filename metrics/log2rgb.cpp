// log2[RGB] RMSE (Xu, Pattanaik & Hughes 2005, IEEE CG&A 25(6); the HDR-texture error of Munkberg 2006/2008),
// SPECS.md section 1a, with the astcenc normalisation (ARM-software/astc-encoder astcenccli_error_metrics.cpp):
//     log2rgb = sqrt( (1/N_pixels) * sum_pixels sum_{c in R,G,B} (log2 X_c - log2 Y_c)^2 )
// i.e. divided by the pixel count, not by 3 x pixels. Zeros, negatives and NaN follow metrics/zero_rule.h.
// Only R, G, B are compared (alpha is ignored).
// Error map: per pixel sqrt( sum_c (log2 X_c - log2 Y_c)^2 ), so log2rgb is the RMS of the map.
#include <cmath>
#include <cstddef>

#include "core/error.h"
#include "metrics/builtin_metrics.h"
#include "metrics/row_reduction.h"
#include "metrics/validation.h"
#include "metrics/zero_rule.h"

namespace blocklab {

namespace {

constexpr const char* kFloorOption = "floor";

class Log2RgbMetric final : public Metric {
 public:
  std::string name() const override { return "log2rgb"; }
  std::string description() const override {
    return "log2[RGB] RMSE, sqrt(sum over pixels and R,G,B of (log2 ref - log2 test)^2 / pixel count) "
           "(Xu et al. 2005; astcenc normalisation; SPECS.md 1a)";
  }
  std::string unit() const override { return "log2 units"; }
  bool higher_is_better() const override { return false; }
  std::vector<std::string> option_names() const override { return {kFloorOption}; }

  MetricResult compute(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    const LogDomainZeroRule rule = zero_rule_from(options);
    // Accumulators per row: [0] sum of squared log2 differences, [1] clamped reference samples, [2] clamped test.
    const std::vector<double> sums = sum_rows_in_order(reference.height, 3, [&](int y, double* out) {
      std::size_t clamped_reference = 0, clamped_test = 0;
      for (int x = 0; x < reference.width; ++x) {
        out[0] += squared_log2_distance(rule, reference.texel(x, y), test.texel(x, y), clamped_reference,
                                        clamped_test);
      }
      out[1] = static_cast<double>(clamped_reference);
      out[2] = static_cast<double>(clamped_test);
    });
    MetricResult result;
    result.value = std::sqrt(sums[0] / static_cast<double>(reference.texel_count()));
    result.details = {
        {"variant", "astcenc normalisation: sqrt(sum_pixels sum_RGB dlog2^2 / pixel_count)"},
        {"channels", "RGB (alpha ignored)"},
        {"zero_rule", rule.describe()},
        {"floor", format_number(rule.floor)},
        {"clamped_reference_samples", format_number(sums[1])},
        {"clamped_test_samples", format_number(sums[2])},
        {"error_map", "per pixel sqrt(sum_RGB dlog2^2); log2rgb = RMS of the map"},
    };
    return result;
  }

  Image error_map(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    const LogDomainZeroRule rule = zero_rule_from(options);
    return make_error_map(reference.width, reference.height, [&](int x, int y) {
      std::size_t unused_reference = 0, unused_test = 0;
      return std::sqrt(
          squared_log2_distance(rule, reference.texel(x, y), test.texel(x, y), unused_reference, unused_test));
    });
  }

 private:
  LogDomainZeroRule zero_rule_from(const MetricOptions& options) const {
    LogDomainZeroRule rule;
    rule.floor = option_double(name(), options, kFloorOption, kLogDomainDefaultFloor);
    // log2 of a non-positive floor is -inf or NaN: the floor must be a positive number.
    if (!(rule.floor > 0.0)) fail(name() + ": option 'floor'", "must be > 0, got " + format_number(rule.floor));
    return rule;
  }

  // sum over R, G, B of (log2 ref - log2 test)^2 for one pixel, in channel order.
  static double squared_log2_distance(const LogDomainZeroRule& rule, const float* reference_texel,
                                      const float* test_texel, std::size_t& clamped_reference,
                                      std::size_t& clamped_test) {
    double sum = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double d = std::log2(rule.apply(reference_texel[c], clamped_reference)) -
                       std::log2(rule.apply(test_texel[c], clamped_test));
      sum += d * d;
    }
    return sum;
  }
};

}  // namespace

const Metric& log2rgb_metric() {
  static const Log2RgbMetric metric;
  return metric;
}

}  // namespace blocklab
