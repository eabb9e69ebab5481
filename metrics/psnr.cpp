// LDR PSNR over R, G, B (SPECS.md section 1d; astcenc "PSNR (LDR-RGB)"): inputs are code values scaled to [0, 1],
// clamped to [0, 1] (metrics/code_value_clamp.h), and
//     PSNR = 10 log10(1 / MSE),  MSE = mean over all R, G, B samples of (ref - test)^2,
// which equals 10 log10(255^2 / MSE_8bit) for 8-bit data. No gamma linearisation, no luma weighting. Alpha is
// ignored. Identical images give +inf.
// Option `channels` (default "rgb") picks the channels averaged instead: any of the letters r, g, b, a once each,
// e.g. "r" for a single-channel format such as BC4, "a" for the alpha PSNR of BC3/BC7, "rgba".
// Error map: per pixel mean over the chosen channels of the squared difference; its mean is the MSE.
//
// Option `peak` (default "1") picks the signal peak and the domain:
//   1              the definition above (code values clamped to [0, 1], peak 1).
//   reference_max  the HDR PSNR of Wang et al. 2007 Table 2 ("PSNR via the metric in [Li et al. 2005] ... across all
//                  color channels"): linear values, not clamped (NaN -> 0), peak = the largest value of the chosen
//                  channels over the whole reference image, PSNR = 10 log10(peak^2 / MSE). Wang 2007 states neither
//                  the peak nor the domain; this one is calibrated on their memorial row (LUV / LUVW / RGBE / FP16 =
//                  64 / 65 / 77 / inf dB): it gives our wang luv / luvw 64.2 / 66.9 dB and fp16 inf (memorial.hdr's
//                  RGBE values are exact in half floats), and RGBE of float sources 64-66 dB (Tree, MtTamWest; the
//                  paper's RGBE column is 57-77 dB). Peak 1 on linear values gives 15 / 18 dB, peak = mean 5 / 8
//                  dB, log-domain PSNRs 33-56 dB (configs/papers/wang2007/README.md). Our rgbe is lossless on RGBE
//                  sources such as memorial.hdr (inf where the paper has 77 dB).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"

#include "metrics/builtin_metrics.h"
#include "metrics/code_value_clamp.h"
#include "metrics/row_reduction.h"
#include "metrics/validation.h"

namespace blocklab {

namespace {

// Channel indices (0..3) of the `channels` option, in the order written; throws naming the option on anything but
// distinct letters of "rgba".
std::vector<int> parse_channels(const MetricOptions& options) {
  const auto found = options.find("channels");
  const std::string text = found == options.end() ? "rgb" : found->second;
  std::vector<int> channels;
  for (const char letter : text) {
    const std::string letters = "rgba";
    const auto position = letters.find(letter);
    if (position == std::string::npos)
      fail("psnr: option 'channels'", "expected letters of r, g, b, a, got '" + text + "'");
    for (int channel : channels)
      if (channel == static_cast<int>(position))
        fail("psnr: option 'channels'", "channel '" + std::string(1, letter) + "' given twice in '" + text + "'");
    channels.push_back(static_cast<int>(position));
  }
  if (channels.empty()) fail("psnr: option 'channels'", "empty (expected e.g. rgb, r, a, rgba)");
  return channels;
}

std::string channel_names(const std::vector<int>& channels) {
  std::string names;
  for (int channel : channels) names += "RGBA"[channel];
  return names;
}

// The `peak` option: true for reference_max (linear values, peak = reference maximum), false for 1 (code values).
bool parse_reference_max_peak(const MetricOptions& options) {
  const auto found = options.find("peak");
  if (found == options.end() || found->second == "1") return false;
  if (found->second == "reference_max") return true;
  fail("psnr: option 'peak'", "expected 1 or reference_max, got '" + found->second + "'");
}

// A linear value of the reference_max variant: unchanged, NaN -> 0 (as the clamp of the code-value variant does).
double linear_value(float value) { return std::isnan(value) ? 0.0 : static_cast<double>(value); }

// Sum over the chosen channels of the squared difference of one pixel: clamped code values, or linear values.
double pixel_squared_error(const float* reference_texel, const float* test_texel, const std::vector<int>& channels,
                           bool linear, std::size_t& clamped_reference, std::size_t& clamped_test) {
  double sum = 0.0;
  for (int c : channels) {
    const double d = linear ? linear_value(reference_texel[c]) - linear_value(test_texel[c])
                            : clamp_code_value(reference_texel[c], clamped_reference) -
                                  clamp_code_value(test_texel[c], clamped_test);
    sum += d * d;
  }
  return sum;
}

class PsnrMetric final : public Metric {
 public:
  std::string name() const override { return "psnr"; }
  std::string description() const override {
    return "LDR PSNR over R,G,B code values in [0,1] (clamped), 10 log10(1 / MSE) (SPECS.md 1d); peak=reference_max: "
           "linear values, peak = reference maximum (Wang 2007 Table 2)";
  }
  std::string unit() const override { return "dB"; }
  bool higher_is_better() const override { return true; }
  std::vector<std::string> option_names() const override { return {"channels", "peak"}; }

