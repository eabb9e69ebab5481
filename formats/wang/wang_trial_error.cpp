// The trial error of the luminance 1D codec's descent (formats/wang/wang_trial_error.h has the rounding argument).
#include "formats/wang/wang_trial_error.h"

#include <cmath>
#include <cstdio>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/cpu_features.h"
#if BLOCKLAB_HAS_AVX2_PATHS
#include <immintrin.h>
#endif

namespace blocklab {
namespace wang {

namespace {

constexpr double kRelativeSlack = 1e-5;   // >= 5 x 31 eps (header)
constexpr double kAbsoluteSlack = 1e-5;   // >= 16 x 10.1 eps (header)
constexpr double kLargestScreened = 1e30;  // far below FLT_MAX, so no sum of two such values overflows float

// The decoded values part0[i] + part1[j] in the order i = 0.., j = 0.. (the exhaustive scan's order); returns their
// count.
int pair_sums(const double* part0, int count0, const double* part1, int count1, double sums[64]) {
  int count = 0;
  for (int i = 0; i < count0; ++i)
    for (int j = 0; j < count1; ++j) sums[count++] = part0[i] + part1[j];
  return count;
}

// Running minima over `count` sums of |L - sum| for the 8 texels from `first` on (exact: sign bit cleared, min).
void nearest_sum_distances(const LuminanceBlockError& error, const double* sums, int count, int first,
                           double best[16]) {
#if defined(__SSE2__)
  // Two texels per SSE2 register: |L - sum| by clearing the sign bit, minpd (exact; no NaN can occur here).
  const __m128d sign = _mm_set1_pd(-0.0);
  __m128d targets[4], minima[4];
  for (int pair = 0; pair < 4; ++pair) {
    targets[pair] = _mm_loadu_pd(&error.luminance[first + 2 * pair]);
    minima[pair] = _mm_set1_pd(std::numeric_limits<double>::infinity());
  }
  for (int k = 0; k < count; ++k) {
    const __m128d sum = _mm_set1_pd(sums[k]);
    for (int pair = 0; pair < 4; ++pair)
      minima[pair] = _mm_min_pd(_mm_andnot_pd(sign, _mm_sub_pd(targets[pair], sum)), minima[pair]);
  }
  for (int pair = 0; pair < 4; ++pair) _mm_storeu_pd(&best[first + 2 * pair], minima[pair]);
#else
  for (int texel = first; texel < first + 8; ++texel) best[texel] = std::numeric_limits<double>::infinity();
  for (int k = 0; k < count; ++k) {
    const double sum = sums[k];
    for (int texel = first; texel < first + 8; ++texel) {
      const double distance = std::abs(error.luminance[texel] - sum);
      best[texel] = distance < best[texel] ? distance : best[texel];
    }
  }
#endif
}

// The exact total, summed over texels 0..15 in halves: when the first half's sum already reaches `bound` it is
// returned as it is (every term is >= 0, so the full total would reach the bound too). Every distance is the same
// expression as in the exhaustive loop of the codec's evaluate() and a minimum does not depend on the order it is
// taken in, so the total is the same double.
double exact_total(const LuminanceBlockError& error, const double* sums, int count, double bound) {
  double best[16];
  double total = 0.0;
  for (int half = 0; half < 2; ++half) {
    nearest_sum_distances(error, sums, count, 8 * half, best);
    for (int texel = 8 * half; texel < 8 * half + 8; ++texel) total += error.weight[texel] * best[texel];
    if (!(total < bound)) return total;
  }
  return total;
}

#if defined(__SSE2__)
// True when the float screen proves the exact total >= bound. Eight texels (two registers) at a time, each register
// with two running minima (even and odd j) so that consecutive min operations do not wait for each other; after
// each half the partial total is compared, since a partial total of non-negative terms already above the threshold
// decides (the rounding bound holds for any subset of the texels).
bool screen_refuses(const TrialTexels& texels, const float* part0, int count0, const float* part1, int count1,
                    double bound) {
  const float threshold =
      static_cast<float>(bound * (1.0 + kRelativeSlack) + kAbsoluteSlack * texels.weighted_luminance);
  const __m128 sign = _mm_set1_ps(-0.0f);
  const __m128 infinity = _mm_set1_ps(std::numeric_limits<float>::infinity());
  float total = 0.0f;
  for (int half = 0; half < 2; ++half) {
    const __m128 targets[2] = {_mm_load_ps(&texels.luminance[8 * half]), _mm_load_ps(&texels.luminance[8 * half + 4])};
    __m128 even[2] = {infinity, infinity}, odd[2] = {infinity, infinity};
    for (int i = 0; i < count0; ++i) {
      const __m128 part = _mm_set1_ps(part0[i]);
      const __m128 shifted[2] = {_mm_sub_ps(targets[0], part), _mm_sub_ps(targets[1], part)};
      int j = 0;
      for (; j + 1 < count1; j += 2) {
        const __m128 a = _mm_set1_ps(part1[j]), b = _mm_set1_ps(part1[j + 1]);
        for (int r = 0; r < 2; ++r) {
          even[r] = _mm_min_ps(_mm_andnot_ps(sign, _mm_sub_ps(shifted[r], a)), even[r]);
          odd[r] = _mm_min_ps(_mm_andnot_ps(sign, _mm_sub_ps(shifted[r], b)), odd[r]);
        }
      }
      if (j < count1) {
        const __m128 a = _mm_set1_ps(part1[j]);
        for (int r = 0; r < 2; ++r) even[r] = _mm_min_ps(_mm_andnot_ps(sign, _mm_sub_ps(shifted[r], a)), even[r]);
      }
    }
    const __m128 weighted = _mm_add_ps(_mm_mul_ps(_mm_min_ps(even[0], odd[0]), _mm_load_ps(&texels.weight[8 * half])),
                                       _mm_mul_ps(_mm_min_ps(even[1], odd[1]), _mm_load_ps(&texels.weight[8 * half + 4])));
    alignas(16) float lanes[4];
    _mm_store_ps(lanes, weighted);
    total += (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
    if (total >= threshold) return true;
  }
  return false;
}
#endif

#if BLOCKLAB_HAS_AVX2_PATHS
#pragma GCC push_options
#pragma GCC target("avx2")
// screen_refuses with eight texels per register (AVX2): the same distances lane by lane, summed in another order,
// which the rounding bound of the header covers as well (any order of at most 16 non-negative terms).
bool screen_refuses_avx2(const TrialTexels& texels, const float* part0, int count0, const float* part1, int count1,
                         double bound) {
  const float threshold =
      static_cast<float>(bound * (1.0 + kRelativeSlack) + kAbsoluteSlack * texels.weighted_luminance);
  const __m256 sign = _mm256_set1_ps(-0.0f);
  const __m256 infinity = _mm256_set1_ps(std::numeric_limits<float>::infinity());
  float total = 0.0f;
  for (int half = 0; half < 2; ++half) {
    const __m256 targets = _mm256_load_ps(&texels.luminance[8 * half]);
    __m256 even = infinity, odd = infinity;
    for (int i = 0; i < count0; ++i) {
      const __m256 shifted = _mm256_sub_ps(targets, _mm256_set1_ps(part0[i]));
      int j = 0;
      for (; j + 1 < count1; j += 2) {
        even = _mm256_min_ps(_mm256_andnot_ps(sign, _mm256_sub_ps(shifted, _mm256_set1_ps(part1[j]))), even);
        odd = _mm256_min_ps(_mm256_andnot_ps(sign, _mm256_sub_ps(shifted, _mm256_set1_ps(part1[j + 1]))), odd);
      }
      if (j < count1)
        even = _mm256_min_ps(_mm256_andnot_ps(sign, _mm256_sub_ps(shifted, _mm256_set1_ps(part1[j]))), even);
    }
    const __m256 weighted = _mm256_mul_ps(_mm256_min_ps(even, odd), _mm256_load_ps(&texels.weight[8 * half]));
    const __m128 quads = _mm_add_ps(_mm256_castps256_ps128(weighted), _mm256_extractf128_ps(weighted, 1));
    alignas(16) float lanes[4];
    _mm_store_ps(lanes, quads);
    total += (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
    if (total >= threshold) return true;
  }
  return false;
}
#pragma GCC pop_options
#endif

}  // namespace

TrialTexels make_trial_texels(const LuminanceBlockError& error) {
  TrialTexels texels;
  texels.error = &error;
  texels.screen = true;
  for (int texel = 0; texel < 16; ++texel) {
    const double luminance = error.luminance[texel], weight = error.weight[texel];
    // Values float cannot hold with room for a sum (or NaN): the screen is not used for this block.
    if (!(std::abs(luminance) <= kLargestScreened) || !(weight >= 0.0 && weight <= kLargestScreened))
      texels.screen = false;
    texels.luminance[texel] = static_cast<float>(luminance);
    texels.weight[texel] = static_cast<float>(weight);
    texels.weighted_luminance += weight * std::abs(luminance);
  }
#if !defined(__SSE2__)
  texels.screen = false;   // the screen is an SSE2 path; elsewhere every trial is exact
#endif
  texels.wide_screen = cpu_has_avx2();
  return texels;
}

double nearest_sum_total_below(const TrialTexels& texels, const double* part0, int count0, const double* part1,
                               int count1, double bound) {
#if defined(__SSE2__)
  if (texels.screen) {
    // Parts outside [0, 1e30] (never met in practice: the eq. 4 terms are non-negative) go to the exact pass only.
    float part0_float[8], part1_float[8];
    bool in_range = true;
    for (int i = 0; i < count0; ++i) {
      in_range = in_range && part0[i] >= 0.0 && part0[i] <= kLargestScreened;
      part0_float[i] = static_cast<float>(part0[i]);
    }
    for (int j = 0; j < count1; ++j) {
      in_range = in_range && part1[j] >= 0.0 && part1[j] <= kLargestScreened;
      part1_float[j] = static_cast<float>(part1[j]);
    }
    if (in_range) {
#if BLOCKLAB_HAS_AVX2_PATHS
      const bool refused = texels.wide_screen
                               ? screen_refuses_avx2(texels, part0_float, count0, part1_float, count1, bound)
                               : screen_refuses(texels, part0_float, count0, part1_float, count1, bound);
#else
      const bool refused = screen_refuses(texels, part0_float, count0, part1_float, count1, bound);
#endif
      if (refused) return std::numeric_limits<double>::infinity();
    }
  }
#endif
  double sums[64];
  const int count = pair_sums(part0, count0, part1, count1, sums);
  return exact_total(*texels.error, sums, count, bound);
}

double nearest_sum_total_with_choice(const TrialTexels& texels, const double* part0, int count0, const double* part1,
                                     int count1, int first[16], int second[16]) {
  const LuminanceBlockError& error = *texels.error;
  double sums[64];
  const int count = pair_sums(part0, count0, part1, count1, sums);
  double best[16];
  nearest_sum_distances(error, sums, count, 0, best);
  nearest_sum_distances(error, sums, count, 8, best);
  double total = 0.0;
  for (int texel = 0; texel < 16; ++texel) {
    // The minimum is one of the distances, each formed by the same expression, so the scan finds it exactly; the
    // first match in sum order is the pair a strict-improvement scan keeps.
    int k = 0;
    while (k + 1 < count && std::abs(error.luminance[texel] - sums[k]) != best[texel]) ++k;
    first[texel] = k / count1;
    second[texel] = k % count1;
    total += error.weight[texel] * best[texel];
  }
  return total;
}

}  // namespace wang
}  // namespace blocklab
