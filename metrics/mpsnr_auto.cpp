// Multi-exposure PSNR with the automatic exposure range of Banterle's HDR_Toolbox (source_code/Metrics/mPSNR.m),
// SPECS.md section 1b:
//   1. Luminance L = 0.2126 R + 0.7152 G + 0.0722 B (Rec. 709) of both images; cMin = smallest positive L of
//      either image, cMax = largest L of either image.
//   2. minFstop = round(log2 cMin), maxFstop = round(log2 cMax); candidate stops c = -maxFstop .. -minFstop
//      (widened by one stop each way when the two are equal, as the toolbox does).
//   3. T(X, c) = clamp(round(255 (2^c X)^(1/2.2)), 0, 255) per channel (rounded, as the toolbox's quant8).
//   4. Stop c is kept only if the mean over all R, G, B values of T_ref / 255 lies strictly in (0.1, 0.9).
//   5. MSE_c = mean over all R, G, B values of (T_ref - T_test)^2; MSE = MEAN of MSE_c over the kept stops;
//      mPSNR = 10 log10(255^2 / MSE).
// Deliberate difference from the toolbox: it divides the accumulated MSE by length(eMax) (= 1, eMax is a scalar),
// i.e. it SUMS the per-stop MSEs; blocklab averages them (the stated intent) and says so in the details.
// Negative values and NaN -> 0 before the luminance and the power (the toolbox refuses negative input).
// If no pixel has positive luminance or no stop qualifies the value is NaN and details["reason"] says why (the
// toolbox returns -1). Only R, G, B are compared (alpha is ignored). Identical images give +inf.
// Error map: per pixel mean over the kept stops of (dR^2 + dG^2 + dB^2); its mean is 3 x the MSE above. All zero
// when no stop qualifies.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>

#include "metrics/builtin_metrics.h"
#include "metrics/exposure_tonemap.h"
#include "metrics/row_reduction.h"
#include "metrics/validation.h"

namespace blocklab {

namespace {

// Rec. 709 / sRGB primaries luminance weights (HDR_Toolbox lum.m).
constexpr double kRec709LuminanceWeights[3] = {0.2126, 0.7152, 0.0722};
constexpr bool kToolboxQuantisesCodes = true;

// Channel value after the negative rule of mPSNR (negative and NaN -> 0).
double non_negative(float value) {
  const double x = static_cast<double>(value);
  return x > 0.0 ? x : 0.0;   // NaN compares false -> 0
}

double rec709_luminance(const float* texel) {
  return kRec709LuminanceWeights[0] * non_negative(texel[0]) + kRec709LuminanceWeights[1] * non_negative(texel[1]) +
         kRec709LuminanceWeights[2] * non_negative(texel[2]);
}

struct StopSelection {
  std::string failure;                  // non-empty: no value can be computed, this is why
  double min_positive_luminance = 0.0;
  double max_luminance = 0.0;
  int candidate_first = 0;
  int candidate_last = 0;
  std::vector<int> kept_stops;
  std::vector<double> kept_mse;         // per kept stop: mean over R,G,B values of (T_ref - T_test)^2
};

// Steps 1, 2, 4 and the per-stop sums of step 5.
StopSelection select_stops(const Image& reference, const Image& test) {
  StopSelection s;
  double min_positive = std::numeric_limits<double>::infinity();
  double max_positive = 0.0;
  for (const Image* image : {&reference, &test}) {
    for (std::size_t i = 0; i < image->texel_count(); ++i) {
      const double l = rec709_luminance(&image->pixels[i * 4]);
      if (l > 0.0) {   // the toolbox's find(L > 0): zero-luminance pixels do not set the range
        min_positive = std::min(min_positive, l);
        max_positive = std::max(max_positive, l);
      }
    }
  }
  if (max_positive == 0.0) {
    s.failure = "no pixel of either image has positive luminance, so no exposure range exists";
    return s;
  }
  // +Inf luminance has no f-stop; the input policy normally removes it before metrics run.
  if (!std::isfinite(max_positive)) {
    s.failure = "an image has infinite luminance, so no exposure range exists";
    return s;
  }
  s.min_positive_luminance = min_positive;
  s.max_luminance = max_positive;
  const int min_fstop = static_cast<int>(std::round(std::log2(min_positive)));   // MATLAB round: half away from 0
  const int max_fstop = static_cast<int>(std::round(std::log2(max_positive)));
  s.candidate_first = -max_fstop;
  s.candidate_last = -min_fstop;
  // One candidate stop only (all luminances round to the same f-stop): the toolbox widens the range by one each way.
  if (s.candidate_first == s.candidate_last) {
    --s.candidate_first;
    ++s.candidate_last;
  }
  const int candidate_count = s.candidate_last - s.candidate_first + 1;
  std::vector<double> scales;
  for (int c = s.candidate_first; c <= s.candidate_last; ++c) scales.push_back(exposure_stop_scale(c));

  // Per row and candidate stop: [2k] sum of reference codes, [2k+1] sum of squared code differences.
  const std::size_t accumulators = 2 * static_cast<std::size_t>(candidate_count);
  const std::vector<double> sums = sum_rows_in_order(reference.height, accumulators, [&](int y, double* out) {
    for (int x = 0; x < reference.width; ++x) {
      const float* r = reference.texel(x, y);
      const float* t = test.texel(x, y);
      double reference_base[3], test_base[3];
      for (int ch = 0; ch < 3; ++ch) {
        reference_base[ch] = exposure_gamma_base(r[ch]);
        test_base[ch] = exposure_gamma_base(t[ch]);
      }
      for (int k = 0; k < candidate_count; ++k) {
        for (int ch = 0; ch < 3; ++ch) {
          const double code_reference = exposure_code(reference_base[ch], scales[k], kToolboxQuantisesCodes);
          const double d = code_reference - exposure_code(test_base[ch], scales[k], kToolboxQuantisesCodes);
          out[2 * k] += code_reference;
          out[2 * k + 1] += d * d;
        }
      }
    }
  });

  const double value_count = 3.0 * static_cast<double>(reference.texel_count());
  for (int k = 0; k < candidate_count; ++k) {
    // mean(T_ref / 255) in (0.1, 0.9) tested exactly: the code sum is an integer (exact in double below 2^53), so
    // 0.1 < sum / (255 n) < 0.9  <=>  10 sum > 255 n  and  10 sum < 9 * 255 n, all exact integers.
    const double code_sum = sums[2 * static_cast<std::size_t>(k)];
    const double ten_times_sum = 10.0 * code_sum;
    if (ten_times_sum > kExposureCodeMax * value_count && ten_times_sum < 9.0 * kExposureCodeMax * value_count) {
      s.kept_stops.push_back(s.candidate_first + k);
      s.kept_mse.push_back(sums[2 * static_cast<std::size_t>(k) + 1] / value_count);
    }
  }
  if (s.kept_stops.empty())
    s.failure = "no candidate stop has a mean reference code in (0.1, 0.9) of 255";
  return s;
}

std::string join_stops(const std::vector<int>& stops) {
  std::string text;
  for (const int c : stops) text += (text.empty() ? "" : ",") + std::to_string(c);
  return text;
}

class MpsnrAutoMetric final : public Metric {
 public:
  std::string name() const override { return "mpsnr_auto"; }
  std::string description() const override {
    return "multi-exposure PSNR, stops chosen automatically as in Banterle's HDR_Toolbox mPSNR.m, rounded T, "
           "per-stop MSEs averaged (SPECS.md 1b)";
  }
  std::string unit() const override { return "dB"; }
  bool higher_is_better() const override { return true; }

