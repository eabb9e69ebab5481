// Banterle et al. 2008 section 4.5, eqs. 5-7: the error of filtering the tone-mapped texture
// (formats/banterle/filtering_error.h).
#include "formats/banterle/filtering_error.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "formats/banterle/reinhard_operator.h"

namespace blocklab {

namespace {

constexpr const char* kWho = "banterle filtering error";
constexpr double kLog2Floor = 5.9604644775390625e-08;   // 2^-24, metrics/zero_rule.h

double inverse(const ReinhardParameters& p, double tone_mapped) {
  return reinhard_inverse(tone_mapped, p.alpha, p.l_white, p.mean);
}

void require_parameters(const ReinhardParameters& p) {
  // NaN fails every comparison: each parameter must be finite and > 0 for g to be defined.
  if (!(p.alpha > 0.0) || !(p.l_white > 0.0) || !(p.mean > 0.0) || !std::isfinite(p.alpha) ||
      !std::isfinite(p.l_white) || !std::isfinite(p.mean))
    fail(kWho, "TMO parameters must be finite and > 0, got alpha " + std::to_string(p.alpha) + ", l_white " +
                   std::to_string(p.l_white) + ", mean " + std::to_string(p.mean));
}

double floored_log2(double value) { return std::log2(value > kLog2Floor ? value : kLog2Floor); }

}  // namespace

double filtering_error_closed_form(const ReinhardParameters& p, double a, double b, double x) {
  const double white2 = p.l_white * p.l_white;
  const auto s = [white2](double q) { return std::sqrt((1.0 - q) * (1.0 - q) + 4.0 * q / white2); };
  const double q = x * a + (1.0 - x) * b;
  return std::fabs(white2 * p.mean / (2.0 * p.alpha) * (x * s(a) + (1.0 - x) * s(b) - s(q)));
}

std::vector<FilteringCurvePoint> filtering_error_curve(const ReinhardParameters& parameters, double a, double b,
                                                       int samples) {
  require_parameters(parameters);
  if (samples < 2) fail(kWho, "a curve needs at least 2 samples, got " + std::to_string(samples));
  // !(x >= 0 && x <= 1) also rejects NaN.
  if (!(a >= 0.0 && a <= 1.0) || !(b >= 0.0 && b <= 1.0))
    fail(kWho, "interval end points must lie in [0, 1], got [" + std::to_string(a) + ", " + std::to_string(b) + "]");
  const double ga = inverse(parameters, a), gb = inverse(parameters, b);
  std::vector<FilteringCurvePoint> curve(static_cast<std::size_t>(samples));
  for (int i = 0; i < samples; ++i) {
    FilteringCurvePoint& point = curve[static_cast<std::size_t>(i)];
    point.x = static_cast<double>(i) / static_cast<double>(samples - 1);
    point.tone_mapped = point.x * a + (1.0 - point.x) * b;
    point.hdr_filtered = point.x * ga + (1.0 - point.x) * gb;
    point.tone_mapped_filtered = inverse(parameters, point.tone_mapped);
    point.error = std::fabs(point.hdr_filtered - point.tone_mapped_filtered);
    point.closed_form_error = filtering_error_closed_form(parameters, a, b, point.x);
    // Interval [0, 0] at x with eq. 5 = 0: no luminance, no relative error.
    point.relative_error = point.hdr_filtered > 0.0 ? point.error / point.hdr_filtered : 0.0;
  }
  return curve;
}

FilteringMeasurement measure_bilinear_filtering_error(const Image& image, const ReinhardParameters& parameters) {
  require_parameters(parameters);
  if (image.width < 2 || image.height < 2)
    fail(kWho, "bilinear filtering needs at least 2x2 texels, got " + std::to_string(image.width) + "x" +
                   std::to_string(image.height));
  const std::size_t width = static_cast<std::size_t>(image.width);
  const double scale = parameters.alpha / parameters.mean;
  // Per texel: the tone-mapped luminance t (clipped at 1 as the 8-bit texture is) and g(t), the HDR value that the
  // texture represents (= L below the white point).
  std::vector<double> tone(image.texel_count()), hdr(image.texel_count());
  for (std::size_t i = 0; i < image.texel_count(); ++i) {
    const double luminance = static_cast<double>(banterle_luminance(&image.pixels[i * 4]));
    // L <= 0 (black, or negative channels): f(0) = 0, as the format's tone map.
    const double t = luminance > 0.0 ? std::min(reinhard_forward_scaled(scale * luminance, parameters.l_white), 1.0)
                                     : 0.0;
    tone[i] = t;
    hdr[i] = inverse(parameters, t);
  }
  FilteringMeasurement result;
  double sum_interval = 0.0, sum_error2 = 0.0, sum_signed = 0.0, sum_relative2 = 0.0, sum_log2 = 0.0;
  std::size_t wide = 0, relative_above = 0;
  const double weights[2] = {0.25, 0.75};
  for (std::size_t y = 0; y + 1 < static_cast<std::size_t>(image.height); ++y)
    for (std::size_t x = 0; x + 1 < width; ++x) {
      const std::size_t i00 = y * width + x, i10 = i00 + 1, i01 = i00 + width, i11 = i01 + 1;
      const double lo = std::min({tone[i00], tone[i10], tone[i01], tone[i11]});
      const double hi = std::max({tone[i00], tone[i10], tone[i01], tone[i11]});
      for (double v : weights)
        for (double u : weights) {
          const auto bilinear = [u, v](double c00, double c10, double c01, double c11) {
            return (1.0 - v) * ((1.0 - u) * c00 + u * c10) + v * ((1.0 - u) * c01 + u * c11);
          };
          const double correct = bilinear(hdr[i00], hdr[i10], hdr[i01], hdr[i11]);
          const double filtered = inverse(parameters, bilinear(tone[i00], tone[i10], tone[i01], tone[i11]));
          const double difference = correct - filtered;
          const double error = std::fabs(difference);
          // Both filters give 0 only on black quads: no relative error there.
          const double relative = correct > 0.0 ? error / correct : 0.0;
          const double log2_error = std::fabs(floored_log2(correct) - floored_log2(filtered));
          ++result.samples;
          sum_interval += hi - lo;
          sum_error2 += error * error;
          sum_signed += difference;
          sum_relative2 += relative * relative;
          sum_log2 += log2_error * log2_error;
          result.max_error = std::max(result.max_error, error);
          result.max_relative_error = std::max(result.max_relative_error, relative);
          result.max_log2_error = std::max(result.max_log2_error, log2_error);
          relative_above += relative > 0.01;
        }
      result.max_interval = std::max(result.max_interval, hi - lo);
      wide += hi - lo > 0.3;
    }
  const double n = static_cast<double>(result.samples);
  result.mean_interval = sum_interval / n;
  result.fraction_interval_above_0_3 = 4.0 * static_cast<double>(wide) / n;
  result.rms_error = std::sqrt(sum_error2 / n);
  result.mean_signed_error = sum_signed / n;
  result.rms_relative_error = std::sqrt(sum_relative2 / n);
  result.fraction_relative_above_1_percent = static_cast<double>(relative_above) / n;
  result.rms_log2_error = std::sqrt(sum_log2 / n);
  return result;
}

}  // namespace blocklab
