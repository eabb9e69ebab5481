// log2[RGB] RMSE (Xu, Pattanaik & Hughes 2005, IEEE CG&A 25(6); the HDR-texture error of Munkberg 2006/2008),
// SPECS.md section 1a, with the astcenc normalisation (ARM-software/astc-encoder astcenccli_error_metrics.cpp):
//     log2rgb = sqrt( (1/N_pixels) * sum_pixels sum_{c in R,G,B} (log2 X_c - log2 Y_c)^2 )
// i.e. divided by the pixel count, not by 3 x pixels. Zeros, negatives and NaN follow metrics/zero_rule.h: option
// `zero_rule` = floor (default; option `floor`, 2^-24) or skip (piccante / Banterle 2008: values <= 0 in either image
// are left out, and the sum is divided by counted values / 3, which is the pixel count when nothing is left out).
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
constexpr const char* kZeroRuleOption = "zero_rule";

class Log2RgbMetric final : public Metric {
 public:
  std::string name() const override { return "log2rgb"; }
  std::string description() const override {
    return "log2[RGB] RMSE, sqrt(sum over pixels and R,G,B of (log2 ref - log2 test)^2 / pixel count) "
           "(Xu et al. 2005; astcenc normalisation; SPECS.md 1a)";
  }
  std::string unit() const override { return "log2 units"; }
  bool higher_is_better() const override { return false; }
  std::vector<std::string> option_names() const override { return {kZeroRuleOption, kFloorOption}; }

  MetricResult compute(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    const LogDomainZeroRule rule = zero_rule_from(options);
    // Accumulators per row: [0] sum of squared log2 differences, [1] reference samples raised to the floor (floor)
    // or pairs left out (skip), [2] test samples raised to the floor (floor only), [3] pairs counted.
    const std::vector<double> sums = sum_rows_in_order(reference.height, 4, [&](int y, double* out) {
      PairCounts counts;
      for (int x = 0; x < reference.width; ++x)
        out[0] += squared_log2_distance(rule, reference.texel(x, y), test.texel(x, y), counts);
      out[1] = static_cast<double>(counts.first);
      out[2] = static_cast<double>(counts.second);
      out[3] = static_cast<double>(counts.counted);
    });
    MetricResult result;
    const bool skip = rule.mode == LogDomainZeroRule::Mode::skip;
    // Pixel-count normalisation; under skip the "pixel count" is counted values / 3, so an image without zeros gets
    // the same value under both rules. Nothing counted (every pair had a zero): the RMSE is undefined, NaN.
    const double normaliser = skip ? sums[3] / 3.0 : static_cast<double>(reference.texel_count());
    result.value = normaliser > 0.0 ? std::sqrt(sums[0] / normaliser) : std::nan("");
    result.details = {
        {"variant", "astcenc normalisation: sqrt(sum_pixels sum_RGB dlog2^2 / pixel_count)"},
        {"channels", "RGB (alpha ignored)"},
        {"zero_rule", rule.describe()},
    };
    if (skip) {
      result.details["skipped_samples"] = format_number(sums[1]);
    } else {
      result.details["floor"] = format_number(rule.floor);
      result.details["clamped_reference_samples"] = format_number(sums[1]);
      result.details["clamped_test_samples"] = format_number(sums[2]);
    }
    result.details["error_map"] = "per pixel sqrt(sum_RGB dlog2^2 over the counted values); log2rgb = RMS of the map "
                                  "when nothing is left out";
    return result;
  }

  Image error_map(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    const LogDomainZeroRule rule = zero_rule_from(options);
    return make_error_map(reference.width, reference.height, [&](int x, int y) {
      PairCounts unused;
      return std::sqrt(squared_log2_distance(rule, reference.texel(x, y), test.texel(x, y), unused));
    });
  }

 private:
  // Per-row sample counts: floor: first/second = reference/test samples raised; skip: first = pairs left out.
  struct PairCounts {
    std::size_t first = 0, second = 0, counted = 0;
  };

  LogDomainZeroRule zero_rule_from(const MetricOptions& options) const {
    LogDomainZeroRule rule;
    const auto it = options.find(kZeroRuleOption);
    if (it != options.end()) {
      if (it->second == "skip") rule.mode = LogDomainZeroRule::Mode::skip;
      else if (it->second != "floor")
        fail(name() + ": option 'zero_rule'", "unknown zero rule '" + it->second + "'; valid zero rules: floor, skip");
      // A floor under the skip rule would be silently ignored: say so instead.
      if (rule.mode == LogDomainZeroRule::Mode::skip && options.count(kFloorOption) != 0)
        fail(name() + ": option 'floor'", "applies to zero_rule=floor only (zero_rule=skip leaves zeros out)");
    }
    rule.floor = option_double(name(), options, kFloorOption, kLogDomainDefaultFloor);
    // log2 of a non-positive floor is -inf or NaN: the floor must be a positive number.
    if (!(rule.floor > 0.0)) fail(name() + ": option 'floor'", "must be > 0, got " + format_number(rule.floor));
    return rule;
  }

  // sum over R, G, B of (log2 ref - log2 test)^2 for one pixel, in channel order, under the zero rule.
  static double squared_log2_distance(const LogDomainZeroRule& rule, const float* reference_texel,
                                      const float* test_texel, PairCounts& counts) {
    double sum = 0.0;
    for (int c = 0; c < 3; ++c) {
      double d = 0.0;
      if (rule.mode == LogDomainZeroRule::Mode::skip) {
        // A zero, negative or NaN on either side has no logarithm: the pair is left out (piccante's rule).
        if (!LogDomainZeroRule::both_positive(reference_texel[c], test_texel[c])) {
          ++counts.first;
          continue;
        }
        d = std::log2(static_cast<double>(reference_texel[c])) - std::log2(static_cast<double>(test_texel[c]));
      } else {
        d = std::log2(rule.apply(reference_texel[c], counts.first)) - std::log2(rule.apply(test_texel[c], counts.second));
      }
      ++counts.counted;
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
