// Optimal BC1/BC3 endpoints for a single colour (formats/common/s3tc_color_fit.h, step 1).
//
// A flat block is reproduced best not by its nearest 565 endpoint but by an interpolated palette entry: the 2/3
// point (2 E0 + E1) / 3 of the 4-colour palette (code 2) or the midpoint (E0 + E1) / 2 of the 3-colour palette
// (code 2) can hit 8-bit values that no bit-replicated 565 value equals. The channels are independent, so one
// table per channel width and mode, built once by trying every endpoint pair (32^2 or 64^2 pairs x 256 values),
// gives the optimum under the reference decoding (exact fractions). Ties prefer the closest endpoints, whose
// interpolant differs least between vendor decoders (SPECS.md 2.1 rounding rules).
#include <array>
#include <cmath>
#include <cstdlib>

#include "formats/common/s3tc_color_fit.h"

namespace blocklab {

namespace {

struct SingleColorEntry {
  std::uint8_t endpoint0 = 0, endpoint1 = 0;
};

// table[v] for 8-bit value v: the endpoint pair whose code-2 entry is closest to v.
using SingleColorTable = std::array<SingleColorEntry, 256>;

SingleColorTable build_table(int channel, Bc1Mode mode) {
  SingleColorTable table;
  const int max_value = rgb565_channel_max(channel);
  const PaletteWeights weights = bc1_palette_weights(mode, 2);
  for (int target = 0; target < 256; ++target) {
    double best_error = 1e30;
    int best_spread = 1 << 30;
    for (int q0 = 0; q0 <= max_value; ++q0) {
      for (int q1 = 0; q1 <= max_value; ++q1) {
        const int e0 = expand_565_channel(q0, channel), e1 = expand_565_channel(q1, channel);
        const double value = static_cast<double>(weights.w0 * e0 + weights.w1 * e1) / weights.d;
        const double error = std::fabs(value - target);
        const int spread = std::abs(e0 - e1);
        // Smaller error wins; at equal error the closer endpoints win (1e-9: errors are multiples of 1/6).
        if (error < best_error - 1e-9 || (std::fabs(error - best_error) <= 1e-9 && spread < best_spread)) {
          best_error = error;
          best_spread = spread;
          table[target] = {static_cast<std::uint8_t>(q0), static_cast<std::uint8_t>(q1)};
        }
      }
    }
  }
  return table;
}

const SingleColorTable& table_for(int channel, Bc1Mode mode) {
  // Built on first use (thread-safe function-local statics); R and B share the 5-bit tables.
  static const SingleColorTable five_four = build_table(0, Bc1Mode::four_color);
  static const SingleColorTable six_four = build_table(1, Bc1Mode::four_color);
  static const SingleColorTable five_three = build_table(0, Bc1Mode::three_color);
  static const SingleColorTable six_three = build_table(1, Bc1Mode::three_color);
  if (mode == Bc1Mode::four_color) return channel == 1 ? six_four : five_four;
  return channel == 1 ? six_three : five_three;
}

}  // namespace

ColorCandidate single_color_candidate(const float rgb[3], Bc1Mode mode) {
  ColorCandidate candidate;
  candidate.mode = mode;
  for (int channel = 0; channel < 3; ++channel) {
    // Non-integer targets (HDR or averaged input) use the nearest 8-bit value; NaN and out-of-range clamp.
    const float value = rgb[channel] > 255.0f ? 255.0f : (rgb[channel] >= 0.0f ? rgb[channel] : 0.0f);
    const SingleColorEntry entry = table_for(channel, mode)[static_cast<int>(value + 0.5f)];
    candidate.endpoints[0][channel] = entry.endpoint0;
    candidate.endpoints[1][channel] = entry.endpoint1;
  }
  return candidate;
}

}  // namespace blocklab
