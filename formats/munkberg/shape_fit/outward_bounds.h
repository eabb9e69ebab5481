// Branch-free outward bounds for interval hot loops: a double computed in round-to-nearest, moved outward far enough
// to cover the exact value, with no rounding-mode switch and no branch.
//
//   widen_up(r)   = r + (|r| 2^-52 + 2^-1074)
//   widen_down(r) = r - (|r| 2^-52 + 2^-1074)
//
// Why it is enough: the spacing of the doubles next to r is at most |r| 2^-52 for normal r and exactly 2^-1074 for
// subnormal r, so the (rounded) sum lands on or beyond the neighbouring double next_up(r) / next_down(r) (Rump,
// Zimmermann, Boldo, Melquiond, "Computing predecessor and successor in rounding to nearest", BIT 49, 2009, who prove
// it with the smaller factor 2^-53 (1 + 2^-52)). It lands at most 2 ulps away, or 3 for |r| < 2^-1020, where
// |r| 2^-52 is itself a rounded subnormal (measured by the test below). So when r is the round-to-nearest
// result of one operation, [widen_down(r), widen_up(r)] contains the exact result. Assumptions, as core/interval.h:
// round-to-nearest, no flush-to-zero; r finite (a NaN stays NaN, an infinity stays infinite).
// tests/unit/test_outward_bounds.cpp checks those distances across the doubles.
//
// Where SSE2 is available, *_pair versions work on two doubles at once, lane for lane the scalar operations, so their
// results are bit-identical (tested). In them, std::max(a, b), which is (a < b) ? b : a, is written _mm_max_pd(b, a):
// MAXPD returns its first operand when it is greater and otherwise its second, which agrees with std::max on signed
// zeros and NaN too; std::abs is a cleared sign bit and negation a flipped one.
#pragma once

#include <algorithm>
#include <cmath>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace blocklab {

inline double widen_up(double r) { return r + (std::abs(r) * 0x1p-52 + 0x1p-1074); }
inline double widen_down(double r) { return r - (std::abs(r) * 0x1p-52 + 0x1p-1074); }

// Enclosure [*lower, *upper] of (t - L)^2 over L in [lo, hi] (lo <= hi, all finite), from the rounded differences
// widened outward. Branch-free: over t - L in [a, b], the smallest |t - L| is max(a, -b, 0) (a when a >= 0, -b when
// b <= 0, else 0) and the largest max(-a, b); a widened lower bound of a square is clamped at 0 (squares are never
// negative).
inline void squared_difference_bounds(double t, double lo, double hi, double* lower, double* upper) {
  const double a = widen_down(t - hi), b = widen_up(t - lo);   // t - L lies in [a, b]
  const double nearest = std::max(std::max(a, -b), 0.0), farthest = std::max(-a, b);
  *lower = std::max(0.0, widen_down(nearest * nearest));
  *upper = widen_up(farthest * farthest);
}

#if defined(__SSE2__)
inline __m128d widen_up_pair(__m128d r) {
  const __m128d magnitude = _mm_andnot_pd(_mm_set1_pd(-0.0), r);
  return _mm_add_pd(r, _mm_add_pd(_mm_mul_pd(magnitude, _mm_set1_pd(0x1p-52)), _mm_set1_pd(0x1p-1074)));
}
inline __m128d widen_down_pair(__m128d r) {
  const __m128d magnitude = _mm_andnot_pd(_mm_set1_pd(-0.0), r);
  return _mm_sub_pd(r, _mm_add_pd(_mm_mul_pd(magnitude, _mm_set1_pd(0x1p-52)), _mm_set1_pd(0x1p-1074)));
}
// squared_difference_bounds on two (t, lo, hi) lanes.
inline void squared_difference_bounds_pair(__m128d t, __m128d lo, __m128d hi, __m128d* lower, __m128d* upper) {
  const __m128d sign = _mm_set1_pd(-0.0), zero = _mm_setzero_pd();
  const __m128d a = widen_down_pair(_mm_sub_pd(t, hi)), b = widen_up_pair(_mm_sub_pd(t, lo));
  const __m128d nearest = _mm_max_pd(zero, _mm_max_pd(_mm_xor_pd(b, sign), a));
  const __m128d farthest = _mm_max_pd(b, _mm_xor_pd(a, sign));
  *lower = _mm_max_pd(widen_down_pair(_mm_mul_pd(nearest, nearest)), zero);
  *upper = widen_up_pair(_mm_mul_pd(farthest, farthest));
}
#endif

}  // namespace blocklab
