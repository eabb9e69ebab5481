// Quantisation-aware refinement of BC1/BC3 colour endpoints (formats/common/s3tc_color_fit.h, steps 4 and 5):
//   * exact evaluation on the reference palette (bit-replicated 565 endpoints, exact-fraction interpolants) with
//     the optimal code per texel;
//   * the least-squares endpoints for fixed codes: minimise sum_i w_c (alpha_i A + beta_i B - x_i)^2 per channel,
//     whose normal equations are the 2x2 system [sum a^2, sum ab; sum ab, sum b^2] (A, B) = (sum a x, sum b x)
//     (alpha/beta = interpolation weights of each code, beta = 1 - alpha), then quantised to 565;
//   * hill climbing: +-1 steps of each of the six 565 coordinates, accepted while they lower the exact error
//     (quantisation-aware polish: the least-squares point rounded per coordinate is not the best lattice point);
//   * exhaustive neighbourhood: every lattice point within +-radius of each coordinate.
#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "formats/common/s3tc_color_fit.h"

namespace blocklab {

namespace {

// Palette of a candidate in 8-bit units (float), the reference decoding's exact fractions rounded to float.
void candidate_palette(const ColorCandidate& candidate, float palette[4][3]) {
  for (int index = 0; index < 4; ++index) {
    const PaletteWeights weights = bc1_palette_weights(candidate.mode, index);
    for (int channel = 0; channel < 3; ++channel) {
      const int e0 = expand_565_channel(candidate.endpoints[0][channel], channel);
      const int e1 = expand_565_channel(candidate.endpoints[1][channel], channel);
      // d = 0 is the constant black entry of the 3-colour mode.
      palette[index][channel] =
          weights.d == 0 ? 0.0f : static_cast<float>(weights.w0 * e0 + weights.w1 * e1) / static_cast<float>(weights.d);
    }
  }
}

}  // namespace

int quantize_to_565_channel(float value, int channel) {
  // Clamp first: least-squares endpoints may leave [0, 255], and NaN (a degenerate solve) maps to 0.
  const float clamped = value > 255.0f ? 255.0f : (value >= 0.0f ? value : 0.0f);
  const int max_value = rgb565_channel_max(channel);
  // Linear guess, then check the neighbours: bit replication is not exactly linear (steps of 8 or 9 / 4 or 5).
  const int guess = static_cast<int>(clamped * static_cast<float>(max_value) / 255.0f + 0.5f);
  int best = guess;
  float best_distance = std::numeric_limits<float>::infinity();
  for (int q = std::max(0, guess - 1); q <= std::min(max_value, guess + 1); ++q) {
    const float distance = std::fabs(static_cast<float>(expand_565_channel(q, channel)) - clamped);
    if (distance < best_distance) {   // strict: ties keep the lower value
      best_distance = distance;
      best = q;
    }
  }
  return best;
}

float evaluate_color_candidate(const ColorBlock& block, const ColorCandidate& candidate, std::uint8_t* indices) {
  float palette[4][3];
  candidate_palette(candidate, palette);
  const float wr = block.weights[0], wg = block.weights[1], wb = block.weights[2];
  float total = 0.0f;
#if defined(__SSE2__)
  // The four palette entries in the four lanes; each lane computes exactly the scalar expression below
  // (((w dr) dr + (w dg) dg) + (w db) db), so both paths give the same bits.
  const __m128 red = _mm_setr_ps(palette[0][0], palette[1][0], palette[2][0], palette[3][0]);
  const __m128 green = _mm_setr_ps(palette[0][1], palette[1][1], palette[2][1], palette[3][1]);
  const __m128 blue = _mm_setr_ps(palette[0][2], palette[1][2], palette[2][2], palette[3][2]);
  const __m128 weight_r = _mm_set1_ps(wr), weight_g = _mm_set1_ps(wg), weight_b = _mm_set1_ps(wb);
#endif
  for (int texel = 0; texel < 16; ++texel) {
    const float* x = block.texels[texel];
    float errors[4];
#if defined(__SSE2__)
    const __m128 dr = _mm_sub_ps(red, _mm_set1_ps(x[0])), dg = _mm_sub_ps(green, _mm_set1_ps(x[1])),
                 db = _mm_sub_ps(blue, _mm_set1_ps(x[2]));
    const __m128 error = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(weight_r, dr), dr),
                                               _mm_mul_ps(_mm_mul_ps(weight_g, dg), dg)),
                                    _mm_mul_ps(_mm_mul_ps(weight_b, db), db));
    if (indices == nullptr) {
      // Only the smallest of the four counts: a branch-free minimum across the lanes (the same value the strict
      // scan below finds; the errors are finite, the texels being clamped to [0, 255]), added in texel order.
      const __m128 pairs = _mm_min_ps(error, _mm_shuffle_ps(error, error, _MM_SHUFFLE(2, 3, 0, 1)));
      total += _mm_cvtss_f32(_mm_min_ps(pairs, _mm_shuffle_ps(pairs, pairs, _MM_SHUFFLE(1, 0, 3, 2))));
      continue;
    }
    _mm_storeu_ps(errors, error);
#else
    for (int index = 0; index < 4; ++index) {
      const float dr = palette[index][0] - x[0], dg = palette[index][1] - x[1], db = palette[index][2] - x[2];
      errors[index] = wr * dr * dr + wg * dg * dg + wb * db * db;
    }
