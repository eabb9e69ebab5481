// Joint code choice of the `wang` encoder (formats/wang/wang_joint_codes.h).
#include "formats/wang/wang_joint_codes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "formats/wang/wang_luminance_codec.h"
#include "formats/wang/wang_residual_codec.h"

namespace blocklab {
namespace wang {

namespace {

// Distinct values of a palette, each with its lowest code.
int distinct_entries(const double* values, int count, double* out, int* codes) {
  int n = 0;
  for (int code = 0; code < count; ++code) {
    bool seen = false;
    for (int m = 0; m < n; ++m) seen = seen || out[m] == values[code];
    if (seen) continue;
    out[n] = values[code];
    codes[n++] = code;
  }
  return n;
}

// The largest decoded value <= target and the smallest > target over `count` values (padded to even with NaN,
// which no comparison selects); -inf / +inf when there is none.
void nearest_below_and_above(const double* values, int count, double target, double& below, double& above) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
#if defined(__SSE2__)
  const __m128d t = _mm_set1_pd(target);
  __m128d low = _mm_set1_pd(-kInfinity), high = _mm_set1_pd(kInfinity);
  const __m128d minus_infinity = low, plus_infinity = high;
  for (int k = 0; k < count; k += 2) {
    const __m128d v = _mm_loadu_pd(values + k);
    const __m128d at_most = _mm_cmple_pd(v, t), greater = _mm_cmpgt_pd(v, t);
    low = _mm_max_pd(low, _mm_or_pd(_mm_and_pd(at_most, v), _mm_andnot_pd(at_most, minus_infinity)));
    high = _mm_min_pd(high, _mm_or_pd(_mm_and_pd(greater, v), _mm_andnot_pd(greater, plus_infinity)));
  }
  double lows[2], highs[2];
  _mm_storeu_pd(lows, low);
  _mm_storeu_pd(highs, high);
  below = std::max(lows[0], lows[1]);
  above = std::min(highs[0], highs[1]);
#else
  below = -kInfinity;
  above = kInfinity;
  for (int k = 0; k < count; ++k) {
    if (values[k] <= target) below = std::max(below, values[k]);
    else if (values[k] > target) above = std::min(above, values[k]);
  }
#endif
}

}  // namespace

double choose_codes_jointly(const LuminanceBlockError& luminance, const ResidualBlockError& residual,
                            BlockParams& params) {
  double part0[8], part1[8], entry[4];
  alpha_parts(luminance, params.tex0.alpha, params.tex1.alpha, part0, part1);
  residual_entries(residual, params.tex1.color, entry);
  // Every decoded value of the block once, over distinct palette values (each with its lowest code), in i, j, k
  // order: equal values keep the first combination.
  double values0[8], values1[8], values2[4];
  int codes0[8], codes1[8], codes2[4];
  const int n0 = distinct_entries(part0, 8, values0, codes0);
  const int n1 = distinct_entries(part1, 8, values1, codes1);
  const int n2 = distinct_entries(entry, 4, values2, codes2);
  double decoded[256 + 1];
  int combination[256];   // 32 i + 4 j + k
  int count = 0;
  for (int a = 0; a < n0; ++a)
    for (int b = 0; b < n1; ++b) {
      const double base = values0[a] + values1[b];
      for (int c = 0; c < n2; ++c) {
        decoded[count] = residual.reconstruct(base, values2[c]);
        combination[count++] = 32 * codes0[a] + 4 * codes1[b] + codes2[c];
      }
    }
  decoded[count] = std::numeric_limits<double>::quiet_NaN();
  const int padded = count + (count & 1);

  double total = 0.0;
  for (int texel = 0; texel < 16; ++texel) {
    // The texel error falls as the decoded value nears L from either side (ResidualBlockError::texel_error), so the
    // best combination is the first one decoding nearest below L or nearest above it; the texel's current codes
    // are kept unless one of the two is strictly better.
    int best_i = params.tex0.alpha.indices[texel] & 7, best_j = params.tex1.alpha.indices[texel] & 7;
    int best_k = params.tex1.color.indices[texel] & 3;
    const double target = residual.luminance[texel];
    double best = residual.texel_error(target, residual.reconstruct(part0[best_i] + part1[best_j], entry[best_k]));
    double below, above;
    nearest_below_and_above(decoded, padded, target, below, above);
    for (const double candidate : {below, above}) {
      if (!std::isfinite(candidate)) continue;
      const double distance = residual.texel_error(target, candidate);
      if (!(distance < best)) continue;
      int index = 0;
      while (decoded[index] != candidate) ++index;
      best = distance;
      best_i = combination[index] / 32;
      best_j = (combination[index] / 4) % 8;
      best_k = combination[index] % 4;
    }
    params.tex0.alpha.indices[texel] = static_cast<std::uint8_t>(best_i);
    params.tex1.alpha.indices[texel] = static_cast<std::uint8_t>(best_j);
    params.tex1.color.indices[texel] = static_cast<std::uint8_t>(best_k);
    total += best;
  }
  return total;
}

}  // namespace wang
}  // namespace blocklab
