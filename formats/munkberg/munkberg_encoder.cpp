// The per-block encoder of the `munkberg` format (formats/munkberg/munkberg_encoder.h; Munkberg et al. 2008,
// sections 3.1, 5, 6 and 7).
#include "formats/munkberg/munkberg_encoder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "formats/munkberg/munkberg_color_spaces.h"
#include "formats/munkberg/munkberg_log_error.h"
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
  return block_log2_error(texel_log2(source), decoded);
}

double block_log2_error(const TexelLog2& source_log2, const BlockTexels& decoded) {
  double sum = 0.0;
  for (int i = 0; i < kTexels; ++i)
    for (int c = 0; c < 3; ++c) {
      const double a = metric_log2(decoded.rgba[i][c]);
      const double b = source_log2[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)];
      sum += (a - b) * (a - b);
    }
  return sum;
}

namespace {

Rgb<double> texel_rgb(const BlockTexels& texels, int i) {
  return {static_cast<double>(texels.rgba[i][0]), static_cast<double>(texels.rgba[i][1]),
          static_cast<double>(texels.rgba[i][2])};
}

// block_targets' entries for texel i, whose logYuv is `yuv`.
void texel_targets(const Rgb<double>& rgb, const LogYuv<double>& yuv, int i, double log_luminance[kTexels],
                   ChromaPoints* chroma) {
  // True black (Y == 0; the input policy guarantees non-negative channels): eq. (3)'s black level, no chroma.
  const bool black = rgb.r == 0.0 && rgb.g == 0.0 && rgb.b == 0.0;
  log_luminance[i] = black ? kBlackLog2 : std::min(kLogLumMax, std::max(kBlackLog2, yuv.log_luminance));
  const std::size_t ii = static_cast<std::size_t>(i);
  // u, v are in [0, 1] for non-negative RGB; the clamp only removes rounding overshoot.
  chroma->point[ii] = {std::min(1.0, std::max(0.0, yuv.u)), std::min(1.0, std::max(0.0, yuv.v))};
  chroma->weight[ii] = black ? 0.0 : 1.0;
}

}  // namespace

void block_targets(const BlockTexels& texels, double log_luminance[kTexels], ChromaPoints* chroma) {
  for (int i = 0; i < kTexels; ++i) {
    const Rgb<double> rgb = texel_rgb(texels, i);
    texel_targets(rgb, rgb_to_logyuv(rgb), i, log_luminance, chroma);
  }
}

BlockAnalysis analyse_block(const BlockTexels& texels) {
  BlockAnalysis analysis;
  analysis.source_log2 = texel_log2(texels);
  for (int i = 0; i < kTexels; ++i) {
    const Rgb<double> rgb = texel_rgb(texels, i);
    const LogYuv<double> yuv = rgb_to_logyuv(rgb);
    texel_targets(rgb, yuv, i, analysis.log_luminance.data(), &analysis.chroma);
    analysis.source_log_luminance[static_cast<std::size_t>(i)] = yuv.log_luminance;
  }
  return analysis;
}

