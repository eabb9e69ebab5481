// The trial error of the luminance 1D codec's coordinate descent (wang_luminance_codec.cpp): the block's eq. 9 error
// sum_t w_t min_(i, j) |L_t - (part0[i] + part1[j])| of one candidate pair of alpha palettes, where the caller only
// asks whether it is below the current error.
//
// Two stages, one answer:
//   1. a float screen (SSE2, four texels per register, twice the lanes of double; eight with AVX2 when the CPU has
//      it, core/cpu_features.h): when its total exceeds the bound by more than its rounding can account for, the
//      exact total is at or above the bound too, and the trial is refused without the double pass;
//   2. otherwise the exact double total (two texels per register), the same double as the exhaustive loop of the
//      codec's evaluate().
// Rounding bound of the screen (eps = 2^-24, unit roundoff of float; parts a = part0[i], b = part1[j] >= 0, the
// eq. 4 terms): the screen forms |(fl(L) - fl(a)) - fl(b)| in float; each of the five roundings is at most eps times
// a magnitude <= L + a + b + |L - a - b| <= 2 L + 2 d (d = |L - a - b|, since a + b <= L + d), so every distance,
// hence every texel's minimum, is off by at most 10.1 eps (L + d). The weight's rounding, the product and a float
// sum of at most 16 non-negative terms add at most 19 eps relative. So
//     total_float <= (1 + 30 eps) total_exact + 10.1 eps sum_t w_t L_t,
// and total_float >= bound (1 + kRelativeSlack) + kAbsoluteSlack * sum_t w_t L_t (the threshold rounded to float:
// one more eps) proves total_exact >= bound; the slacks (1e-5) are 5x and 16x the derived ones. A block whose values
// float cannot hold (beyond 1e30 or not finite), or a part outside [0, 1e30], skips the screen.
#pragma once

#include "formats/wang/wang_block_problem.h"

namespace blocklab {
namespace wang {

// The block's texels as the screen reads them, formed once per block.
struct TrialTexels {
  const LuminanceBlockError* error = nullptr;
  alignas(32) float luminance[16] = {};   // 32: aligned loads of the AVX2 screen
  alignas(32) float weight[16] = {};
  double weighted_luminance = 0.0;   // sum_t w_t |L_t|, the scale of the screen's absolute slack
  bool screen = false;               // false: every trial takes the exact double pass
  bool wide_screen = false;          // the AVX2 screen (set when the CPU has it; a test may clear it for SSE2)
};

TrialTexels make_trial_texels(const LuminanceBlockError& error);

// The exact total when it is below `bound`; otherwise a value at or above `bound` (a partial total or +inf).
double nearest_sum_total_below(const TrialTexels& texels, const double* part0, int count0, const double* part1,
                               int count1, double bound);

// The exact total and each texel's choice: the first pair (i, j) in the order i = 0.., j = 0.. whose distance is the
// texel's minimum (the strict-improvement scan's answer), as `first[t]` = i and `second[t]` = j.
double nearest_sum_total_with_choice(const TrialTexels& texels, const double* part0, int count0, const double* part1,
                                     int count1, int first[16], int second[16]);

}  // namespace wang
}  // namespace blocklab
