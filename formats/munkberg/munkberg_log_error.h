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
// The error is a choice (option `error`, formats/common/hdr_block_error.h): each squared term is multiplied by the
// weight of its source value (ChromaLogTargets::weight): 1 everywhere for log2_floor (the sum above), 0 on source
// values <= 0 for log2_skip, and the exposure weight W_log2 of the source value for mpsnr_weighted.
//
// One functor templated on the scalar type (core/problem.h rules), so the Problem also has interval enclosures and
// Jet gradients; it differs from decoding + the metric only by the float rounding of decoded values.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/problem.h"
#include "core/scalar.h"
#include "formats/common/hdr_block_error.h"
#include "formats/munkberg/munkberg_block.h"
#include "formats/munkberg/munkberg_luminance.h"

namespace blocklab::munkberg {

constexpr double kFactorFloor = 0x1p-60;
// The metric's floor in log2 (-24): the level a true-black luminance is scored at (munkberg_luminance.h).
constexpr double kLog2MetricFloor = kBlackLog2;

struct ChromaLogTargets {
  std::array<double, kTexels> log2_luminance{};            // decoded log2 Y per texel
  std::array<bool, kTexels> black{};                       // decoded luminance is true black
  std::array<std::array<double, 3>, kTexels> source_log2{};   // log2 max(source channel, 2^-24)
  // Weight of each texel's and channel's squared difference (the `error` choice; all 1: log2_floor).
  std::array<std::array<double, 3>, kTexels> weight = unit_weights();

  static std::array<std::array<double, 3>, kTexels> unit_weights() {
    std::array<std::array<double, 3>, kTexels> ones{};
    for (auto& texel : ones) texel = {1.0, 1.0, 1.0};
    return ones;
  }
  // The weights of `error` for the source texels (linear RGB; log2_domain_weight of each channel value).
  void set_error_weights(const BlockTexels& source, HdrBlockError error) {
    for (std::size_t i = 0; i < static_cast<std::size_t>(kTexels); ++i)
      for (std::size_t c = 0; c < 3; ++c) weight[i][c] = log2_domain_weight(error, source.rgba[i][c]);
  }

  // The error of the texels whose luminance decodes to true black, which ChromaLogError leaves out: every channel
  // decodes to 0, i.e. the floor, whatever the chroma (a constant of the block and mode).
  double black_texels_error() const {
    double sum = 0.0;
    for (int i = 0; i < kTexels; ++i)
      if (black[static_cast<std::size_t>(i)])
        for (std::size_t c = 0; c < 3; ++c) {
          const double d = kLog2MetricFloor - source_log2[static_cast<std::size_t>(i)][c];
          sum += weight[static_cast<std::size_t>(i)][c] * (d * d);
        }
    return sum;
  }
};

// log2 of the Rec. 601 weights (log2 w_R, log2 w_G, log2 w_B), computed once (the same values as computing them per
// use); the offsets below and the encoder's index assignment (munkberg_encoder.cpp) subtract them.
inline const std::array<double, 3>& log2_rec601_weights() {
  static const std::array<double, 3> weights = {std::log2(kRec601WeightR), std::log2(kRec601WeightG),
                                                std::log2(kRec601WeightB)};
  return weights;
}

struct ChromaLogError {
  static constexpr int kDim = kBaseCoordinateCount;

  Mode mode = Mode::shape_i;
  ShapeTemplate shape;
  ChromaLogTargets targets;
  // Per texel and channel: log2 Y_i - log2 w_c (precomputed).
  std::array<std::array<double, 3>, kTexels> offset{};
#if defined(__SSE2__)
  // offset and targets.source_log2 with each value in both lanes, for the SSE2 group sums (loads instead of a
  // broadcast per texel and channel; the same values).
  struct alignas(16) Lanes {
    double value[2];
  };
  std::array<std::array<Lanes, 3>, kTexels> offset_lanes{};
  std::array<std::array<Lanes, 3>, kTexels> source_lanes{};
  std::array<std::array<Lanes, 3>, kTexels> weight_lanes{};
  // The same values with two chroma groups side by side, for group_sums_of_factors: pair p holds groups 2p (lane 0)
  // and 2p + 1 (lane 1), texel j of each group at [p][j] (a group has at most 2 texels: shape II's pairs). `live`
  // is all ones for a texel that is not decoded black and all zeros for one that is (its square is masked to +0.0).
  static constexpr int kMaxTexelsPerGroup = 2;
  struct alignas(16) LaneMask {
    std::uint64_t bits[2];
  };
  std::array<std::array<std::array<Lanes, 3>, kMaxTexelsPerGroup>, kTexels / 2> pair_offset{};
  std::array<std::array<std::array<Lanes, 3>, kMaxTexelsPerGroup>, kTexels / 2> pair_source{};
  std::array<std::array<std::array<Lanes, 3>, kMaxTexelsPerGroup>, kTexels / 2> pair_weight{};
  std::array<std::array<LaneMask, kMaxTexelsPerGroup>, kTexels / 2> pair_live{};
#endif

