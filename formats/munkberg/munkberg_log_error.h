// The reconstruction error of a block's chroma in the log2[RGB] metric (Munkberg et al. 2008, eq. 1), as a function
// of the four stored base-colour coordinates, for the lattice polish of section 7.1 ("we search in a small radius of
// quantized values around each base point to minimize the mean square error for the reconstructed chrominance
// block"). The block's luminance is already decoded and fixed; every chroma group takes its best landmark.
//
//   E(u0, v0, u1, v1) = sum_groups min_k sum_{texels i of the group} sum_{c in R,G,B}
//                         (max(log2 max(f_c(L_k), kFactorFloor) + log2 Y_i - log2 w_c, -24) - s_ic)^2
// with L_k the decoded (clamped) landmarks (munkberg_block.h), f_R = v, f_G = max(0, 1 - u - v), f_B = u, Y_i the
// decoded luminance of texel i, w_c the Rec. 601 weights and s_ic = log2 max(source_ic, 2^-24) (metrics/zero_rule.h
// floor). Texels whose decoded luminance is true black (eq. 3) decode to 0 whatever the chroma and are left out
// (a constant). kFactorFloor keeps log2 finite: any factor below it gives a channel below 2^-24 for every stored
// luminance (<= 2^16), so the max with -24 makes the floor invisible.
//
// One functor templated on the scalar type (core/problem.h rules), so the Problem also has interval enclosures and
// Jet gradients; it differs from decoding + the metric only by the float rounding of decoded values.
#pragma once

#include <array>
#include <cmath>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/problem.h"
#include "core/scalar.h"
#include "formats/munkberg/munkberg_block.h"

namespace blocklab::munkberg {

constexpr double kFactorFloor = 0x1p-60;
constexpr double kLog2MetricFloor = -24.0;

struct ChromaLogTargets {
  std::array<double, kTexels> log2_luminance{};            // decoded log2 Y per texel
  std::array<bool, kTexels> black{};                       // decoded luminance is true black
  std::array<std::array<double, 3>, kTexels> source_log2{};   // log2 max(source channel, 2^-24)
};

struct ChromaLogError {
  static constexpr int kDim = kBaseCoordinateCount;

  Mode mode = Mode::shape_i;
  ShapeTemplate shape;
  ChromaLogTargets targets;
  // Per texel and channel: log2 Y_i - log2 w_c (precomputed).
  std::array<std::array<double, 3>, kTexels> offset{};

  static ChromaLogError make(Mode mode, const ShapeTemplate& shape, const ChromaLogTargets& targets) {
    ChromaLogError error;
    error.mode = mode;
    error.shape = shape;
    error.targets = targets;
    // log2 of the Rec. 601 weights, computed once (the same values as computing them per call).
    static const std::array<double, 3> log2_weights = {std::log2(kRec601WeightR), std::log2(kRec601WeightG),
                                                       std::log2(kRec601WeightB)};
    for (int i = 0; i < kTexels; ++i)
      for (int c = 0; c < 3; ++c)
        error.offset[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)] =
            targets.log2_luminance[static_cast<std::size_t>(i)] - log2_weights[static_cast<std::size_t>(c)];
    return error;
  }

