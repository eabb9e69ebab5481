// Closed-form weighted Procrustes fits of every landmark correspondence of a cluster level from shared tables
// (solvers/procrustes/correspondence_fits.h; "Practical HDR Texture Compression" (2008) section 7.1, eqs. 12-15).
#include "solvers/procrustes/correspondence_fits.h"

#include <algorithm>
#include <limits>

#include "core/error.h"

namespace blocklab {

CorrespondenceFits::CorrespondenceFits(const SimilarityFitter& targets, const LandmarkCoefficients& landmarks)
    : count_(targets.count()),
      total_weight_(targets.total_weight()),
      target_mean_(targets.target_mean()),
      target_scatter_(targets.target_scatter()) {
  if (count_ < 1 || count_ > kFitLandmarkCount)
    fail("procrustes", "internal: CorrespondenceFits takes 1 to 4 cluster centres");
  // All weights 0: nothing constrains the fit; fit() answers scale 0 at the plain mean (the fitter's mean then).
  if (!(total_weight_ > 0.0)) return;
  for (int j = 0; j < count_; ++j) {
    const double w = targets.weight(j);
    const Point2 c = targets.centred_target(j);
    for (int l = 0; l < kFitLandmarkCount; ++l) {
      const double su = landmarks.along(l), sv = landmarks.across(l);
      Terms& t = terms_[static_cast<std::size_t>(j)][static_cast<std::size_t>(l)];
      t.dot = w * (su * c.u + sv * c.v);
      t.cross = w * (su * c.v - sv * c.u);
      t.mean_u = w * su;
      t.mean_v = w * sv;
      t.square = w * (su * su + sv * sv);
    }
  }
}

SimilarityFit CorrespondenceFits::fit(const int* choice) const {
  SimilarityFit fit;
  if (!(total_weight_ > 0.0)) {
    fit.translation = target_mean_;   // all weights 0: scale 0 at the plain mean
    return fit;
  }
  double dot = 0.0, cross = 0.0, mean_u = 0.0, mean_v = 0.0, square = 0.0;
  for (int j = 0; j < count_; ++j) {
    const Terms& t = terms_[static_cast<std::size_t>(j)][static_cast<std::size_t>(choice[j])];
    dot += t.dot;
    cross += t.cross;
    mean_u += t.mean_u;
    mean_v += t.mean_v;
    square += t.square;
  }
  mean_u /= total_weight_;
  mean_v /= total_weight_;
  const double source_scatter = square - total_weight_ * (mean_u * mean_u + mean_v * mean_v);
  // Coincident weighted sources (one cluster with weight, or coincident landmarks): the difference above is then
  // cancellation noise of a few ulps of `square`; 64 ulps is far below any real spread of landmarks
  // (which are O(1) apart) unless a cluster holds under ~1e-13 of the weight. NaN also takes this branch.
  if (source_scatter > 64.0 * std::numeric_limits<double>::epsilon() * square) {
    fit.scale_cos = dot / source_scatter;
    fit.scale_sin = cross / source_scatter;
    // |C|^2 - (dot^2 + cross^2) / S, clamped: rounding can make it slightly negative.
    fit.residual = std::max(0.0, target_scatter_ - (dot * fit.scale_cos + cross * fit.scale_sin));
  } else {
    fit.residual = target_scatter_;   // minimum-norm z = 0: every landmark on the weighted mean
  }
  fit.translation = {target_mean_.u - (fit.scale_cos * mean_u - fit.scale_sin * mean_v),
                     target_mean_.v - (fit.scale_sin * mean_u + fit.scale_cos * mean_v)};
  return fit;
}

}  // namespace blocklab
