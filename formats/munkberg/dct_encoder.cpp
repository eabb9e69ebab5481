// Encoder of the fixed-rate DCT mode (formats/munkberg/dct_encoder.h; Munkberg et al. 2008, section 6.2).
#include "formats/munkberg/dct_encoder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "formats/munkberg/munkberg_color_spaces.h"
#include "formats/munkberg/munkberg_encoder.h"

namespace blocklab::munkberg {

namespace {

// A decoded block's float texels and the log2 of each channel (max with the metric floor).
struct DecodedLog2 {
  BlockTexels texels;
  double log2[kTexels][3] = {};
};

// block_log2_error of `decoded` with the source's log2 computed once (the same operations in the same order, so the
// same sums), the decoded log2 reused from `reference` wherever a texel channel decodes to the same float (a trial
// changes one channel's samples), and written to `out`. Summed only while below `bound`: at or above it, a partial
// sum >= bound is returned (every term is a square); a NaN sum never stops early.
double log2_error_below(const TexelLog2& source_log2, const BlockTexels& decoded, const DecodedLog2* reference,
                        double bound, DecodedLog2* out) {
  out->texels = decoded;
  double sum = 0.0;
  for (int i = 0; i < kTexels; ++i) {
    for (int c = 0; c < 3; ++c) {
      const float value = decoded.rgba[i][c];
      const double a = reference != nullptr && reference->texels.rgba[i][c] == value
                           ? reference->log2[i][c]
                           : metric_log2(value);
      out->log2[i][c] = a;
      const double d = a - source_log2[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)];
      sum += d * d;
    }
    if (sum >= bound) return sum;
  }
  return sum;
}

DctParams quantise(const DctChannelSamples& targets, const DctTables& tables) {
  DctParams params;
  for (int c = 0; c < kDctChannelCount; ++c) {
    const std::array<double, kDctCoefficientCount> coefficients = forward_dct(targets[static_cast<std::size_t>(c)]);
    for (int k = 0; k < kDctCoefficientCount; ++k)
      params.codes[static_cast<std::size_t>(c)][static_cast<std::size_t>(k)] = static_cast<std::uint16_t>(
          dct_nearest_code(tables.channel[static_cast<std::size_t>(c)], k, coefficients[static_cast<std::size_t>(k)]));
  }
  return params;
}

// Coordinate descent over the codes: each coded coefficient one code down, then up; strict improvements only, in
// channel and coefficient order, so the result is deterministic. A trial changes one channel: only that channel's
// inverse transform is recomputed (decode_dct_params' own steps, so the same texels), and it is measured only while
// it can still beat the best.
double refine(const TexelLog2& source_log2, const DctTables& tables, int passes, DctParams* params) {
  std::array<DctChannelValues, kDctChannelCount> samples{};
  for (int c = 0; c < kDctChannelCount; ++c) samples[static_cast<std::size_t>(c)] = dct_channel_samples(*params, tables, c);
  DecodedLog2 current, trial_log2;
  double best = log2_error_below(source_log2, dct_texels_from_samples(samples), nullptr,
                                 std::numeric_limits<double>::infinity(), &current);
  for (int pass = 0; pass < passes; ++pass) {
    bool improved = false;
    for (int c = 0; c < kDctChannelCount; ++c)
      for (int k = 0; k < kDctCoefficientCount; ++k) {
        const int bits = tables.channel[static_cast<std::size_t>(c)].bits[static_cast<std::size_t>(k)];
        if (bits == 0) continue;
        const int top = (1 << bits) - 1;
        for (const int step : {-1, 1}) {
          const int code = params->codes[static_cast<std::size_t>(c)][static_cast<std::size_t>(k)] + step;
          if (code < 0 || code > top) continue;
          DctParams trial = *params;
          trial.codes[static_cast<std::size_t>(c)][static_cast<std::size_t>(k)] = static_cast<std::uint16_t>(code);
          std::array<DctChannelValues, kDctChannelCount> trial_samples = samples;
          trial_samples[static_cast<std::size_t>(c)] = dct_channel_samples(trial, tables, c);
          const double e =
              log2_error_below(source_log2, dct_texels_from_samples(trial_samples), &current, best, &trial_log2);
          if (e < best) {
            best = e;
            *params = trial;
            samples = trial_samples;
            std::swap(current, trial_log2);
            improved = true;
          }
        }
      }
    if (!improved) break;
  }
  return best;
}

}  // namespace

DctChannelSamples dct_block_targets(const BlockTexels& texels, double black_target) {
  DctChannelSamples out{};
  for (int i = 0; i < kTexels; ++i) {
    const std::size_t ii = static_cast<std::size_t>(i);
    const Rgb<double> rgb{static_cast<double>(texels.rgba[i][0]), static_cast<double>(texels.rgba[i][1]),
                          static_cast<double>(texels.rgba[i][2])};
    const LogYuv<double> yuv = rgb_to_logyuv(rgb);
    // Y <= 2^-16 cannot be stored above the bottom of the range, which is true black: aim at black.
    out[0][ii] = yuv.log_luminance <= kLogLumMin ? black_target : std::min(kLogLumMax, yuv.log_luminance);
    out[1][ii] = yuv.u;
    out[2][ii] = yuv.v;
  }
  return out;
}

unsigned dct_nearest_code(const DctChannelTable& table, int k, double value) {
  const int bits = table.bits[static_cast<std::size_t>(k)];
  if (bits == 0) return 0;
  if (k == 0) {
    const double steps = static_cast<double>((1 << bits) - 1);
    const double scaled = (value - table.dc_min) / (table.dc_max - table.dc_min) * steps;
    // Outside the range (targets are inside, so only rounding): the nearest end.
    return static_cast<unsigned>(std::min(steps, std::max(0.0, std::nearbyint(scaled))));
  }
  const std::vector<double>& levels = table.levels[static_cast<std::size_t>(k)];
  const auto above = std::lower_bound(levels.begin(), levels.end(), value);
  if (above == levels.begin()) return 0;
  if (above == levels.end()) return static_cast<unsigned>(levels.size() - 1);
  const auto below = above - 1;
  // Ties go to the lower level.
  return static_cast<unsigned>((value - *below <= *above - value ? below : above) - levels.begin());
}

DctParams encode_dct(const BlockTexels& texels, const DctTables& tables, int refine_passes, double* error) {
  const TexelLog2 source_log2 = texel_log2(texels);
  const DctChannelSamples targets = dct_block_targets(texels, kDctBlackTarget);
  const bool has_black = std::find(targets[0].begin(), targets[0].end(), kDctBlackTarget) != targets[0].end();
  DctParams best = quantise(targets, tables);
  double best_error = refine(source_log2, tables, refine_passes, &best);
  if (has_black) {
    DctParams low = quantise(dct_block_targets(texels, kDctBlackTargetLow), tables);
    const double low_error = refine(source_log2, tables, refine_passes, &low);
    if (low_error < best_error) {   // strict: ties keep the first
      best = low;
      best_error = low_error;
    }
  }
  if (error != nullptr) *error = block_log2_error(texels, decode_dct_params(best, tables));
  return best;
}

}  // namespace blocklab::munkberg