  // operator()<double> with an early exit: the exact error when it is below `bound`, otherwise a partial sum that is
  // already >= bound (every group's minimum is >= 0 and adding a non-negative double never lowers a sum, so the full
  // error is >= bound too). The same operations in the same order as operator(), so values below the bound are
  // bit-identical to it.
  double eval_below(const double* x, double bound) const {
    double lu[kShapeLandmarkCount], lv[kShapeLandmarkCount];
    decode_landmarks(shape, x, lu, lv);
    // log_factor[c][k]: the landmark index innermost, so the four landmarks' sums run side by side (each sum still
    // adds its terms in operator()'s order: texels of the group, then R, G, B).
    double log_factor[3][kShapeLandmarkCount];
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      log_factor[0][k] = std::log2(max(lv[k], kFactorFloor));
      log_factor[1][k] = std::log2(max(1.0 - lu[k] - lv[k], kFactorFloor));
      log_factor[2][k] = std::log2(max(lu[k], kFactorFloor));
    }
    double total = 0.0;
    const int groups = chroma_groups(mode);
    const int per_group = kTexels / groups;
    for (int g = 0; g < groups; ++g) {
      double sum[kShapeLandmarkCount] = {0.0, 0.0, 0.0, 0.0};
#if defined(__SSE2__)
      // Landmarks (0, 1) and (2, 3) in two SSE2 registers: the same IEEE additions, subtractions and products per
      // landmark, and max_pd(a, -24) equals max(a, -24) for every non-NaN a (equal operands are equal values).
      __m128d sum01 = _mm_setzero_pd(), sum23 = _mm_setzero_pd();
      const __m128d floor = _mm_set1_pd(kLog2MetricFloor);
      for (int j = 0; j < per_group; ++j) {
        const std::size_t ii = static_cast<std::size_t>(g * per_group + j);
        if (targets.black[ii]) continue;
        for (int c = 0; c < 3; ++c) {
          const std::size_t cc = static_cast<std::size_t>(c);
          const __m128d o = _mm_set1_pd(offset[ii][cc]), s = _mm_set1_pd(targets.source_log2[ii][cc]);
          const __m128d d01 = _mm_sub_pd(_mm_max_pd(_mm_add_pd(_mm_loadu_pd(&log_factor[c][0]), o), floor), s);
          const __m128d d23 = _mm_sub_pd(_mm_max_pd(_mm_add_pd(_mm_loadu_pd(&log_factor[c][2]), o), floor), s);
          sum01 = _mm_add_pd(sum01, _mm_mul_pd(d01, d01));
          sum23 = _mm_add_pd(sum23, _mm_mul_pd(d23, d23));
        }
      }
      _mm_storeu_pd(&sum[0], sum01);
      _mm_storeu_pd(&sum[2], sum23);
#else
      for (int j = 0; j < per_group; ++j) {
        const std::size_t ii = static_cast<std::size_t>(g * per_group + j);
        if (targets.black[ii]) continue;
        for (int c = 0; c < 3; ++c) {
          const std::size_t cc = static_cast<std::size_t>(c);
          const double o = offset[ii][cc], s = targets.source_log2[ii][cc];
          for (int k = 0; k < kShapeLandmarkCount; ++k) {
            const double d = max(log_factor[c][k] + o, kLog2MetricFloor) - s;
            sum[k] = sum[k] + d * d;
          }
        }
      }
#endif
      double best = sum[0];
      for (int k = 1; k < kShapeLandmarkCount; ++k) best = min(best, sum[k]);
      total = total + best;
      if (!(total < bound)) return total;   // cannot end below the bound (also stops on NaN)
    }
    return total;
  }

  template <typename T>
  T operator()(const T* x) const {
    using std::log2;
    T lu[kShapeLandmarkCount], lv[kShapeLandmarkCount];
    decode_landmarks(shape, x, lu, lv);
    T log_factor[kShapeLandmarkCount][3];
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      log_factor[k][0] = log2(max(lv[k], T(kFactorFloor)));
      log_factor[k][1] = log2(max(T(1.0) - lu[k] - lv[k], T(kFactorFloor)));
      log_factor[k][2] = log2(max(lu[k], T(kFactorFloor)));
    }
    T total = T(0.0);
    const int groups = chroma_groups(mode);
    const int per_group = kTexels / groups;   // texels of group g: g * per_group .. (munkberg_layout.h)
    for (int g = 0; g < groups; ++g) {
      T best = T(0.0);
      for (int k = 0; k < kShapeLandmarkCount; ++k) {
        T sum = T(0.0);
        for (int j = 0; j < per_group; ++j) {
          const std::size_t ii = static_cast<std::size_t>(g * per_group + j);
          // Decoded-black texels have a constant error: skipped (a branch on data, not on T).
          if (targets.black[ii]) continue;
          for (int c = 0; c < 3; ++c) {
            const std::size_t cc = static_cast<std::size_t>(c);
            const T decoded = max(log_factor[k][c] + offset[ii][cc], T(kLog2MetricFloor));
            sum = sum + square(decoded - targets.source_log2[ii][cc]);
          }
        }
        best = k == 0 ? sum : min(best, sum);
      }
      total = total + best;
    }
    return total;
  }
};

// Section 7.1's lattice polish of base-colour codes in a ChromaLogError, exactly lattice_polish's full radius-1
// neighbourhood search (solvers/lattice_polish: all 80 neighbours of the centre in lexicographic offset order, the
// strictly best moves the centre, at most `max_passes` passes) with two exact shortcuts: a neighbour is evaluated only
// up to the incumbent's error (ChromaLogError::eval_below), and a neighbour already searched in the previous pass is
// skipped (its error is >= the previous pass's best, which is the current incumbent, so it could not be accepted).
// Same answer as lattice_polish on make_chroma_log_problem(...), bit for bit (tested). Replaces *codes and *error
// when a strictly lower error is found; returns whether it did.
bool polish_log_error_full(const ChromaLogError& error, int max_passes, std::array<int, kBaseCoordinateCount>* codes,
                           double* error_at_codes);

// The Problem on the 7-bit base-colour lattice (the same bounds and lattice as the shape-fit problem).
inline ErrorProblem<ChromaLogError> make_chroma_log_problem(Mode mode, const ShapeTemplate& shape,
                                                            const ChromaLogTargets& targets) {
  return make_problem(ChromaLogError::make(mode, shape, targets), shape_fit_bounds(),
                      shape_fit_lattices(kBaseCoordinateBits));
}

}  // namespace blocklab::munkberg