double assign_chroma_indices_log2(const TexelLog2& source_log2, const ShapeSet& shapes, Params* params) {
  // The exact error of a texel on a landmark needs the decoded float channel's log2 (3 libm calls). Most groups have
  // one clear best landmark, so each (texel, landmark) is first scored in the log domain, where a channel's log2 is
  // model = max(log2 f_c + log2 Y - log2 w_c, -24) with one log2 per landmark channel; only the landmarks the model
  // cannot rule out are decoded. |exact log2 - model| <= kModelSlack per channel: the float rounding of the decoded
  // value (2^-24 relative, 8.6e-8 in log2) plus double rounding (< 1e-13 for |log2| <= 64); the floor at -24 is
  // 1-Lipschitz. A channel d = model - s then has an exact squared error within 2 |d| kModelSlack + kModelSlack^2.
  constexpr double kModelSlack = 1e-6;
  const Mode mode = params->mode;
  const int n = lum_levels_minus_one(mode);
  const std::array<double, 6> x = decode_parameters(*params);
  double landmark_u[kShapeLandmarkCount], landmark_v[kShapeLandmarkCount];
  decode_landmarks(shapes.shapes[static_cast<std::size_t>(params->shape)], x.data() + 2, landmark_u, landmark_v);
  double luminance[kTexels], log_luminance[kTexels];
  bool black[kTexels];
  for (int i = 0; i < kTexels; ++i) {
    const int l = params->lum_index[static_cast<std::size_t>(i)];
    const std::int64_t q = static_cast<std::int64_t>(n - l) * params->lum[0] + static_cast<std::int64_t>(l) * params->lum[1];
    black[i] = q == 0;   // eq. (3): every channel decodes to 0, i.e. exactly -24, on any landmark
    luminance[i] = decode_texel_luminance(*params, x.data(), i);
    log_luminance[i] = black[i] ? 0.0 : log_luminance_of_numerator(q, n);
  }
  const std::array<double, 3>& log2_weight = log2_rec601_weights();
  double log_factor[kShapeLandmarkCount][3];
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const double u = landmark_u[k], v = landmark_v[k];
    const double factor[3] = {v, std::max(0.0, 1.0 - u - v), u};   // decode_texel_rgb's factors
    for (int c = 0; c < 3; ++c) log_factor[k][c] = std::log2(std::max(factor[c], kFactorFloor));
  }
  // The exact decoded log2 of texel i on landmark k, computed on first use.
  double decoded_log2[kTexels][kShapeLandmarkCount][3];
  bool decoded[kTexels][kShapeLandmarkCount] = {};
  const auto exact = [&](int i, int k, int c) {
    if (!decoded[i][k]) {
      double rgb[3];
      decode_texel_rgb(landmark_u[k], landmark_v[k], luminance[i], rgb);
      for (int cc = 0; cc < 3; ++cc) decoded_log2[i][k][cc] = metric_log2(static_cast<float>(rgb[cc]));
      decoded[i][k] = true;
    }
    const double d = decoded_log2[i][k][c] - source_log2[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)];
    return d * d;
  };
  // The texels of group g are g * per_group .. (munkberg_layout.h: chroma_group_of_texel).
  const int per_group = kTexels / chroma_groups(mode);
  const auto exact_group_error = [&](int g, int k) {
    double error = 0.0;
    for (int i = g * per_group; i < (g + 1) * per_group; ++i)
      for (int c = 0; c < 3; ++c) error += exact(i, k, c);
    return error;
  };
  // Per group the landmark whose texels (in texel order, then R, G, B) have the smallest exact error; ties keep the
  // lower. A landmark whose model error minus its slack is above another's model error plus slack cannot be it.
  for (int g = 0; g < chroma_groups(mode); ++g) {
    double low[kShapeLandmarkCount], high[kShapeLandmarkCount];
    double best_high = std::numeric_limits<double>::infinity();
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      double model = 0.0, slack = 0.0;
      for (int i = g * per_group; i < (g + 1) * per_group; ++i) {
        for (int c = 0; c < 3; ++c) {
          const double s = source_log2[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)];
          if (black[i]) {   // exact: decodes to 0 whatever the landmark
            model += (kLog2MetricFloor - s) * (kLog2MetricFloor - s);
            continue;
          }
          const double channel = log_factor[k][c] + log_luminance[i] - log2_weight[static_cast<std::size_t>(c)];
          const double d = std::max(channel, kLog2MetricFloor) - s;
          model += d * d;
          slack += 2.0 * std::abs(d) * kModelSlack + kModelSlack * kModelSlack;
        }
      }
      // 1e-12 relative: the rounding of these sums themselves.
      low[k] = (model - slack) * (1.0 - 1e-12);
      high[k] = (model + slack) * (1.0 + 1e-12);
      best_high = std::min(best_high, high[k]);
    }
    int best = -1;
    double best_error = 0.0;
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      // (NaN model values are not ruled out: such a landmark is decoded like any other.)
      if (low[k] > best_high) continue;
      const double error = exact_group_error(g, k);
      if (best < 0 || error < best_error) {
        best = k;
        best_error = error;
      }
    }
    params->chroma_index[static_cast<std::size_t>(g)] = static_cast<std::uint8_t>(best);
  }
  // The block's error in block_log2_error's order of additions (every chosen landmark's texels are decoded).
  double sum = 0.0;
  for (int i = 0; i < kTexels; ++i) {
    const int k = params->chroma_index[static_cast<std::size_t>(chroma_group_of_texel(mode, i))];
    for (int c = 0; c < 3; ++c) sum += exact(i, k, c);
  }
  return sum;
}