  static ChromaLogError make(Mode mode, const ShapeTemplate& shape, const ChromaLogTargets& targets) {
    ChromaLogError error;
    error.mode = mode;
    error.shape = shape;
    error.targets = targets;
    const std::array<double, 3>& log2_weights = log2_rec601_weights();
    for (int i = 0; i < kTexels; ++i)
      for (int c = 0; c < 3; ++c)
        error.offset[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)] =
            targets.log2_luminance[static_cast<std::size_t>(i)] - log2_weights[static_cast<std::size_t>(c)];
#if defined(__SSE2__)
    for (std::size_t i = 0; i < kTexels; ++i)
      for (std::size_t c = 0; c < 3; ++c) {
        error.offset_lanes[i][c] = {{error.offset[i][c], error.offset[i][c]}};
        error.source_lanes[i][c] = {{targets.source_log2[i][c], targets.source_log2[i][c]}};
        error.weight_lanes[i][c] = {{targets.weight[i][c], targets.weight[i][c]}};
      }
    const std::size_t per_group = static_cast<std::size_t>(kTexels / chroma_groups(mode));
    static_assert(kTexels / kShape1ChromaGroups <= kMaxTexelsPerGroup && kTexels / kShape2ChromaGroups <= kMaxTexelsPerGroup &&
                      kShape1ChromaGroups % 2 == 0 && kShape2ChromaGroups % 2 == 0,
                  "group pairs: an even number of groups of at most kMaxTexelsPerGroup texels");
    for (std::size_t p = 0; p < static_cast<std::size_t>(chroma_groups(mode) / 2); ++p)
      for (std::size_t j = 0; j < per_group; ++j)
        for (std::size_t lane = 0; lane < 2; ++lane) {
          const std::size_t i = (2 * p + lane) * per_group + j;
          for (std::size_t c = 0; c < 3; ++c) {
            error.pair_offset[p][j][c].value[lane] = error.offset[i][c];
            error.pair_source[p][j][c].value[lane] = targets.source_log2[i][c];
            error.pair_weight[p][j][c].value[lane] = targets.weight[i][c];
          }
          error.pair_live[p][j].bits[lane] = targets.black[i] ? 0 : ~std::uint64_t{0};
        }
#endif
    return error;
  }

  // operator()<double> with an early exit: the exact error when it is below `bound`, otherwise a partial sum that is
  // already >= bound (every group's minimum is >= 0 and adding a non-negative double never lowers a sum, so the full
  // error is >= bound too). The same operations in the same order as operator(), so values below the bound are
  // bit-identical to it.
  double eval_below(const double* x, double bound) const {
    double lu[kShapeLandmarkCount], lv[kShapeLandmarkCount];
    decode_landmarks(shape, x, lu, lv);
    double log_factor[kShapeLandmarkCount][3];
    for (int k = 0; k < kShapeLandmarkCount; ++k) landmark_log_factors(lu[k], lv[k], log_factor[k]);
    const double* const factors[kShapeLandmarkCount] = {log_factor[0], log_factor[1], log_factor[2], log_factor[3]};
    double total = 0.0;
    const int groups = chroma_groups(mode);
    for (int g = 0; g < groups; ++g) {
      // Each landmark's sum adds its terms in operator()'s order (texels of the group, then R, G, B); landmarks
      // (0, 1) and (2, 3) side by side.
      double sum[kShapeLandmarkCount];
      landmark_group_sums_side_by_side<2>(factors, g, sum);
      double best = sum[0];
      for (int k = 1; k < kShapeLandmarkCount; ++k) best = min(best, sum[k]);
      total = total + best;
      if (!(total < bound)) return total;   // cannot end below the bound (also stops on NaN)
    }
    return total;
  }

