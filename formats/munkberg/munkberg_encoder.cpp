// The per-block encoder of the `munkberg` format (formats/munkberg/munkberg_encoder.h; Munkberg et al. 2008,
// sections 3.1, 5, 6 and 7).
#include "formats/munkberg/munkberg_encoder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/color_spaces.h"
#include "formats/munkberg/munkberg_luminance.h"

namespace blocklab::munkberg {

TexelLog2 texel_log2(const BlockTexels& texels) {
  TexelLog2 out{};
  for (int i = 0; i < kTexels; ++i)
    for (int c = 0; c < 3; ++c)
      out[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)] = metric_log2(texels.rgba[i][c]);
  return out;
}

double block_log2_error(const BlockTexels& source, const BlockTexels& decoded) {
  double sum = 0.0;
  for (int i = 0; i < kTexels; ++i)
    for (int c = 0; c < 3; ++c) {
      const double a = metric_log2(decoded.rgba[i][c]);
      const double b = metric_log2(source.rgba[i][c]);
      sum += (a - b) * (a - b);
    }
  return sum;
}

void block_targets(const BlockTexels& texels, double log_luminance[kTexels], ChromaPoints* chroma) {
  for (int i = 0; i < kTexels; ++i) {
    const Rgb<double> rgb{static_cast<double>(texels.rgba[i][0]), static_cast<double>(texels.rgba[i][1]),
                          static_cast<double>(texels.rgba[i][2])};
    const LogYuv<double> yuv = rgb_to_logyuv(rgb);
    // True black (Y == 0; the input policy guarantees non-negative channels): eq. (3)'s black level, no chroma.
    const bool black = rgb.r == 0.0 && rgb.g == 0.0 && rgb.b == 0.0;
    log_luminance[i] = black ? kBlackLog2 : std::min(kLogLumMax, std::max(kBlackLog2, yuv.log_luminance));
    const std::size_t ii = static_cast<std::size_t>(i);
    // u, v are in [0, 1] for non-negative RGB; the clamp only removes rounding overshoot.
    chroma->point[ii] = {std::min(1.0, std::max(0.0, yuv.u)), std::min(1.0, std::max(0.0, yuv.v))};
    chroma->weight[ii] = black ? 0.0 : 1.0;
  }
}

void assign_chroma_indices_log2(const BlockTexels& texels, const ShapeSet& shapes, Params* params) {
  // The block decoded once per landmark (every group on landmark k), then per group the landmark whose decoded
  // texels have the smallest log2[RGB] error; ties keep the lower landmark.
  std::array<BlockTexels, kShapeLandmarkCount> decoded;
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    Params trial = *params;
    for (int g = 0; g < chroma_groups(params->mode); ++g) trial.chroma_index[static_cast<std::size_t>(g)] = static_cast<std::uint8_t>(k);
    decoded[static_cast<std::size_t>(k)] = decode_params(trial, shapes);
  }
  // The source's log2 once per texel and channel (the same values the comparison below used to recompute per landmark).
  const TexelLog2 source_log2 = texel_log2(texels);
  for (int g = 0; g < chroma_groups(params->mode); ++g) {
    int best = 0;
    double best_error = 0.0;
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      double error = 0.0;
      for (int i = 0; i < kTexels; ++i) {
        if (chroma_group_of_texel(params->mode, i) != g) continue;
        for (int c = 0; c < 3; ++c) {
          const double a = metric_log2(decoded[static_cast<std::size_t>(k)].rgba[i][c]);
          const double b = source_log2[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)];
          error += (a - b) * (a - b);
        }
      }
      if (k == 0 || error < best_error) {
        best = k;
        best_error = error;
      }
    }
    params->chroma_index[static_cast<std::size_t>(g)] = static_cast<std::uint8_t>(best);
  }
}

ChromaLogTargets chroma_log_targets(const BlockTexels& texels, Mode mode, const LuminanceFit& luminance) {
  ChromaLogTargets targets;
  const int n = lum_levels_minus_one(mode);
  for (int i = 0; i < kTexels; ++i) {
    const std::size_t ii = static_cast<std::size_t>(i);
    const int l = luminance.index[ii];
    const std::int64_t q = static_cast<std::int64_t>(n - l) * luminance.lum[0] + static_cast<std::int64_t>(l) * luminance.lum[1];
    targets.black[ii] = q == 0;   // eq. (3)
    targets.log2_luminance[ii] = q == 0 ? kBlackLog2 : log_luminance_of_numerator(q, n);
  }
  targets.source_log2 = texel_log2(texels);
  return targets;
}

