// Luminance endpoint neighbourhood search of the `munkberg` format (formats/munkberg/munkberg_luminance.h;
// Munkberg et al. 2008, section 7.3, Figure 9; black level eq. 3).
#include "formats/munkberg/munkberg_luminance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "formats/munkberg/munkberg_block.h"

namespace blocklab::munkberg {

namespace {

// Real-valued endpoint code of a log2 luminance (inside the stored range [kLogLumMin, kLogLumMax]).
double code_of(double log2_value) {
  const double clamped = std::min(kLogLumMax, std::max(kLogLumMin, log2_value));
  return (clamped - kLogLumMin) * static_cast<double>(kLumEndpointMax) / kLogLumRange;
}

}  // namespace

double scored_level_log2(Mode mode, int e0, int e1, int l) {
  const int n = lum_levels_minus_one(mode);
  const std::int64_t q = static_cast<std::int64_t>(n - l) * e0 + static_cast<std::int64_t>(l) * e1;
  // Eq. (3): q == 0 decodes to true black, scored at the metric floor.
  if (q == 0) return kBlackLog2;
  return log_luminance_of_numerator(q, n);
}

LuminanceFit assign_luminance_indices(Mode mode, int e0, int e1, const double target[kTexels], double bound) {
  const int n = lum_levels_minus_one(mode);
  double levels[16];
  for (int l = 0; l <= n; ++l) levels[l] = scored_level_log2(mode, e0, e1, l);
  LuminanceFit fit;
  fit.lum = {e0, e1};
  for (int i = 0; i < kTexels; ++i) {
    int best = 0;
    double best_error = (levels[0] - target[i]) * (levels[0] - target[i]);
    for (int l = 1; l <= n; ++l) {
      const double e = (levels[l] - target[i]) * (levels[l] - target[i]);
      if (e < best_error) {   // strict: ties keep the lower index
        best_error = e;
        best = l;
      }
    }
    fit.index[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(best);
    fit.error += best_error;
    // Every texel adds a square (>= 0), so the error only grows: once it reaches the bound it ends there or above.
    if (fit.error >= bound) return fit;   // (a NaN error never stops early: it is fitted in full as before)
  }
  return fit;
}

LuminanceFit fit_luminance(Mode mode, const double target[kTexels], int radius) {
  double smallest = target[0], largest = target[0];
  for (int i = 1; i < kTexels; ++i) {
    smallest = std::min(smallest, target[i]);
    largest = std::max(largest, target[i]);
  }
  const int lo = static_cast<int>(std::floor(code_of(smallest)));
  const int hi = static_cast<int>(std::ceil(code_of(largest)));
  // A target at or below the stored range (black, or darker than 2^-16) may be best served by the black code 0.
  const bool try_black = smallest <= kLogLumMin;

  LuminanceFit best;
  bool have_best = false;
  auto consider = [&](int e0, int e1) {
    // Only a strictly lower error replaces the best: a pair is fitted only while it can still be below it.
    const LuminanceFit fit = assign_luminance_indices(mode, e0, e1, target,
                                                      have_best ? best.error : std::numeric_limits<double>::infinity());
    if (!have_best || fit.error < best.error) {   // strict: ties keep the earlier pair
      best = fit;
      have_best = true;
    }
  };
  const int e0_first = std::max(0, lo - radius), e0_last = std::min(kLumEndpointMax, lo + radius);
  const int e1_first = std::max(0, hi - radius), e1_last = std::min(kLumEndpointMax, hi + radius);
  // The black code first when it lies outside the neighbourhood (it is inside it when e0_first == 0).
  if (try_black && e0_first > 0)
    for (int e1 = e1_first; e1 <= e1_last; ++e1) consider(0, e1);
  for (int e0 = e0_first; e0 <= e0_last; ++e0)
    for (int e1 = std::max(e0, e1_first); e1 <= e1_last; ++e1) consider(e0, e1);
  // Neighbourhoods that do not overlap in the right order (cannot happen since lo <= hi, kept for safety): a flat fit.
  if (!have_best) consider(std::min(lo, kLumEndpointMax), std::min(lo, kLumEndpointMax));
  return best;
}

}  // namespace blocklab::munkberg
