// The 8 bpp luminance residual: range fit and per-block alpha encoding (formats/banterle/luminance_residual.h).
#include "formats/banterle/luminance_residual.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

// The decoded luminance's error as (squared log2 error, |decoded - original|): compared lexicographically, the
// second term only separates entries whose log2 errors are equal (both below the 2^-24 floor).
struct TexelCost {
  double log2_error;
  double absolute_error;
  bool operator<(const TexelCost& other) const {
    if (log2_error != other.log2_error) return log2_error < other.log2_error;
    return absolute_error < other.absolute_error;
  }
};

TexelCost texel_cost(float original, float reconstructed, float residual) {
  const double decoded = static_cast<double>(decoded_luminance(reconstructed, residual));
  return {residual_log2_error(original, reconstructed, residual), std::fabs(decoded - static_cast<double>(original))};
}

}  // namespace

bool zero_exact_residual_range(double step, int k0, ResidualRange& range) {
  const float zero_code = static_cast<float>(static_cast<double>(k0) / 255.0);   // the decoder's alpha value
  const float hi = static_cast<float>((255 - k0) * step);
  const float lo_start = static_cast<float>(-k0 * step);
  for (int distance = 0; distance <= kMaxZeroUlps; ++distance)
    for (const float direction : {1.0f, -1.0f}) {
      if (distance == 0 && direction < 0.0f) continue;   // distance 0 is one candidate
      float lo = lo_start;
      for (int i = 0; i < distance; ++i) lo = std::nextafter(lo, direction * std::numeric_limits<float>::infinity());
      const ResidualRange candidate{lo, hi};
      // A range of zero width or an inverted one (only possible for a step of a few subnormal ulps) is no range.
      if (!(lo < hi)) continue;
      if (dequantise_residual(candidate, zero_code) == 0.0f) {
        range = candidate;
        return true;
      }
    }
  return false;
}

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
      // No float range decodes this zero code to exactly 0 near the ideal one: skip it (k0 = 0 and 255 always work).
      if (!zero_exact_residual_range(step, k0, range)) continue;
      const double error = evaluate(range);
      if (error < best_error) {   // strict: ties keep the earlier (coarser, simpler) candidate
        best_error = error;
        best = range;
      }
    }
  }
  return best;
}

namespace {

// Every texel on the palette entry with the smallest TexelCost (ties keep the lower index); returns the block's
// summed cost (log2 errors summed, absolute errors summed).
TexelCost assign_residual_indices(const float original[16], const float reconstructed[16], const ResidualRange& range,
                                  Bc4Params& params) {
  double palette[8];
  bc4_palette(static_cast<double>(params.endpoints[0]), static_cast<double>(params.endpoints[1]), params.mode, palette);
  float residuals[8];
  // The decoder's residual for each palette entry: the alpha value as float, then dequantised in float.
  for (int k = 0; k < 8; ++k) residuals[k] = dequantise_residual(range, static_cast<float>(palette[k]));
  TexelCost total{0.0, 0.0};
  for (int texel = 0; texel < 16; ++texel) {
    int best_index = 0;
    TexelCost best_error = texel_cost(original[texel], reconstructed[texel], residuals[0]);
    for (int k = 1; k < 8; ++k) {
      const TexelCost error = texel_cost(original[texel], reconstructed[texel], residuals[k]);
      if (error < best_error) {   // ties (equal log2 and absolute errors) keep the lower index
        best_error = error;
        best_index = k;
      }
    }
    params.indices[static_cast<std::size_t>(texel)] = static_cast<std::uint8_t>(best_index);
    total.log2_error += best_error.log2_error;
    total.absolute_error += best_error.absolute_error;
  }
  return total;
}

}  // namespace

Bc4Params encode_residual_block(const float original[16], const float reconstructed[16], const ResidualRange& range,
                                S3tcSearch search) {
  const double span = static_cast<double>(range.hi) - static_cast<double>(range.lo);
  float targets[16], black_at_zero[16];
  bool has_lit_black = false;
  for (int texel = 0; texel < 16; ++texel) {
    const double delta = static_cast<double>(original[texel]) - static_cast<double>(reconstructed[texel]);
    // No range (no residual stored): every target is code 0, which dequantises to lo = 0.
    targets[texel] = span > 0.0 ? static_cast<float>(std::clamp((delta - range.lo) / span * 255.0, 0.0, 255.0)) : 0.0f;
    // A black source texel is decoded exactly by ANY residual <= -reconstructed (the decoder clamps the total at
    // 0), so code 0 (= lo, the 6-value mode's constant) serves it as well as its own target.
    const bool lit_black = original[texel] <= 0.0f && reconstructed[texel] > 0.0f;
    has_lit_black = has_lit_black || lit_black;
    black_at_zero[texel] = lit_black ? 0.0f : targets[texel];
  }
  Bc4Params params = fit_bc4_block(targets, search);
  TexelCost cost = assign_residual_indices(original, reconstructed, range, params);
  // Blocks where the colour half lights a black texel: the code-unit fit may leave no palette entry low enough to
  // cancel it (a leak that log2 error punishes by ~(log2 leak + 24)^2); also fit with those targets at code 0 and
  // keep the block with the smaller log2 cost (then absolute cost; the first candidate on a tie).
  if (has_lit_black && span > 0.0) {
    Bc4Params alternative = fit_bc4_block(black_at_zero, search);
    const TexelCost alternative_cost = assign_residual_indices(original, reconstructed, range, alternative);
    if (alternative_cost < cost) params = alternative;
  }
  return params;
}

}  // namespace blocklab
