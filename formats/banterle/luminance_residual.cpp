// The 8 bpp luminance residual: range fit and per-block alpha encoding (formats/banterle/luminance_residual.h).
#include "formats/banterle/luminance_residual.h"

#include <algorithm>
#include <cmath>

#include "formats/bc4/bc4_encoder.h"

namespace blocklab {

namespace {

constexpr std::size_t kMaxRangeSamples = 16384;
constexpr int kStepCandidates = 48;   // half-stop steps: 24 stops below the full-range step
constexpr float kFloor = 5.9604645e-08f;   // 2^-24

double floored_log2(float value) { return std::log2(static_cast<double>(value > kFloor ? value : kFloor)); }

// The decoder's luminance of one texel: total = reconstructed + residual, negative -> 0 (itmo_lut.h).
float decoded_luminance(float reconstructed, float residual) {
  const float total = reconstructed + residual;
  return total > 0.0f ? total : 0.0f;
}

}  // namespace

double residual_log2_error(float original, float reconstructed, float residual) {
  const double difference = floored_log2(original) - floored_log2(decoded_luminance(reconstructed, residual));
  return difference * difference;
}

ResidualRange fit_residual_range(const std::vector<float>& original, const std::vector<float>& reconstructed) {
  const std::size_t count = original.size();
  ResidualRange best;   // lo = hi = 0: no residual
  if (count == 0) return best;
  const std::size_t stride = (count + kMaxRangeSamples - 1) / kMaxRangeSamples;
  std::vector<float> sample_original, sample_reconstructed, delta;
  for (std::size_t i = 0; i < count; i += stride) {
    sample_original.push_back(original[i]);
    sample_reconstructed.push_back(reconstructed[i]);
    delta.push_back(original[i] - reconstructed[i]);
  }
  const auto evaluate = [&](const ResidualRange& range) {
    const double span = static_cast<double>(range.hi) - static_cast<double>(range.lo);
    double sum = 0.0;
    for (std::size_t i = 0; i < delta.size(); ++i) {
      float residual = 0.0f;
      if (span > 0.0) {
        // Linear quantisation to the nearest of the 256 codes, residuals outside the range clipped.
        const double code = std::clamp(std::floor((delta[i] - range.lo) / span * 255.0 + 0.5), 0.0, 255.0);
        residual = dequantise_residual(range, static_cast<float>(code / 255.0));
      }
      sum += residual_log2_error(sample_original[i], sample_reconstructed[i], residual);
    }
    return sum;
  };
  double best_error = evaluate(best);
  const auto [min_it, max_it] = std::minmax_element(delta.begin(), delta.end());
  const double delta_min = std::min(0.0, static_cast<double>(*min_it));
  const double delta_max = std::max(0.0, static_cast<double>(*max_it));
  const double span = delta_max - delta_min;
  // Every residual is 0 (or the sample is empty): nothing to store.
  if (!(span > 0.0)) return best;
  const int proportional = static_cast<int>(std::lround(-delta_min / span * 255.0));
  const int zero_codes[] = {proportional, 0, 32, 128, 224, 255};
  for (int j = 0; j < kStepCandidates; ++j) {
    const double step = span / 255.0 * std::exp2(-0.5 * j);
    for (int k0 : zero_codes) {
      ResidualRange range;
      range.lo = static_cast<float>(-k0 * step);
      range.hi = static_cast<float>((255 - k0) * step);
      const double error = evaluate(range);
      if (error < best_error) {   // strict: ties keep the earlier (coarser, simpler) candidate
        best_error = error;
        best = range;
      }
    }
  }
  return best;
}

Bc4Params encode_residual_block(const float original[16], const float reconstructed[16], const ResidualRange& range,
                                S3tcSearch search) {
  const double span = static_cast<double>(range.hi) - static_cast<double>(range.lo);
  float targets[16];
  for (int texel = 0; texel < 16; ++texel) {
    const double delta = static_cast<double>(original[texel]) - static_cast<double>(reconstructed[texel]);
    // No range (no residual stored): every target is code 0, which dequantises to lo = 0.
    targets[texel] = span > 0.0 ? static_cast<float>(std::clamp((delta - range.lo) / span * 255.0, 0.0, 255.0)) : 0.0f;
  }
  Bc4Params params = fit_bc4_block(targets, search);
  double palette[8];
  bc4_palette(static_cast<double>(params.endpoints[0]), static_cast<double>(params.endpoints[1]), params.mode, palette);
  float residuals[8];
  // The decoder's residual for each palette entry: the alpha value as float, then dequantised in float.
  for (int k = 0; k < 8; ++k) residuals[k] = dequantise_residual(range, static_cast<float>(palette[k]));
  for (int texel = 0; texel < 16; ++texel) {
    int best_index = 0;
    double best_error = residual_log2_error(original[texel], reconstructed[texel], residuals[0]);
    for (int k = 1; k < 8; ++k) {
      const double error = residual_log2_error(original[texel], reconstructed[texel], residuals[k]);
      if (error < best_error) {   // ties keep the lower index
        best_error = error;
        best_index = k;
      }
    }
    params.indices[static_cast<std::size_t>(texel)] = static_cast<std::uint8_t>(best_index);
  }
  return params;
}

}  // namespace blocklab