namespace {

// Minimum over a shared log2 chroma factor L (any real, or -infinity for a zero factor) of
// sum_i (max(y_i + L, -24) - s_i)^2 for the texels of one chroma group: the smallest error one channel of the group
// can have when its texels share a landmark (decoded log2 = max(y_i + log2 f_c - log2 w_c, -24)). The function is a
// quadratic on each interval between the floor breakpoints L = -24 - y_i, so its minimum is at a breakpoint, at an
// interval's clipped quadratic optimum, or at -infinity (all floored).
double shared_factor_minimum(const double* y, const double* s, int count) {
  const auto value = [&](double L) {
    double sum = 0.0;
    for (int i = 0; i < count; ++i) {
      const double d = std::max(y[i] + L, kBlackLog2) - s[i];
      sum += d * d;
    }
    return sum;
  };
  double best = 0.0;
  for (int i = 0; i < count; ++i) best += (kBlackLog2 - s[i]) * (kBlackLog2 - s[i]);   // L -> -infinity
  // Breakpoints, sorted; on [b_k, b_k+1) the texels with breakpoint <= L are unfloored.
  double breaks[kTexels];
  for (int i = 0; i < count; ++i) breaks[i] = kBlackLog2 - y[i];
  std::sort(breaks, breaks + count);
  for (int k = 0; k < count; ++k) {
    best = std::min(best, value(breaks[k]));
    // Unfloored on [breaks[k], next): the texels with kBlackLog2 - y_i <= breaks[k]; optimum = mean of s_i - y_i.
    double sum = 0.0;
    int unfloored = 0;
    for (int i = 0; i < count; ++i)
      if (kBlackLog2 - y[i] <= breaks[k]) {
        sum += s[i] - y[i];
        ++unfloored;
      }
    const double next = k + 1 < count ? breaks[k + 1] : std::numeric_limits<double>::infinity();
    best = std::min(best, value(std::min(next, std::max(breaks[k], sum / unfloored))));
  }
  return best;
}

}  // namespace

