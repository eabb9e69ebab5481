// Multi-exposure PSNR with a fixed stop range (Munkberg et al. 2006, SIGGRAPH, "HDR Texture Compression for Graphics
// Hardware"), SPECS.md section 1b, normalised like astcenc (ARM-software/astc-encoder astcenccli_error_metrics.cpp):
//     T(X, c) = clamp(255 * (2^c X)^(1/2.2), 0, 255) per channel, NOT rounded by default (option quantise=true
//               rounds half away from zero),
//     MSE     = (1/(n w h)) sum_{c = start..stop} sum_xy (dR^2 + dG^2 + dB^2),   n = stop - start + 1,
//     mPSNR   = 10 log10(3 * 255^2 / MSE).
// Defaults start = -10, stop = +10 (astcenc's -mpsnr defaults). Negative values and NaN -> 0 before the power.
// Only R, G, B are compared (alpha is ignored). Identical images give +inf.
// Error map: per pixel (1/n) sum_c (dR^2 + dG^2 + dB^2), so the mean of the map is the MSE above.
#include <cmath>
#include <limits>

#include "core/error.h"
#include "metrics/builtin_metrics.h"
#include "metrics/exposure_tonemap.h"
#include "metrics/row_reduction.h"
#include "metrics/validation.h"

namespace blocklab {

namespace {

constexpr int kDefaultStartStop = -10;
constexpr int kDefaultStopStop = 10;
constexpr int kLargestStopMagnitude = 1000;   // beyond +-1000 stops every T is 0 or 255: a typo, not a range

struct StopRange {
  int start = kDefaultStartStop;
  int stop = kDefaultStopStop;
  bool quantise = false;
  int count() const { return stop - start + 1; }
};

class MpsnrMetric final : public Metric {
 public:
  std::string name() const override { return "mpsnr"; }
  std::string description() const override {
    return "multi-exposure PSNR over fixed integer stops start..stop, T = clamp(255 (2^c X)^(1/2.2), 0, 255) "
           "unrounded (Munkberg et al. 2006; astcenc normalisation; SPECS.md 1b)";
  }
  std::string unit() const override { return "dB"; }
  bool higher_is_better() const override { return true; }
  std::vector<std::string> option_names() const override { return {"start", "stop", "quantise"}; }

  MetricResult compute(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    const StopRange range = range_from(options);
    const std::vector<double> scales = stop_scales(range);
    const double squared_sum = sum_rows_in_order(reference.height, [&](int y) {
      double row = 0.0;
      for (int x = 0; x < reference.width; ++x)
        row += pixel_squared_code_error(reference.texel(x, y), test.texel(x, y), scales, range.quantise);
      return row;
    });
    const double mse = squared_sum / (static_cast<double>(range.count()) * static_cast<double>(reference.texel_count()));
    MetricResult result;
    // MSE = 0 (identical after T): the PSNR is +inf; computed explicitly rather than through a division by zero.
    result.value = mse > 0.0 ? 10.0 * std::log10(3.0 * kExposureCodeMax * kExposureCodeMax / mse)
                             : std::numeric_limits<double>::infinity();
    result.details = {
        {"variant", "fixed"},
        {"start", std::to_string(range.start)},
        {"stop", std::to_string(range.stop)},
        {"stop_count", std::to_string(range.count())},
        {"gamma", format_number(kExposureGamma)},
        {"quantised", range.quantise ? "true" : "false"},
        {"normalisation", "astcenc: 10 log10(3 * 255^2 / MSE), MSE = sum_stops sum_pixels (dR^2+dG^2+dB^2) / "
                          "(stops * pixels)"},
        {"negative_rule", "negative and NaN channel values -> 0 before the power"},
        {"channels", "RGB (alpha ignored)"},
        {"mse", format_number(mse)},
        {"error_map", "per pixel mean over stops of (dR^2+dG^2+dB^2) in 8-bit code units; its mean is the MSE"},
    };
    return result;
  }

  Image error_map(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    const StopRange range = range_from(options);
    const std::vector<double> scales = stop_scales(range);
    return make_error_map(reference.width, reference.height, [&](int x, int y) {
      return pixel_squared_code_error(reference.texel(x, y), test.texel(x, y), scales, range.quantise) /
             static_cast<double>(range.count());
    });
  }

 private:
  StopRange range_from(const MetricOptions& options) const {
    StopRange range;
    range.start = option_int(name(), options, "start", kDefaultStartStop);
    range.stop = option_int(name(), options, "stop", kDefaultStopStop);
    range.quantise = option_bool(name(), options, "quantise", false);
    for (const auto& [key, value] : {std::pair{"start", range.start}, std::pair{"stop", range.stop}})
      if (value < -kLargestStopMagnitude || value > kLargestStopMagnitude)
        fail(name() + ": option '" + key + "'",
             "must lie in [-" + std::to_string(kLargestStopMagnitude) + ", " + std::to_string(kLargestStopMagnitude) +
                 "], got " + std::to_string(value));
    if (range.start > range.stop)
      fail(name() + ": option 'start'", "start (" + std::to_string(range.start) + ") must be <= stop (" +
                                            std::to_string(range.stop) + ")");
    return range;
  }

  static std::vector<double> stop_scales(const StopRange& range) {
    std::vector<double> scales;
    for (int c = range.start; c <= range.stop; ++c) scales.push_back(exposure_stop_scale(c));
    return scales;
  }

  // sum over stops of (dR^2 + dG^2 + dB^2) for one pixel, stops in increasing order.
  static double pixel_squared_code_error(const float* reference_texel, const float* test_texel,
                                         const std::vector<double>& scales, bool quantise) {
    double reference_base[3], test_base[3];
    for (int ch = 0; ch < 3; ++ch) {
      reference_base[ch] = exposure_gamma_base(reference_texel[ch]);
      test_base[ch] = exposure_gamma_base(test_texel[ch]);
    }
    double sum = 0.0;
    for (const double scale : scales) {
      for (int ch = 0; ch < 3; ++ch) {
        const double d = exposure_code(reference_base[ch], scale, quantise) - exposure_code(test_base[ch], scale, quantise);
        sum += d * d;
      }
    }
    return sum;
  }
};

}  // namespace

const Metric& mpsnr_metric() {
  static const MpsnrMetric metric;
  return metric;
}

}  // namespace blocklab
