// The candidate transforms of one cluster level (the `procrustes` solver's steps 1 and 2, procrustes_solver.h;
// "Practical HDR Texture Compression", CGF 27(6), 2008, section 7.1, eqs. 12-15): the nested PNN + k-means cluster
// levels of a point set, and per level one weighted Procrustes fit for every ordered choice of distinct landmarks
// of a LandmarkCoefficients set (core/problem.h). Callers that rank the candidates of several landmark sets from
// ONE clustering build the level's targets and fitter once (LevelTargets) and reuse them for every set.
#pragma once

#include <array>
#include <vector>

#include "core/problem.h"
#include "solvers/procrustes/point_clustering.h"
#include "solvers/procrustes/procrustes_refinement.h"
#include "solvers/procrustes/procrustes_solver.h"
#include "solvers/procrustes/weighted_procrustes.h"

namespace blocklab {

// Cluster levels k = 1 .. min(options.max_clusters, points) (nested PNN partitions, each refined by
// options.kmeans_iterations Lloyd iterations): levels[k - 1] has k clusters.
std::vector<PointClustering> procrustes_cluster_levels(const std::vector<Point2>& points,
                                                       const std::vector<double>& weights,
                                                       const ProcrustesOptions& options);
// The same into `levels` (reused storage: no allocation once warmed up).
void procrustes_cluster_levels(const std::vector<Point2>& points, const std::vector<double>& weights,
                               const ProcrustesOptions& options, std::vector<PointClustering>& levels);

// A level's cluster centres and weights: the targets of every candidate fit of the level.
struct LevelTargets {
  int count = 0;
  std::array<Point2, kFitLandmarkCount> centres;
  std::array<double, kFitLandmarkCount> weights{};

  explicit LevelTargets(const PointClustering& level);
  SimilarityFitter fitter() const { return SimilarityFitter(centres.data(), weights.data(), count); }
};

// Appends the candidates of `landmarks` on one cluster level (k = its cluster count): one weighted Procrustes fit
// per ordered choice of k distinct landmarks, in lexicographic order (4!/(4-k)! of them; one for k = 1, where the
// fit is scale 0 at the centre whatever the landmark). Bound = the fit's residual + the level's scatter.
void append_level_candidates(const PointClustering& level, const LandmarkCoefficients& landmarks,
                             ProcrustesMethod method, std::vector<ProcrustesCandidate>* out);
// The same with the level's targets and, for the closed form and the tables, their fitter built by the caller
// (nullptr: the method's own fit_weighted_similarity), so that several landmark sets share them.
void append_level_candidates(const PointClustering& level, const LevelTargets& targets,
                             const SimilarityFitter* fitter, const LandmarkCoefficients& landmarks,
                             ProcrustesMethod method, std::vector<ProcrustesCandidate>* out);

// Whether a candidate's bound ties with `last` (the bound of the last candidate kept or evaluated): within 1e-9
// relative, plus 1e-15 absolute (squared distance, far below one 8-bit step (1/255)^2 ~ 1.5e-5) for bounds that
// are 0 up to rounding. Exact fits (two colours fit by any pair of landmarks) all tie at ~0.
bool procrustes_bound_ties(double bound, double last);

}  // namespace blocklab