  MetricResult compute(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    const std::vector<int> channels = parse_channels(options);
    const bool linear = parse_reference_max_peak(options);
    // Accumulators per row: [0] sum of squared errors, [1] clamped reference values, [2] clamped test values.
    const std::vector<double> sums = sum_rows_in_order(reference.height, 3, [&](int y, double* out) {
      std::size_t clamped_reference = 0, clamped_test = 0;
      for (int x = 0; x < reference.width; ++x)
        out[0] += pixel_squared_error(reference.texel(x, y), test.texel(x, y), channels, linear, clamped_reference,
                                      clamped_test);
      out[1] = static_cast<double>(clamped_reference);
      out[2] = static_cast<double>(clamped_test);
    });
    const double mse = sums[0] / (static_cast<double>(channels.size()) * static_cast<double>(reference.texel_count()));
    const std::string names = channel_names(channels);
    MetricResult result;
    if (linear) {
      double peak = 0.0;   // a maximum: the same in any order
      for (std::size_t i = 0; i < reference.texel_count(); ++i)
        for (int c : channels) peak = std::max(peak, linear_value(reference.pixels[i * 4 + c]));
      result.value = mse > 0.0 ? 10.0 * std::log10(peak * peak / mse) : std::numeric_limits<double>::infinity();
      result.details = {
          {"variant", names + ", 10 log10(peak^2 / MSE) on linear values, peak = largest reference value (Wang 2007 "
                              "Table 2's Li et al. 2005 PSNR)"},
          {"clamp", "none (NaN -> 0)"},
          {"peak", format_number(peak)},
          {"channels", names == "RGB" ? "RGB (alpha ignored)" : names},
          {"mse", format_number(mse)},
          {"error_map", "per pixel mean over " + names + " of the squared difference; its mean is the MSE"},
      };
      return result;
    }
    // MSE = 0: identical images, +inf (explicit, not a division by zero).
    result.value = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
    result.details = {
        {"variant", names + ", 10 log10(1 / MSE) on [0,1] code values (= 10 log10(255^2 / MSE) for 8-bit)"},
        {"clamp", "values clamped to [0, 1] before the error (NaN -> 0)"},
        {"clamped_reference_samples", format_number(sums[1])},
        {"clamped_test_samples", format_number(sums[2])},
        {"channels", names == "RGB" ? "RGB (alpha ignored)" : names},
        {"mse", format_number(mse)},
        {"error_map", "per pixel mean over " + names + " of the squared difference; its mean is the MSE"},
    };
    return result;
  }

  Image error_map(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    const std::vector<int> channels = parse_channels(options);
    const bool linear = parse_reference_max_peak(options);
    return make_error_map(reference.width, reference.height, [&](int x, int y) {
      std::size_t unused_reference = 0, unused_test = 0;
      return pixel_squared_error(reference.texel(x, y), test.texel(x, y), channels, linear, unused_reference,
                                 unused_test) /
             static_cast<double>(channels.size());
    });
  }
};

}  // namespace

const Metric& psnr_metric() {
  static const PsnrMetric metric;
  return metric;
}

}  // namespace blocklab
