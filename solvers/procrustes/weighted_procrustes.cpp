// Weighted 2D orthogonal Procrustes with scaling, through a 2x2 SVD or in closed form
// (solvers/procrustes/weighted_procrustes.h; "Practical HDR Texture Compression" (2008) section 7.1, eqs. 12-15).
#include "solvers/procrustes/weighted_procrustes.h"

#include <Eigen/Dense>
#include <Eigen/SVD>

#include <algorithm>
#include <limits>

#include "core/error.h"

namespace blocklab {

const char* to_string(ProcrustesMethod method) {
  switch (method) {
    case ProcrustesMethod::eigen_svd:
      return "eigen";
    case ProcrustesMethod::tables:
      return "tables";
    case ProcrustesMethod::closed_form:
      break;
  }
  return "closed_form";
}

namespace {

// Whether the weighted sources coincide up to rounding: their centred scatter is at the level of the rounding noise
// of centring (each centred coordinate carries an error of a few ulps of the raw coordinate, so the scatter of
// coincident sources is at most ~(4 eps)^2 times their raw second moment). Scale and rotation are then undetermined
// (any z fits equally) and both methods return the minimum-norm choice z = 0 instead of a ratio of rounding noise.
bool sources_coincide(double source_scatter, const Point2* source, const double* weights, int count) {
  double raw = 0.0;
  for (int j = 0; j < count; ++j) raw += weights[j] * (source[j].u * source[j].u + source[j].v * source[j].v);
  const double eps = std::numeric_limits<double>::epsilon();
  return !(source_scatter > 16.0 * eps * eps * raw);
}

// The target side of the closed form: weighted mean and scatter of the targets. Precondition: total weight > 0.
struct TargetSide {
  Point2 mean;
  double scatter = 0.0;
};

TargetSide target_side(const Point2* target, const double* weights, int count, double total_weight) {
  TargetSide side;
  double tu = 0.0, tv = 0.0;
  for (int j = 0; j < count; ++j) {
    tu += weights[j] * target[j].u;
    tv += weights[j] * target[j].v;
  }
  side.mean = {tu / total_weight, tv / total_weight};
  for (int j = 0; j < count; ++j) {
    const double c_u = target[j].u - side.mean.u, c_v = target[j].v - side.mean.v;
    side.scatter += weights[j] * (c_u * c_u + c_v * c_v);
  }
  return side;
}

// The closed form (header): z = (dot + i cross) / |S|^2 on the weighted-centred sets, given the target side;
// centred(j) returns target j minus the target mean (computed on the fly or cached: the same values). Every sum
// has its own accumulator and adds its terms in index order, so splitting the target sums off changes no bit.
// Precondition: total weight > 0.
template <typename CentredTarget>
SimilarityFit closed_form_fit(const Point2* source, const double* weights, int count, double total_weight,
                              const TargetSide& target, CentredTarget centred) {
  double su = 0.0, sv = 0.0;
  for (int j = 0; j < count; ++j) {
    su += weights[j] * source[j].u;
    sv += weights[j] * source[j].v;
  }
  su /= total_weight;
  sv /= total_weight;
  double dot = 0.0, cross = 0.0, source_scatter = 0.0;
  for (int j = 0; j < count; ++j) {
    const double s_u = source[j].u - su, s_v = source[j].v - sv;
    const Point2 c = centred(j);
    dot += weights[j] * (c.u * s_u + c.v * s_v);
    cross += weights[j] * (s_u * c.v - s_v * c.u);
    source_scatter += weights[j] * (s_u * s_u + s_v * s_v);
  }
  SimilarityFit fit;
  if (!sources_coincide(source_scatter, source, weights, count)) {
    fit.scale_cos = dot / source_scatter;
    fit.scale_sin = cross / source_scatter;
    // Minimum of the functional: |C|^2 - |z|^2 |S|^2 = |C|^2 - (dot^2 + cross^2) / |S|^2 (clamped: rounding can
    // make the difference slightly negative).
    fit.residual = std::max(0.0, target.scatter - (dot * fit.scale_cos + cross * fit.scale_sin));
  } else {
    // The weighted sources coincide: scale and rotation undetermined; minimum-norm choice z = 0 (as eigen_svd).
    fit.residual = target.scatter;
  }
  fit.translation = {target.mean.u - (fit.scale_cos * su - fit.scale_sin * sv),
                     target.mean.v - (fit.scale_sin * su + fit.scale_cos * sv)};
  return fit;
}

// All weights 0: nothing constrains the fit. Scale 0 at the plain mean of the targets (residual 0).
Point2 plain_mean(const Point2* target, int count) {
  Eigen::Vector2d plain = Eigen::Vector2d::Zero();
  for (int j = 0; j < count; ++j) plain += Eigen::Vector2d(target[j].u, target[j].v);
  if (count > 0) plain /= count;
  return {plain.x(), plain.y()};
}

}  // namespace

SimilarityFit fit_weighted_similarity(const Point2* source, const Point2* target, const double* weights, int count,
                                      ProcrustesMethod method) {
  SimilarityFit fit;
  double total_weight = 0.0;
  for (int j = 0; j < count; ++j) total_weight += weights[j];
  if (!(total_weight > 0.0)) {
    fit.translation = plain_mean(target, count);   // all weights 0 (plain_mean)
    return fit;
  }
  if (method != ProcrustesMethod::eigen_svd) {   // closed_form, and tables for a single fit
    const TargetSide side = target_side(target, weights, count, total_weight);
    return closed_form_fit(source, weights, count, total_weight, side, [&](int j) {
      return Point2{target[j].u - side.mean.u, target[j].v - side.mean.v};
    });
  }
  Eigen::Vector2d source_mean = Eigen::Vector2d::Zero(), target_mean = Eigen::Vector2d::Zero();
  for (int j = 0; j < count; ++j) {
    source_mean += weights[j] * Eigen::Vector2d(source[j].u, source[j].v);
    target_mean += weights[j] * Eigen::Vector2d(target[j].u, target[j].v);
  }
  source_mean /= total_weight;
  target_mean /= total_weight;

  Eigen::Matrix2d cross = Eigen::Matrix2d::Zero();   // M = sum_j w_j C_j S_j^T
  double source_scatter = 0.0, target_scatter = 0.0;
  for (int j = 0; j < count; ++j) {
    const Eigen::Vector2d s = Eigen::Vector2d(source[j].u, source[j].v) - source_mean;
    const Eigen::Vector2d c = Eigen::Vector2d(target[j].u, target[j].v) - target_mean;
    cross += weights[j] * c * s.transpose();
    source_scatter += weights[j] * s.squaredNorm();
    target_scatter += weights[j] * c.squaredNorm();
  }

  Eigen::Matrix2d rotation = Eigen::Matrix2d::Identity();
  double scale = 0.0;
  if (!sources_coincide(source_scatter, source, weights, count)) {
    const Eigen::JacobiSVD<Eigen::Matrix2d> svd(cross, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Matrix2d& u = svd.matrixU();
    const Eigen::Matrix2d& v = svd.matrixV();
    // Reflection excluded: when U V^T is a reflection, flip the direction of the smaller singular value. This also
    // settles rank-1 M (collinear points), whose second singular vectors are only defined up to sign.
    const double handedness = (u * v.transpose()).determinant() < 0.0 ? -1.0 : 1.0;
    const Eigen::Vector2d sigma = svd.singularValues();
    rotation = u * Eigen::Vector2d(1.0, handedness).asDiagonal() * v.transpose();
    // sigma_0 >= sigma_1 >= 0, so the scale is never negative; M = 0 gives scale 0 (any rotation is optimal and
    // the SVD's identity factors give R = I).
    scale = std::max(0.0, (sigma(0) + handedness * sigma(1)) / source_scatter);
    // Minimum of the functional: |C|^2 - s^2 |S|^2 (clamped: rounding can make the difference slightly negative).
    fit.residual = std::max(0.0, target_scatter - scale * scale * source_scatter);
  } else {
    // The weighted sources coincide (a single correspondence, or coincident landmarks): scale and rotation
    // are undetermined. Minimum-norm choice: scale 0, every landmark on the weighted target mean.
    fit.residual = target_scatter;
  }
  fit.scale_cos = scale * rotation(0, 0);
  fit.scale_sin = scale * rotation(1, 0);
  const Eigen::Vector2d translation = target_mean - scale * rotation * source_mean;
  fit.translation = {translation.x(), translation.y()};
  return fit;
}

SimilarityFitter::SimilarityFitter(const Point2* target, const double* weights, int count) : count_(count) {
  if (count < 0 || count > kFitLandmarkCount) fail("procrustes", "internal: SimilarityFitter takes up to 4 points");
  for (int j = 0; j < count; ++j) {
    weights_[j] = weights[j];
    total_weight_ += weights[j];
  }
  if (!(total_weight_ > 0.0)) {
    target_mean_ = plain_mean(target, count);   // every fit is scale 0 there
    return;
  }
  const TargetSide side = target_side(target, weights, count, total_weight_);
  target_mean_ = side.mean;
  target_scatter_ = side.scatter;
  for (int j = 0; j < count; ++j) {
    centred_u_[j] = target[j].u - side.mean.u;
    centred_v_[j] = target[j].v - side.mean.v;
  }
}

SimilarityFit SimilarityFitter::fit(const Point2* source) const {
  if (!(total_weight_ > 0.0)) {
    SimilarityFit fit;
    fit.translation = target_mean_;
    return fit;
  }
  const TargetSide side{target_mean_, target_scatter_};
  return closed_form_fit(source, weights_, count_, total_weight_, side,
                         [this](int j) { return Point2{centred_u_[j], centred_v_[j]}; });
}

}  // namespace blocklab