#endif
    // Ties go to the lower code (strict comparisons in index order).
    int best_index = 0;
    float best = errors[0];
    for (int index = 1; index < 4; ++index)
      if (errors[index] < best) {
        best = errors[index];
        best_index = index;
      }
    total += best;
    if (indices != nullptr) indices[texel] = static_cast<std::uint8_t>(best_index);
  }
  return total;
}

bool least_squares_candidate(const ColorBlock& block, const std::uint8_t* indices, ColorCandidate& candidate) {
  // Interpolation weight of endpoint 0 for each code; -1 marks black (3-colour code 3), which no endpoint moves.
  static constexpr float kAlphaFour[4] = {1.0f, 0.0f, 2.0f / 3.0f, 1.0f / 3.0f};
  static constexpr float kAlphaThree[4] = {1.0f, 0.0f, 0.5f, -1.0f};
  const float* alpha_of = candidate.mode == Bc1Mode::four_color ? kAlphaFour : kAlphaThree;
  float aa = 0.0f, bb = 0.0f, ab = 0.0f, ax[3] = {0, 0, 0}, bx[3] = {0, 0, 0};
  for (int texel = 0; texel < 16; ++texel) {
    const float alpha = alpha_of[indices[texel] & 3];
    if (alpha < 0.0f) continue;   // black texel: fixed colour, not part of the fit
    const float beta = 1.0f - alpha;
    aa += alpha * alpha;
    bb += beta * beta;
    ab += alpha * beta;
    for (int channel = 0; channel < 3; ++channel) {
      ax[channel] += alpha * block.texels[texel][channel];
      bx[channel] += beta * block.texels[texel][channel];
    }
  }
  const float determinant = aa * bb - ab * ab;
  // All fitted texels share one code (or none is fitted): the system is singular and the codes pin down at most
  // one endpoint; leave the candidate as it is.
  if (!(determinant > 1e-4f)) return false;
  const float inverse = 1.0f / determinant;
  for (int channel = 0; channel < 3; ++channel) {
    const float a = (bb * ax[channel] - ab * bx[channel]) * inverse;
    const float b = (aa * bx[channel] - ab * ax[channel]) * inverse;
    candidate.endpoints[0][channel] = quantize_to_565_channel(a, channel);
    candidate.endpoints[1][channel] = quantize_to_565_channel(b, channel);
  }
  return true;
}

float polish_color_candidate(const ColorBlock& block, ColorCandidate& candidate, int hill_climb_passes) {
  std::uint8_t indices[16];
  float error = evaluate_color_candidate(block, candidate, indices);
  // Alternate: codes for the endpoints, endpoints for the codes, while it helps (at most 3 rounds).
  for (int round = 0; round < 3; ++round) {
    ColorCandidate refit = candidate;
    if (!least_squares_candidate(block, indices, refit)) break;
    std::uint8_t refit_indices[16];
    const float refit_error = evaluate_color_candidate(block, refit, refit_indices);
    if (!(refit_error < error)) break;
    candidate = refit;
    error = refit_error;
    std::copy(refit_indices, refit_indices + 16, indices);
  }
  // Hill climbing on the lattice: first improvement per coordinate, passes until no step helps.
  for (int pass = 0; pass < hill_climb_passes; ++pass) {
    bool improved = false;
    for (int e = 0; e < 2; ++e) {
      for (int channel = 0; channel < 3; ++channel) {
        for (int step = -1; step <= 1; step += 2) {
          const int value = candidate.endpoints[e][channel] + step;
          if (value < 0 || value > rgb565_channel_max(channel)) continue;   // stay on the lattice
          ColorCandidate trial = candidate;
          trial.endpoints[e][channel] = value;
          const float trial_error = evaluate_color_candidate(block, trial, nullptr);
          if (trial_error < error) {
            candidate = trial;
            error = trial_error;
            improved = true;
          }
        }
      }
    }
    if (!improved) break;
  }
  return error;
}

float exhaustive_color_neighbourhood(const ColorBlock& block, ColorCandidate& candidate, int radius) {
  const ColorCandidate centre = candidate;
  float best_error = evaluate_color_candidate(block, candidate, nullptr);
  int low[6], high[6];
  for (int k = 0; k < 6; ++k) {
    const int e = k / 3, channel = k % 3;
    low[k] = std::max(0, centre.endpoints[e][channel] - radius);
    high[k] = std::min(rgb565_channel_max(channel), centre.endpoints[e][channel] + radius);
  }
  int point[6];
  for (int k = 0; k < 6; ++k) point[k] = low[k];
  // Odometer over the 6-dimensional box, in lexicographic order (deterministic; ties keep the earlier point).
  while (true) {
    ColorCandidate trial = centre;
    for (int k = 0; k < 6; ++k) trial.endpoints[k / 3][k % 3] = point[k];
    const float error = evaluate_color_candidate(block, trial, nullptr);
    if (error < best_error) {
      best_error = error;
      candidate = trial;
    }
    int k = 5;
    while (k >= 0 && point[k] == high[k]) {
      point[k] = low[k];
      --k;
    }
    if (k < 0) break;
    ++point[k];
  }
  return best_error;
}

}  // namespace blocklab