  // One landmark's share of eval_below: log2 of its three chroma factors (eval_below's log_factor column), and per
  // chroma group the sum over the group's non-black texels and R, G, B of (max(log2 f_c + offset, -24) - s)^2 with
  // exactly eval_below's operations in its order (one lane of its SSE2 pairs). So the group sums are bit-identical to
  // those eval_below forms for a landmark at (u, v); the polish caches them for the base colours (landmarks 0 and 1),
  // which take only 9 positions each in a radius-1 neighbourhood.
  static void landmark_log_factors(double u, double v, double log_factor[3]) {
    log_factor[0] = std::log2(max(v, kFactorFloor));
    log_factor[1] = std::log2(max(1.0 - u - v, kFactorFloor));
    log_factor[2] = std::log2(max(u, kFactorFloor));
  }
  double landmark_group_sum(const double log_factor[3], int group) const {
    const int per_group = kTexels / chroma_groups(mode);
    double sum = 0.0;
    for (int j = 0; j < per_group; ++j) {
      const std::size_t ii = static_cast<std::size_t>(group * per_group + j);
      if (targets.black[ii]) continue;
      for (int c = 0; c < 3; ++c) {
        const std::size_t cc = static_cast<std::size_t>(c);
        const double d = max(log_factor[c] + offset[ii][cc], kLog2MetricFloor) - targets.source_log2[ii][cc];
        sum = sum + targets.weight[ii][cc] * (d * d);
      }
    }
    return sum;
  }
  // landmark_group_sum for 2 kPairs landmarks at once (factors[k] = landmark k's log_factor), in one pass over the
  // group's texels with the landmark pairs in SSE2 lanes where available: lane-wise the same IEEE additions,
  // subtractions and products as landmark_group_sum, and max_pd(a, -24) equals max(a, -24) for every non-NaN a
  // (equal operands are equal values).
  template <int kPairs>
  void landmark_group_sums_side_by_side(const double* const factors[2 * kPairs], int group, double sums[2 * kPairs]) const {
#if defined(__SSE2__)
    const int per_group = kTexels / chroma_groups(mode);
    __m128d sum[kPairs], factor[kPairs][3];
    for (int p = 0; p < kPairs; ++p) {
      sum[p] = _mm_setzero_pd();
      for (int c = 0; c < 3; ++c) factor[p][c] = _mm_set_pd(factors[2 * p + 1][c], factors[2 * p][c]);
    }
    const __m128d floor = _mm_set1_pd(kLog2MetricFloor);
    for (int j = 0; j < per_group; ++j) {
      const std::size_t ii = static_cast<std::size_t>(group * per_group + j);
      if (targets.black[ii]) continue;
      for (int c = 0; c < 3; ++c) {
        const std::size_t cc = static_cast<std::size_t>(c);
        const __m128d o = _mm_load_pd(offset_lanes[ii][cc].value), s = _mm_load_pd(source_lanes[ii][cc].value);
        const __m128d w = _mm_load_pd(weight_lanes[ii][cc].value);
        for (int p = 0; p < kPairs; ++p) {
          const __m128d d = _mm_sub_pd(_mm_max_pd(_mm_add_pd(factor[p][c], o), floor), s);
          sum[p] = _mm_add_pd(sum[p], _mm_mul_pd(w, _mm_mul_pd(d, d)));
        }
      }
    }
    for (int p = 0; p < kPairs; ++p) _mm_storeu_pd(&sums[2 * p], sum[p]);
#else
    for (int k = 0; k < 2 * kPairs; ++k) sums[k] = landmark_group_sum(factors[k], group);
#endif
  }
  void landmark_group_sums(double u, double v, double sums[kTexels]) const {
    double log_factor[3];
    landmark_log_factors(u, v, log_factor);
    group_sums_of_factors(log_factor, sums);
  }
  // landmark_group_sum of every chroma group for one landmark's log factors, with groups 2p and 2p + 1 in the two
  // SSE2 lanes where available (pair_offset): each lane does landmark_group_sum's IEEE operations in its order (the
  // max as in landmark_group_sums_side_by_side). A decoded-black texel, which landmark_group_sum skips, adds its
  // square masked to +0.0 instead: a sum starts at +0.0 and adds squares, so it is never -0.0 and sum + 0.0 == sum
  // bit for bit (a NaN or infinite square of a black texel's lane is masked too).
  void group_sums_of_factors(const double log_factor[3], double sums[kTexels]) const {
#if defined(__SSE2__)
    const int per_group = kTexels / chroma_groups(mode);
    const __m128d floor = _mm_set1_pd(kLog2MetricFloor);
    const __m128d factor[3] = {_mm_set1_pd(log_factor[0]), _mm_set1_pd(log_factor[1]), _mm_set1_pd(log_factor[2])};
    for (int p = 0; p < chroma_groups(mode) / 2; ++p) {
      const std::size_t pp = static_cast<std::size_t>(p);
      __m128d sum = _mm_setzero_pd();
      for (int j = 0; j < per_group; ++j) {
        const std::size_t jj = static_cast<std::size_t>(j);
        const __m128d live = _mm_castsi128_pd(_mm_load_si128(reinterpret_cast<const __m128i*>(pair_live[pp][jj].bits)));
        for (std::size_t c = 0; c < 3; ++c) {
          const __m128d o = _mm_load_pd(pair_offset[pp][jj][c].value), s = _mm_load_pd(pair_source[pp][jj][c].value);
          const __m128d w = _mm_load_pd(pair_weight[pp][jj][c].value);
          const __m128d d = _mm_sub_pd(_mm_max_pd(_mm_add_pd(factor[c], o), floor), s);
          sum = _mm_add_pd(sum, _mm_and_pd(_mm_mul_pd(w, _mm_mul_pd(d, d)), live));
        }
      }
      _mm_storeu_pd(&sums[2 * p], sum);
    }
#else
    for (int g = 0; g < chroma_groups(mode); ++g) sums[g] = landmark_group_sum(log_factor, g);
#endif
  }

