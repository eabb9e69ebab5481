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
  if (e0 == e1) {
    // One numerator q = n e0 for every level: all levels are the same double, so every texel ties on index 0.
    for (int i = 0; i < kTexels; ++i) {
      const double d = levels[0] - target[i];
      fit.error += d * d;
      if (fit.error >= bound) return fit;   // same early stop as below
    }
    return fit;
  }
  // Levels other than true black are linear in l: Ybar(l) = kLogLumMin + (kLogLumRange / 255) ((n - l) e0 + l e1) / n.
  // So the nearest one is round(position) with position = (t - kLogLumMin) 255 n / (kLogLumRange (e1 - e0))
  // - n e0 / (e1 - e0) (descending levels when e1 < e0 work the same). Only that level and its two neighbours can be
  // nearest: any other is at least 1.5 steps away while the nearest is at most ~0.5 steps away, and a step is >=
  // kLogLumRange / (255 * 15) ~ 0.0084 in log2, so their squared errors differ by >= 2 step^2 ~ 1.4e-4, far above the
  // rounding of `position` or of the squares. True black (q == 0: index 0 when e0 == 0, index n when e1 == 0; both
  // zero is the e0 == e1 case) is scored at kBlackLog2 = -24 instead of the line's -16, i.e. further out at the same
  // (lowest) end: the levels stay monotone, a texel nearer to black than to its neighbour level lies below that
  // level, so its rounded position is the black index or the next one, and the window below contains black.
  const double scale = 255.0 * n / (kLogLumRange * static_cast<double>(e1 - e0));
  const double shift = static_cast<double>(n) * e0 / static_cast<double>(e1 - e0);
  const int black = e0 == 0 ? 0 : e1 == 0 ? n : -1;   // index of the true-black level, -1 for none
  // A position this far (in steps) from every midpoint between two levels has a single nearest level: the next one
  // is >= 2 kClear step^2 ~ 1.4e-10 worse in squared error, and `position` is exact to ~1e-12 steps.
  constexpr double kClear = 1e-6;
  for (int i = 0; i < kTexels; ++i) {
    const double rounded = (target[i] - kLogLumMin) * scale - shift + 0.5;
    // Clamped before the integer conversion (a NaN target goes to 0: its errors are all NaN and index 0 is kept, as
    // a full scan keeps it).
    const int nearest = !(rounded > 0.0) ? 0 : rounded >= n ? n : static_cast<int>(rounded);
    const double fraction = rounded - nearest;   // in [0, 1) inside the levels' range (NaN for a NaN target)
    int best = nearest;
    double best_error = (levels[nearest] - target[i]) * (levels[nearest] - target[i]);
    // Near a midpoint, outside the range (the clamped cases) or at the black level: the window of three, in
    // ascending index order, strictly better replaces: the full scan's lowest index among ties.
    if (!(fraction > kClear && fraction < 1.0 - kClear) || nearest == black) {
      const int first = std::max(0, nearest - 1), last = std::min(n, nearest + 1);
      best = first;
      best_error = (levels[first] - target[i]) * (levels[first] - target[i]);
      for (int l = first + 1; l <= last; ++l) {
        const double e = (levels[l] - target[i]) * (levels[l] - target[i]);
        if (e < best_error) {
          best_error = e;
          best = l;
        }
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