  MetricResult compute(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    const StopSelection s = select_stops(reference, test);
    MetricResult result;
    result.details = {
        {"variant", "auto (HDR_Toolbox mPSNR.m exposure selection)"},
        {"luminance_weights", "Rec.709 0.2126 R + 0.7152 G + 0.0722 B"},
        {"gamma", format_number(kExposureGamma)},
        {"quantised", "true (round half away from zero, then clamp to [0, 255])"},
        {"selection", "keep stop c if mean over all R,G,B values of T_ref/255 is in (0.1, 0.9)"},
        {"averaging", "mean of the per-stop MSEs (HDR_Toolbox divides by length(eMax) = 1, i.e. sums them; "
                      "that bug is not reproduced)"},
        {"negative_rule", "negative and NaN channel values -> 0 before luminance and power"},
        {"channels", "RGB (alpha ignored)"},
        {"error_map", "per pixel mean over kept stops of (dR^2+dG^2+dB^2) in 8-bit code units"},
    };
    if (s.max_luminance > 0.0) {
      result.details["min_positive_luminance"] = format_number(s.min_positive_luminance);
      result.details["max_luminance"] = format_number(s.max_luminance);
      result.details["candidate_start"] = std::to_string(s.candidate_first);
      result.details["candidate_stop"] = std::to_string(s.candidate_last);
      result.details["stops"] = join_stops(s.kept_stops);
      result.details["stop_count"] = std::to_string(s.kept_stops.size());
    }
    if (!s.failure.empty()) {
      result.value = std::numeric_limits<double>::quiet_NaN();
      result.details["reason"] = s.failure;
      return result;
    }
    double mse_sum = 0.0;
    for (const double mse : s.kept_mse) mse_sum += mse;   // kept stops in increasing order
    const double mse = mse_sum / static_cast<double>(s.kept_mse.size());
    result.details["mse"] = format_number(mse);
    // MSE = 0 (identical after T): +inf, computed explicitly rather than through a division by zero.
    result.value = mse > 0.0 ? 10.0 * std::log10(kExposureCodeMax * kExposureCodeMax / mse)
                             : std::numeric_limits<double>::infinity();
    return result;
  }

  Image error_map(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    const StopSelection s = select_stops(reference, test);
    std::vector<double> scales;
    for (const int c : s.kept_stops) scales.push_back(exposure_stop_scale(c));
    return make_error_map(reference.width, reference.height, [&](int x, int y) {
      // No qualifying stop: nothing was measured, the map is zero (compute() reports NaN with the reason).
      if (scales.empty()) return 0.0;
      const float* r = reference.texel(x, y);
      const float* t = test.texel(x, y);
      double reference_base[3], test_base[3];
      for (int ch = 0; ch < 3; ++ch) {
        reference_base[ch] = exposure_gamma_base(r[ch]);
        test_base[ch] = exposure_gamma_base(t[ch]);
      }
      double sum = 0.0;
      for (const double scale : scales) {
        for (int ch = 0; ch < 3; ++ch) {
          const double d = exposure_code(reference_base[ch], scale, kToolboxQuantisesCodes) -
                           exposure_code(test_base[ch], scale, kToolboxQuantisesCodes);
          sum += d * d;
        }
      }
      return sum / static_cast<double>(scales.size());
    });
  }
};

}  // namespace

const Metric& mpsnr_auto_metric() {
  static const MpsnrAutoMetric metric;
  return metric;
}

}  // namespace blocklab
