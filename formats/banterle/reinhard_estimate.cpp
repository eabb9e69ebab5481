// Reinhard 2002 parameter estimation (formats/banterle/reinhard_estimate.h; SPECS.md section 3).
#include "formats/banterle/reinhard_estimate.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "formats/banterle/reinhard_operator.h"

namespace blocklab {

namespace {

// HDR_Toolbox logMean.m's delta: keeps log and 1/x finite at L = 0.
constexpr double kMeanDelta = 1e-6;

// Value of rank floor(p * (n - 1)) of `values` (reordered in place). Precondition: non-empty.
double percentile(std::vector<double>& values, double p) {
  const std::size_t rank = static_cast<std::size_t>(std::floor(p * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
  return values[rank];
}

}  // namespace

TmoMean parse_tmo_mean(const std::string& text, const std::string& who) {
  if (text == "geometric") return TmoMean::geometric;
  if (text == "harmonic") return TmoMean::harmonic;
  fail(who, "option 'mean': unknown value '" + text + "'; valid values: geometric, harmonic");
}

const char* to_string(TmoMean mean) { return mean == TmoMean::geometric ? "geometric" : "harmonic"; }

std::vector<double> banterle_luminances(const Image& image) {
  std::vector<double> luminances(image.texel_count());
  for (std::size_t i = 0; i < luminances.size(); ++i)
    luminances[i] = static_cast<double>(banterle_luminance(&image.pixels[i * 4]));
  return luminances;
}

ReinhardParameters estimate_reinhard_parameters(const std::vector<double>& luminances, TmoMean mean) {
  ReinhardParameters parameters;
  std::vector<double> positive;
  positive.reserve(luminances.size());
  double sum = 0.0;
  for (double value : luminances) {
    // Negative luminance (negative channels that passed a `zero`-less policy) counts as 0 in the mean.
    const double clamped = value > 0.0 ? value : 0.0;
    sum += mean == TmoMean::geometric ? std::log(kMeanDelta + clamped) : 1.0 / (kMeanDelta + clamped);
    if (value > 0.0) positive.push_back(value);
  }
  // A black image (no positive luminance): nothing to estimate; keep the neutral defaults.
  if (positive.empty()) return parameters;
  const double count = static_cast<double>(luminances.size());
  parameters.mean = mean == TmoMean::geometric ? std::exp(sum / count) : count / sum;

  const auto [min_it, max_it] = std::minmax_element(positive.begin(), positive.end());
  const double log_min_full = std::log2(*min_it), log_max_full = std::log2(*max_it);
  const double log_min = std::log2(percentile(positive, 0.01));
  const double log_max = std::log2(percentile(positive, 0.99));
  const double log_mean = std::log2(parameters.mean);
  // A (nearly) flat luminance distribution has no key to estimate: the exponent's denominator would be 0.
  if (log_max - log_min > 1e-9)
    parameters.alpha = 0.18 * std::pow(4.0, (2.0 * log_mean - log_min - log_max) / (log_max - log_min));
  parameters.l_white = 1.5 * std::exp2(log_max_full - log_min_full - 5.0);
  return parameters;
}

}  // namespace blocklab