  // eval_below at the decoded landmarks (lu, lv) (decode_landmarks of the parameters) when landmarks 0 and 1's group
  // sums are already known (landmark_group_sums at (lu[0], lv[0]) and (lu[1], lv[1])): only landmarks 2 and 3 are
  // computed, group by group up to the early exit. The same value as eval_below below the bound, bit for bit, and
  // >= bound otherwise.
  double eval_below_given_base_sums(const double* lu, const double* lv, const double* sums0, const double* sums1,
                                    double bound) const {
    double log_factor2[3], log_factor3[3];
    landmark_log_factors(lu[2], lv[2], log_factor2);
    landmark_log_factors(lu[3], lv[3], log_factor3);
    const double* const factors[2] = {log_factor2, log_factor3};
    double total = 0.0;
    const int groups = chroma_groups(mode);
    for (int g = 0; g < groups; ++g) {
      // eval_below's minimum: landmark 0's sum, then the min with landmarks 1, 2, 3 in turn.
      double best = sums0[g];
      best = min(best, sums1[g]);
      double sum23[2];
      landmark_group_sums_side_by_side<1>(factors, g, sum23);
      best = min(best, sum23[0]);
      best = min(best, sum23[1]);
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
            sum = sum + T(targets.weight[ii][cc]) * square(decoded - targets.source_log2[ii][cc]);
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
// Same answer as lattice_polish on make_chroma_log_problem(...), bit for bit (tested). *error_at_codes is the error at
// *codes on entry (+inf or NaN: unknown, evaluated here). Replaces *codes and *error when a strictly lower error is
// found; returns whether it did. `cache` (munkberg_base_colour_sums.h: the base colours'
// error shares, one per block and mode) may be shared with other evaluations of the same block and mode; without one
// the polish keeps its own.
class BaseColourSums;
bool polish_log_error_full(const ChromaLogError& error, int max_passes, std::array<int, kBaseCoordinateCount>* codes,
                           double* error_at_codes, BaseColourSums* cache = nullptr);
// lattice_polish's coordinate descent (radius `radius` >= 1, at most `max_passes` passes; what it runs when the full
// neighbourhood is over its limit) in a ChromaLogError, through the same cache and early exit. Same answer as
// lattice_polish with those options on make_chroma_log_problem(...), bit for bit (tested); same contract as
// polish_log_error_full.
bool polish_log_error_coordinate(const ChromaLogError& error, int radius, int max_passes,
                                 std::array<int, kBaseCoordinateCount>* codes, double* error_at_codes,
                                 BaseColourSums* cache = nullptr);

// The Problem on the 7-bit base-colour lattice (the same bounds and lattice as the shape-fit problem).
inline ErrorProblem<ChromaLogError> make_chroma_log_problem(Mode mode, const ShapeTemplate& shape,
                                                            const ChromaLogTargets& targets) {
  return make_problem(ChromaLogError::make(mode, shape, targets), shape_fit_bounds(),
                      shape_fit_lattices(kBaseCoordinateBits));
}

}  // namespace blocklab::munkberg