ChromaLogTargets chroma_log_targets(const TexelLog2& source_log2, Mode mode, const LuminanceFit& luminance) {
  ChromaLogTargets targets;
  const int n = lum_levels_minus_one(mode);
  for (int i = 0; i < kTexels; ++i) {
    const std::size_t ii = static_cast<std::size_t>(i);
    const int l = luminance.index[ii];
    const std::int64_t q = static_cast<std::int64_t>(n - l) * luminance.lum[0] + static_cast<std::int64_t>(l) * luminance.lum[1];
    targets.black[ii] = q == 0;   // eq. (3)
    targets.log2_luminance[ii] = q == 0 ? kBlackLog2 : log_luminance_of_numerator(q, n);
  }
  targets.source_log2 = source_log2;
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

void luminance_texel_bounds(const BlockTexels& texels, const BlockAnalysis& analysis, const bool black[kTexels],
                            const double decoded_log2[kTexels], double texel_bound[kTexels]) {
  // Slack for the float rounding of decoded channels (2^-24 relative ~ 8.6e-8 in log2) and exp2 / the source
  // luminance sum (a few 1e-16): a decoded channel's log2 is within 1e-6 of its exact value.
  constexpr double kSlack = 1e-6;
  const TexelLog2& source_log2 = analysis.source_log2;
  for (int i = 0; i < kTexels; ++i) {
    const std::size_t ii = static_cast<std::size_t>(i);
    texel_bound[i] = 0.0;
    bool above_floor = true;
    for (int c = 0; c < 3; ++c) above_floor = above_floor && static_cast<double>(texels.rgba[i][c]) > kMetricValueFloor;
    if (black[i]) {
      // Decoded true black: every channel decodes to 0 -> log2 2^-24 = -24, whatever the chroma (exact term).
      for (int c = 0; c < 3; ++c) texel_bound[i] += (kBlackLog2 - source_log2[i][c]) * (kBlackLog2 - source_log2[i][c]);
      continue;
    }
    if (!above_floor) continue;   // a floored source channel breaks the ratio argument: no luminance term
    const double delta = decoded_log2[i] - analysis.source_log_luminance[ii];
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
}

double shape_mode_lower_bound(const BlockTexels& texels, const BlockAnalysis& analysis, Mode mode,
                              const EncoderSettings& settings, LuminanceFit* luminance_out) {
  const LuminanceFit luminance = fit_luminance(mode, analysis.log_luminance.data(), settings.luma_radius);
  if (luminance_out != nullptr) *luminance_out = luminance;
  // The shared-factor term's slack (luminance_texel_bounds' kSlack).
  constexpr double kSlack = 1e-6;
  const int n = lum_levels_minus_one(mode);
  double texel_bound[kTexels] = {};
  double decoded_log2[kTexels] = {};
  const TexelLog2& source_log2 = analysis.source_log2;
  bool black[kTexels] = {};
  for (int i = 0; i < kTexels; ++i) {
    const std::size_t ii = static_cast<std::size_t>(i);
    const int l = luminance.index[ii];
    const std::int64_t q = static_cast<std::int64_t>(n - l) * luminance.lum[0] + static_cast<std::int64_t>(l) * luminance.lum[1];
    black[i] = q == 0;
    if (!black[i]) decoded_log2[i] = log_luminance_of_numerator(q, n);
  }
  luminance_texel_bounds(texels, analysis, black, decoded_log2, texel_bound);
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
          s[j] = source_log2[static_cast<std::size_t>(g * per_group + j)][static_cast<std::size_t>(c)];
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

Params encode_mode(const BlockTexels& texels, const BlockAnalysis& analysis, Mode mode, const ShapeSet& shapes,
                   const EncoderSettings& settings, std::uint64_t block_seed, ShapeSolveCache* cache,
                   const LuminanceFit* known_luminance, double* block_error, ChromaWorkspace* workspace) {
  const LuminanceFit luminance = known_luminance != nullptr
                                     ? *known_luminance
                                     : fit_luminance(mode, analysis.log_luminance.data(), settings.luma_radius);
  ChromaLogTargets targets = chroma_log_targets(analysis.source_log2, mode, luminance);
  if (settings.error != HdrBlockError::log2_floor) targets.set_error_weights(texels, settings.error);
  const ChromaFit fit =
      fit_chroma(analysis.chroma, mode, shapes, settings.chroma, block_seed, &targets, cache, workspace);
  Params params;
  params.mode = mode;
  params.shape = fit.shape;
  params.base = fit.base;
  params.lum = luminance.lum;
  params.lum_index = luminance.index;
  params.chroma_index = fit.index;
  double error = 0.0;
  if (settings.index_metric == IndexMetric::log2rgb) {
    error = assign_chroma_indices_log2(analysis.source_log2, shapes, &params);
  } else if (block_error != nullptr) {
    error = block_log2_error(analysis.source_log2, decode_params(params, shapes));
  }
  // Shape I stores texel 0's index in 2 bits: the endpoints swap and the indices mirror, the decoded texels (and so
  // the error) do not change.
  canonicalize_anchor(&params);
  if (block_error != nullptr) *block_error = error;
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
