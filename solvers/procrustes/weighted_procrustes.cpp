// Weighted 2D orthogonal Procrustes with scaling, through a 2x2 SVD or in closed form
// (solvers/procrustes/weighted_procrustes.h; Munkberg et al. 2008 section 7.1, eqs. 12-15).
#include "solvers/procrustes/weighted_procrustes.h"

#include <Eigen/Dense>
#include <Eigen/SVD>

#include <algorithm>
#include <limits>

namespace blocklab {

const char* to_string(ProcrustesMethod method) {
  return method == ProcrustesMethod::eigen_svd ? "eigen" : "closed_form";
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

// The closed form (header): z = (dot + i cross) / |S|^2 on the weighted-centred sets. Precondition: total weight > 0.
SimilarityFit closed_form_fit(const Point2* source, const Point2* target, const double* weights, int count,
                              double total_weight) {
  double su = 0.0, sv = 0.0, tu = 0.0, tv = 0.0;
  for (int j = 0; j < count; ++j) {
    su += weights[j] * source[j].u;
    sv += weights[j] * source[j].v;
    tu += weights[j] * target[j].u;
    tv += weights[j] * target[j].v;
  }
  su /= total_weight;
  sv /= total_weight;
  tu /= total_weight;
  tv /= total_weight;
  double dot = 0.0, cross = 0.0, source_scatter = 0.0, target_scatter = 0.0;
  for (int j = 0; j < count; ++j) {
    const double s_u = source[j].u - su, s_v = source[j].v - sv;
    const double c_u = target[j].u - tu, c_v = target[j].v - tv;
    dot += weights[j] * (c_u * s_u + c_v * s_v);
    cross += weights[j] * (s_u * c_v - s_v * c_u);
    source_scatter += weights[j] * (s_u * s_u + s_v * s_v);
    target_scatter += weights[j] * (c_u * c_u + c_v * c_v);
  }
  SimilarityFit fit;
  if (!sources_coincide(source_scatter, source, weights, count)) {
    fit.scale_cos = dot / source_scatter;
    fit.scale_sin = cross / source_scatter;
    // Minimum of the functional: |C|^2 - |z|^2 |S|^2 = |C|^2 - (dot^2 + cross^2) / |S|^2 (clamped: rounding can
    // make the difference slightly negative).
    fit.residual = std::max(0.0, target_scatter - (dot * fit.scale_cos + cross * fit.scale_sin));
  } else {
    // The weighted sources coincide: scale and rotation undetermined; minimum-norm choice z = 0 (as eigen_svd).
    fit.residual = target_scatter;
  }
  fit.translation = {tu - (fit.scale_cos * su - fit.scale_sin * sv), tv - (fit.scale_sin * su + fit.scale_cos * sv)};
  return fit;
}

}  // namespace

SimilarityFit fit_weighted_similarity(const Point2* source, const Point2* target, const double* weights, int count,
                                      ProcrustesMethod method) {
  SimilarityFit fit;
  double total_weight = 0.0;
  for (int j = 0; j < count; ++j) total_weight += weights[j];
  if (!(total_weight > 0.0)) {
    // All weights 0: nothing constrains the fit. Scale 0 at the plain mean of the targets (residual 0).
    Eigen::Vector2d plain = Eigen::Vector2d::Zero();
    for (int j = 0; j < count; ++j) plain += Eigen::Vector2d(target[j].u, target[j].v);
    if (count > 0) plain /= count;
    fit.translation = {plain.x(), plain.y()};
    return fit;
  }
  if (method == ProcrustesMethod::closed_form) return closed_form_fit(source, target, weights, count, total_weight);
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
    // The weighted sources coincide (a single correspondence, or coincident template landmarks): scale and rotation
    // are undetermined. Minimum-norm choice: scale 0, every landmark on the weighted target mean.
    fit.residual = target_scatter;
  }
  fit.scale_cos = scale * rotation(0, 0);
  fit.scale_sin = scale * rotation(1, 0);
  const Eigen::Vector2d translation = target_mean - scale * rotation * source_mean;
  fit.translation = {translation.x(), translation.y()};
  return fit;
}

}  // namespace blocklab
