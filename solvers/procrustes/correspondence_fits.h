// Closed-form weighted Procrustes fits of EVERY landmark correspondence of one cluster level from shared tables
// (option svd=tables of the `procrustes` solver; "Practical HDR Texture Compression" (2008) section 7.1, eqs. 12-15:
// "we test all 4! = 24 mappings" per level, and a format ranking 8 landmark sets fits 8 x 61 per mode).
//
// The closed form of weighted_procrustes.h minimises sum_j w_j |c_j - z s_j - t|^2 over complex z and t, with
// z = (dot + i cross) / S on the weighted-centred sets. Centring only the targets is enough: sum_j w_j c'_j = 0, so
//   dot   = sum_j w_j s_j . c'_j,        cross = sum_j w_j s_j x c'_j,
//   mean  = sum_j w_j s_j / W,           S     = sum_j w_j |s_j|^2 - W |mean|^2,
// and every term depends on one (cluster j, landmark l) pair only. A table of those terms for the k clusters x 4
// landmarks turns each fit into sums of k table entries and a few operations (about 4x fewer than fitting each
// correspondence from scratch). The transforms are the closed form's up to rounding, not bit for bit: that is why
// it is an option (svd=tables) and not the default.
//
// Degenerate inputs, as the closed form treats them: all weights 0 gives scale 0 at the plain mean of the centres;
// coincident weighted sources (S at the level of its own cancellation, which is larger here than in the centred
// form: a few ulps of sum_j w_j |s_j|^2) give the minimum-norm z = 0 at the weighted mean of the centres.
#pragma once

#include <array>

#include "core/problem.h"
#include "solvers/procrustes/weighted_procrustes.h"

namespace blocklab {

class CorrespondenceFits {
 public:
  // The level's target side (1 to kFitLandmarkCount cluster centres with their weights >= 0: total weight,
  // weighted mean, centred centres, scatter, as the closed form computes them) and the landmark set whose normalised
  // landmarks (along, across) are the sources. One fitter serves the tables of every landmark set.
  CorrespondenceFits(const SimilarityFitter& targets, const LandmarkCoefficients& landmarks);
  // The same from the centres and weights directly.
  CorrespondenceFits(const Point2* centres, const double* weights, int count, const LandmarkCoefficients& landmarks)
      : CorrespondenceFits(SimilarityFitter(centres, weights, count), landmarks) {}

  // The fit with cluster j matched to landmark choice[j], j < count (distinct landmarks).
  SimilarityFit fit(const int* choice) const;

 private:
  struct Terms {
    double dot = 0.0, cross = 0.0;   // w_j s_l . c'_j and w_j s_l x c'_j
    double mean_u = 0.0, mean_v = 0.0;   // w_j s_l
    double square = 0.0;             // w_j |s_l|^2
  };
  int count_ = 0;
  double total_weight_ = 0.0;
  Point2 target_mean_;           // weighted mean of the centres (plain mean when every weight is 0)
  double target_scatter_ = 0.0;  // sum_j w_j |c'_j|^2
  std::array<std::array<Terms, kFitLandmarkCount>, kFitLandmarkCount> terms_{};   // [cluster][landmark]
};

}  // namespace blocklab
