// Weighted orthogonal Procrustes in 2D with scaling ("Practical HDR Texture Compression" (2008) section 7.1, eqs.
// 12-15; Dryden and Mardia 1998): the similarity transform target_j ~ s R source_j + t (uniform scale s >= 0, proper
// rotation R, translation t) minimising
//     sum_j w_j |target_j - s R source_j - t|^2.
// Both methods centre the sets on their weighted means (C the centred targets, S the centred sources) and differ
// only in how they find s R:
//   eigen_svd    eq. 13 with weights: M = sum_j w_j C_j S_j^T (2x2), SVD M = U diag(sigma_0, sigma_1) V^T
//                (Eigen::JacobiSVD), R = U D V^T with D = diag(1, sign det(U V^T)) so that R is never a reflection,
//                s = (sigma_0 + D_11 sigma_1) / sum_j w_j |S_j|^2.
//   closed_form  (default) the same minimum in closed form: in 2D a scaled proper rotation is multiplication by
//                a complex number z = s e^{i theta}, the functional is linear least squares in z, and
//                    z = (dot + i cross) / sum_j w_j |S_j|^2,   dot = sum_j w_j C_j . S_j,
//                    cross = sum_j w_j (S_j x C_j),
//                i.e. theta = atan2(cross, dot) and s = hypot(dot, cross) / sum_j w_j |S_j|^2. Since
//                sigma_0 + D_11 sigma_1 = max over rotations of trace(R^T M) = hypot(M_00 + M_11, M_10 - M_01) =
//                hypot(dot, cross), both methods give the same transform (tests/unit/test_procrustes.cpp checks
//                they agree to 1e-12); the closed form needs ~30 flops and no iteration.
// In both, t = mean(target) - s R mean(source).
// Weights: w_j multiplies the squared residual of correspondence j, i.e. the cluster's total point weight. The
// paper writes ||W(...)||^2 with W = diag(w_k), which literally squares the weights; weighting the squared
// residual by n_k is the reading under which "duplicating template points according to the number of points in
// the matching cluster" (the paper's equivalent alternative) gives the same answer, and under which the functional
// plus the clusters' scatter is exactly the block's error for that assignment. We use it.
#pragma once

#include "core/problem.h"

namespace blocklab {

struct SimilarityFit {
  // The transform as a complex factor z = s (cos theta + i sin theta) and a translation: p -> z p + t.
  double scale_cos = 0.0;   // Re z = s cos theta
  double scale_sin = 0.0;   // Im z = s sin theta
  Point2 translation;
  // The minimised functional sum_j w_j |target_j - z source_j - t|^2 (>= 0).
  double residual = 0.0;

  Point2 apply(Point2 p) const {
    return {scale_cos * p.u - scale_sin * p.v + translation.u, scale_sin * p.u + scale_cos * p.v + translation.v};
  }
};

// Degenerate inputs (each handled at its line in weighted_procrustes.cpp):
//   * all weights 0: nothing constrains the fit; scale 0 and t = plain mean of the targets;
//   * the weighted sources coincide (one correspondence with weight, or coincident landmarks): scale and
//     rotation are undetermined; the minimum-norm solution scale 0, t = weighted target mean is returned;
//   * M of rank 1 (collinear sources or targets): the SVD still gives the unique best rotation (D fixes the
//     arbitrary sign of the null direction); the closed form needs no special case (dot, cross still define z);
//   * M = 0 (e.g. all targets coincide): scale 0, every rotation is optimal, R = I (closed form: z = 0).
// tables: the closed form of every correspondence of a cluster level from tables shared by all of them
// (correspondence_fits.h; the same transforms up to rounding). A single fit has nothing to share:
// fit_weighted_similarity treats `tables` as `closed_form`.
enum class ProcrustesMethod { eigen_svd, closed_form, tables };
// "eigen", "closed_form", "tables" (the option values of `svd`)
const char* to_string(ProcrustesMethod method);

SimilarityFit fit_weighted_similarity(const Point2* source, const Point2* target, const double* weights, int count,
                                      ProcrustesMethod method = ProcrustesMethod::closed_form);

// Many closed-form fits to ONE weighted target set: the candidate enumeration fits every ordered landmark choice of
// every landmark set to the same cluster centres (a format ranking 8 sets: up to 8 x 61 fits per cluster level), so the
// target side (total weight, weighted mean, centred targets, their scatter) is computed once here. fit(source)
// returns exactly fit_weighted_similarity(source, target, weights, count, closed_form): the same operations in the
// same order on the same values, bit for bit (tests/unit/test_procrustes.cpp checks it); only the work is shared.
// Up to kFitLandmarkCount correspondences.
class SimilarityFitter {
 public:
  SimilarityFitter(const Point2* target, const double* weights, int count);
  SimilarityFit fit(const Point2* source) const;

  // The shared target side (correspondence_fits.h builds its tables from it).
  int count() const { return count_; }
  double weight(int j) const { return weights_[j]; }
  double total_weight() const { return total_weight_; }
  Point2 target_mean() const { return target_mean_; }
  double target_scatter() const { return target_scatter_; }
  Point2 centred_target(int j) const { return {centred_u_[j], centred_v_[j]}; }

 private:
  int count_ = 0;
  double total_weight_ = 0.0;
  double weights_[kFitLandmarkCount] = {};
  // The weighted target mean; with all weights 0 the plain mean, which is then every fit's translation (scale 0).
  Point2 target_mean_;
  double centred_u_[kFitLandmarkCount] = {}, centred_v_[kFitLandmarkCount] = {};
  double target_scatter_ = 0.0;
};

}  // namespace blocklab