double shape_mode_lower_bound(const BlockTexels& texels, Mode mode, const EncoderSettings& settings,
                              LuminanceFit* luminance_out) {
  double log_luminance[kTexels];
  ChromaPoints chroma;
  block_targets(texels, log_luminance, &chroma);
  const LuminanceFit luminance = fit_luminance(mode, log_luminance, settings.luma_radius);
  if (luminance_out != nullptr) *luminance_out = luminance;
  // Slack for the float rounding of decoded channels (2^-24 relative ~ 8.6e-8 in log2) and exp2 / the source
  // luminance sum (a few 1e-16): a decoded channel's log2 is within 1e-6 of its exact value.
  constexpr double kSlack = 1e-6;
  const int n = lum_levels_minus_one(mode);
  double texel_bound[kTexels] = {};
  double decoded_log2[kTexels] = {};
  double source_log2[kTexels][3];
  bool black[kTexels] = {};
  for (int i = 0; i < kTexels; ++i) {
    const std::size_t ii = static_cast<std::size_t>(i);
    const int l = luminance.index[ii];
    const std::int64_t q = static_cast<std::int64_t>(n - l) * luminance.lum[0] + static_cast<std::int64_t>(l) * luminance.lum[1];
    bool above_floor = true;
    for (int c = 0; c < 3; ++c) {
      const double value = static_cast<double>(texels.rgba[i][c]);
      source_log2[i][c] = metric_log2(value);
      above_floor = above_floor && value > kMetricValueFloor;
    }
    black[i] = q == 0;
    if (black[i]) {
      // Decoded true black: every channel decodes to 0 -> log2 2^-24 = -24, whatever the chroma (exact term).
      for (int c = 0; c < 3; ++c) texel_bound[i] += (kBlackLog2 - source_log2[i][c]) * (kBlackLog2 - source_log2[i][c]);
      continue;
    }
    decoded_log2[i] = log_luminance_of_numerator(q, n);
    if (!above_floor) continue;   // a floored source channel breaks the ratio argument: no luminance term
    const Rgb<double> rgb{static_cast<double>(texels.rgba[i][0]), static_cast<double>(texels.rgba[i][1]),
                          static_cast<double>(texels.rgba[i][2])};
    const double delta = decoded_log2[i] - rgb_to_logyuv(rgb).log_luminance;
    if (delta > kSlack) {
      texel_bound[i] = (delta - kSlack) * (delta - kSlack);
    } else if (delta < -kSlack) {
      // Decoded darker: some channel's ratio is <= 2^delta (if u + v <= 1) unless the decoded channel is floored at
      // 2^-24 (then its log2 error is -24 - s_c < 0); if u + v > 1 green decodes to 0 (error -24 - s_G). Either
      // way some channel's squared error is >= min(delta^2, min_c (24 + s_c)^2).
      double reach = -delta - kSlack;
      for (int c = 0; c < 3; ++c) reach = std::min(reach, -kBlackLog2 + source_log2[i][c] - kSlack);
      if (reach > 0.0) texel_bound[i] = reach * reach;
    }
  }
  // Per chroma group: its texels' luminance terms, or, when the group shares one landmark over several non-black
  // texels (shape II pairs), the shared-factor minimum per channel if larger (both bound the same error terms).
  double bound = 0.0;
  const int groups = chroma_groups(mode);
  const int per_group = kTexels / groups;
  for (int g = 0; g < groups; ++g) {
    double texels_sum = 0.0;
    bool any_black = false;
    for (int j = 0; j < per_group; ++j) {
      texels_sum += texel_bound[g * per_group + j];
      any_black = any_black || black[g * per_group + j];
    }
    double shared = 0.0;
    if (per_group > 1 && !any_black) {
      for (int c = 0; c < 3; ++c) {
        double y[kTexels], s[kTexels];
        for (int j = 0; j < per_group; ++j) {
          y[j] = decoded_log2[g * per_group + j];
          s[j] = source_log2[g * per_group + j][c];
        }
        // Each decoded log2 may be off by kSlack: the residual vector moves by at most kSlack sqrt(count).
        const double root = std::sqrt(shared_factor_minimum(y, s, per_group)) - kSlack * std::sqrt(static_cast<double>(per_group));
        if (root > 0.0) shared += root * root;
      }
    }
    bound += std::max(texels_sum, shared);
  }
  return bound * (1.0 - 1e-9);
}

Params encode_mode(const BlockTexels& texels, Mode mode, const ShapeSet& shapes, const EncoderSettings& settings,
                   std::uint64_t block_seed, ShapeSolveCache* cache, const LuminanceFit* known_luminance) {
  double log_luminance[kTexels];
  ChromaPoints chroma;
  block_targets(texels, log_luminance, &chroma);
  const LuminanceFit luminance =
      known_luminance != nullptr ? *known_luminance : fit_luminance(mode, log_luminance, settings.luma_radius);
  const ChromaLogTargets targets = chroma_log_targets(texels, mode, luminance);
  const ChromaFit fit = fit_chroma(chroma, mode, shapes, settings.chroma, block_seed, &targets, cache);
  Params params;
  params.mode = mode;
  params.shape = fit.shape;
  params.base = fit.base;
  params.lum = luminance.lum;
  params.lum_index = luminance.index;
  params.chroma_index = fit.index;
  if (settings.index_metric == IndexMetric::log2rgb) assign_chroma_indices_log2(texels, shapes, &params);
  canonicalize_anchor(&params);   // shape I stores texel 0's index in 2 bits (decoding unchanged)
  return params;
}

Params encode_block(const BlockTexels& texels, const ShapeSet& shapes, const EncoderSettings& settings,
                    std::uint64_t block_seed, double* error) {
  Params best;
  double best_error = 0.0;
  bool have = false;
  // No shape mode enabled (e.g. modes=ext_s3tc only): both compete here; the caller decides what to use.
  const bool none = !settings.modes[0] && !settings.modes[1];
  for (const Mode mode : {Mode::shape_ii, Mode::shape_i}) {
    if (!none && !settings.modes[static_cast<std::size_t>(mode)]) continue;
    const Params params = encode_mode(texels, mode, shapes, settings, block_seed);
    const double e = block_log2_error(texels, decode_params(params, shapes));
    // Strict: ties keep shape II (tried first). A NaN error never wins (cannot happen for finite input).
    if (!have || e < best_error) {
      best = params;
      best_error = e;
      have = true;
    }
  }
  if (error != nullptr) *error = best_error;
  return best;
}

}  // namespace blocklab::munkberg
