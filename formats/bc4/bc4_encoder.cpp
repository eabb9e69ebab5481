// The BC4 / BC3-alpha encoder (formats/bc4/bc4_encoder.h). Least squares for fixed codes: minimise
// sum_i (alpha_i a0 + (1 - alpha_i) a1 - v_i)^2 over the texels on interpolated codes (alpha = weight of red0 of
// each code; the 6-value mode's constants 0 and 255 are excluded), whose normal equations are a 2x2 system.
#include "formats/bc4/bc4_encoder.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace blocklab {

namespace {

void float_palette(int endpoint0, int endpoint1, Bc4Mode mode, float palette[8]) {
  for (int index = 0; index < 8; ++index) {
    const PaletteWeights weights = bc4_palette_weights(mode, index);
    // d = 0 marks the constants 0 and 255 (value w0) of the 6-value mode.
    palette[index] = weights.d == 0 ? static_cast<float>(weights.w0)
                                    : static_cast<float>(weights.w0 * endpoint0 + weights.w1 * endpoint1) /
                                          static_cast<float>(weights.d);
  }
}

// Error with early exit: stops (returning a value >= limit) once the partial sum reaches `limit`.
float bounded_error(const float values[16], int endpoint0, int endpoint1, float limit) {
  float palette[8];
  float_palette(endpoint0, endpoint1, endpoint0 > endpoint1 ? Bc4Mode::eight_value : Bc4Mode::six_value, palette);
  float total = 0.0f;
  for (int texel = 0; texel < 16; ++texel) {
    float best = std::numeric_limits<float>::infinity();
    for (int index = 0; index < 8; ++index) {
      const float d = palette[index] - values[texel];
      best = std::min(best, d * d);
    }
    total += best;
    if (total >= limit) return total;   // already no better than the best pair: the rest cannot lower it
  }
  return total;
}

int round_endpoint(float value) {
  // Least-squares endpoints can leave [0, 255] (or be NaN for a degenerate system): clamp, then round.
  const float clamped = value > 255.0f ? 255.0f : (value >= 0.0f ? value : 0.0f);
  return static_cast<int>(clamped + 0.5f);
}

// One least-squares round for the codes in `indices`; false when the codes do not determine both endpoints.
bool least_squares_endpoints(const float values[16], const std::uint8_t* indices, Bc4Mode mode, int& endpoint0,
                             int& endpoint1) {
  float aa = 0.0f, bb = 0.0f, ab = 0.0f, ax = 0.0f, bx = 0.0f;
  for (int texel = 0; texel < 16; ++texel) {
    const PaletteWeights weights = bc4_palette_weights(mode, indices[texel]);
    if (weights.d == 0) continue;   // the constants 0 and 255 do not depend on the endpoints
    const float alpha = static_cast<float>(weights.w0) / static_cast<float>(weights.d);
    const float beta = 1.0f - alpha;
    aa += alpha * alpha;
    bb += beta * beta;
    ab += alpha * beta;
    ax += alpha * values[texel];
    bx += beta * values[texel];
  }
  const float determinant = aa * bb - ab * ab;
  if (!(determinant > 1e-4f)) return false;   // all fitted texels on one code: singular system
  endpoint0 = round_endpoint((bb * ax - ab * bx) / determinant);
  endpoint1 = round_endpoint((aa * bx - ab * ax) / determinant);
  return true;
}

struct Bc4Candidate {
  int endpoint0 = 0, endpoint1 = 0;
  Bc4Mode mode = Bc4Mode::eight_value;
  float error = std::numeric_limits<float>::infinity();
};

// Alternating refinement, then the +-2 box around the result (the mode stays fixed; the endpoints are stored in
// whichever order canonicalise_bc4 needs).
Bc4Candidate refine(const float values[16], Bc4Candidate candidate) {
  std::uint8_t indices[16];
  candidate.error = evaluate_bc4_candidate(values, candidate.endpoint0, candidate.endpoint1, candidate.mode, indices);
  for (int round = 0; round < 3; ++round) {
    int endpoint0 = candidate.endpoint0, endpoint1 = candidate.endpoint1;
    if (!least_squares_endpoints(values, indices, candidate.mode, endpoint0, endpoint1)) break;
    std::uint8_t refit_indices[16];
    const float error = evaluate_bc4_candidate(values, endpoint0, endpoint1, candidate.mode, refit_indices);
    if (!(error < candidate.error)) break;
    candidate.endpoint0 = endpoint0;
    candidate.endpoint1 = endpoint1;
    candidate.error = error;
    std::copy(refit_indices, refit_indices + 16, indices);
  }
  const Bc4Candidate centre = candidate;
  for (int d0 = -2; d0 <= 2; ++d0)
    for (int d1 = -2; d1 <= 2; ++d1) {
      const int endpoint0 = centre.endpoint0 + d0, endpoint1 = centre.endpoint1 + d1;
      if (endpoint0 < 0 || endpoint0 > 255 || endpoint1 < 0 || endpoint1 > 255) continue;   // off the lattice
      const float error = evaluate_bc4_candidate(values, endpoint0, endpoint1, centre.mode, nullptr);
      if (error < candidate.error) {
        candidate.endpoint0 = endpoint0;
        candidate.endpoint1 = endpoint1;
        candidate.error = error;
      }
    }
  return candidate;
}

}  // namespace

