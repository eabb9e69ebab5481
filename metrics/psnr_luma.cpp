// LDR PSNR of luma (SPECS.md section 1d, "report luma PSNR for grayscale modes, with the luma definition"):
//     Y' = 0.299 R' + 0.587 G' + 0.114 B'   (ITU-R BT.601 luma weights, applied to the code values as stored,
//                                           no linearisation; SPECS.md leaves the weights open, this is the choice)
// on code values in [0, 1], each channel clamped to [0, 1] first (metrics/code_value_clamp.h);
//     PSNR = 10 log10(1 / MSE_Y'),  MSE_Y' = mean over pixels of (Y'_ref - Y'_test)^2.
// Alpha is ignored. Identical images give +inf.
// Error map: per pixel (Y'_ref - Y'_test)^2; its mean is the MSE.
#include <cmath>
#include <cstddef>
#include <limits>

#include "metrics/builtin_metrics.h"
#include "metrics/code_value_clamp.h"
#include "metrics/row_reduction.h"
#include "metrics/validation.h"

namespace blocklab {

namespace {

constexpr double kBt601LumaWeights[3] = {0.299, 0.587, 0.114};

double bt601_luma(const float* texel, std::size_t& clamped_count) {
  return kBt601LumaWeights[0] * clamp_code_value(texel[0], clamped_count) +
         kBt601LumaWeights[1] * clamp_code_value(texel[1], clamped_count) +
         kBt601LumaWeights[2] * clamp_code_value(texel[2], clamped_count);
}

double pixel_squared_luma_error(const float* reference_texel, const float* test_texel,
                                std::size_t& clamped_reference, std::size_t& clamped_test) {
  const double d = bt601_luma(reference_texel, clamped_reference) - bt601_luma(test_texel, clamped_test);
  return d * d;
}

class PsnrLumaMetric final : public Metric {
 public:
  std::string name() const override { return "psnr_luma"; }
  std::string description() const override {
    return "LDR PSNR of BT.601 luma Y' = 0.299R + 0.587G + 0.114B of [0,1] code values (clamped), "
           "10 log10(1 / MSE) (SPECS.md 1d)";
  }
  std::string unit() const override { return "dB"; }
  bool higher_is_better() const override { return true; }

  MetricResult compute(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    // Accumulators per row: [0] sum of squared luma errors, [1] clamped reference values, [2] clamped test values.
    const std::vector<double> sums = sum_rows_in_order(reference.height, 3, [&](int y, double* out) {
      std::size_t clamped_reference = 0, clamped_test = 0;
      for (int x = 0; x < reference.width; ++x)
        out[0] += pixel_squared_luma_error(reference.texel(x, y), test.texel(x, y), clamped_reference, clamped_test);
      out[1] = static_cast<double>(clamped_reference);
      out[2] = static_cast<double>(clamped_test);
    });
    const double mse = sums[0] / static_cast<double>(reference.texel_count());
    MetricResult result;
    // MSE = 0: identical luma, +inf (explicit, not a division by zero).
    result.value = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
    result.details = {
        {"variant", "luma, 10 log10(1 / MSE) on [0,1] code values"},
        {"luma", "BT.601 Y' = 0.299 R + 0.587 G + 0.114 B on code values (no linearisation)"},
        {"clamp", "R, G, B clamped to [0, 1] before the luma (NaN -> 0)"},
        {"clamped_reference_samples", format_number(sums[1])},
        {"clamped_test_samples", format_number(sums[2])},
        {"channels", "RGB (alpha ignored)"},
        {"mse", format_number(mse)},
        {"error_map", "per pixel squared luma difference; its mean is the MSE"},
    };
    return result;
  }

  Image error_map(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    return make_error_map(reference.width, reference.height, [&](int x, int y) {
      std::size_t unused_reference = 0, unused_test = 0;
      return pixel_squared_luma_error(reference.texel(x, y), test.texel(x, y), unused_reference, unused_test);
    });
  }
};

}  // namespace

const Metric& psnr_luma_metric() {
  static const PsnrLumaMetric metric;
  return metric;
}

}  // namespace blocklab