float evaluate_bc4_candidate(const float values[16], int endpoint0, int endpoint1, Bc4Mode mode, std::uint8_t* indices) {
  float palette[8];
  float_palette(endpoint0, endpoint1, mode, palette);
  float total = 0.0f;
  for (int texel = 0; texel < 16; ++texel) {
    float best = std::numeric_limits<float>::infinity();
    int best_index = 0;
    for (int index = 0; index < 8; ++index) {
      const float d = palette[index] - values[texel];
      if (d * d < best) {   // strict: ties go to the lower code
        best = d * d;
        best_index = index;
      }
    }
    total += best;
    if (indices != nullptr) indices[texel] = static_cast<std::uint8_t>(best_index);
  }
  return total;
}

Bc4Params fit_bc4_block(const float values[16], S3tcSearch search, bool six_value_start) {
  int low = 255, high = 0;
  for (int texel = 0; texel < 16; ++texel) {
    const int value = round_endpoint(values[texel]);
    low = std::min(low, value);
    high = std::max(high, value);
  }
  Bc4Candidate best;
  best.endpoint0 = high;
  best.endpoint1 = low;
  best.mode = Bc4Mode::eight_value;
  best.error = evaluate_bc4_candidate(values, high, low, Bc4Mode::eight_value, nullptr);
  if (search != S3tcSearch::fast) {
    best = refine(values, best);
  }
  if (search != S3tcSearch::fast && six_value_start) {
    // 6-value start: the range of the texels not served exactly by the constants 0 and 255.
    int inner_low = 255, inner_high = 0;
    for (int texel = 0; texel < 16; ++texel) {
      if (values[texel] == 0.0f || values[texel] == 255.0f) continue;
      const int value = round_endpoint(values[texel]);
      inner_low = std::min(inner_low, value);
      inner_high = std::max(inner_high, value);
    }
    // Every texel is 0 or 255: any endpoints work with the constants; use the ends themselves.
    if (inner_low > inner_high) inner_low = inner_high = 0;
    Bc4Candidate six;
    six.endpoint0 = inner_low;
    six.endpoint1 = inner_high;
    six.mode = Bc4Mode::six_value;
    six = refine(values, six);
    if (six.error < best.error) best = six;
  }
  if (search == S3tcSearch::exhaustive) {
    // Every pair in the decoder's own terms: red0 > red1 is the 8-value mode, otherwise the 6-value mode.
    float best_error = best.error;
    int best0 = -1, best1 = -1;
    for (int endpoint0 = 0; endpoint0 < 256; ++endpoint0)
      for (int endpoint1 = 0; endpoint1 < 256; ++endpoint1) {
        const float error = bounded_error(values, endpoint0, endpoint1, best_error);
        if (error < best_error) {
          best_error = error;
          best0 = endpoint0;
          best1 = endpoint1;
        }
      }
    if (best0 >= 0) {
      best.endpoint0 = best0;
      best.endpoint1 = best1;
      best.mode = best0 > best1 ? Bc4Mode::eight_value : Bc4Mode::six_value;
      best.error = best_error;
    }
  }
  Bc4Params params;
  params.endpoints = {best.endpoint0, best.endpoint1};
  params.mode = best.mode;
  evaluate_bc4_candidate(values, best.endpoint0, best.endpoint1, best.mode, params.indices.data());
  return canonicalise_bc4(params);
}

}  // namespace blocklab
