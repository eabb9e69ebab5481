// The candidates of one cluster level (solvers/procrustes/level_candidates.h; "Practical HDR Texture Compression",
// 2008, section 7.1, eqs. 12-15).
#include "solvers/procrustes/level_candidates.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "solvers/procrustes/correspondence_fits.h"

namespace blocklab {

namespace {

using Permutation = std::array<int, kFitLandmarkCount>;

// The 24 permutations of the landmarks in lexicographic order. Ordered choices of k landmarks are their length-k
// prefixes, which appear in runs of (4 - k)! consecutive permutations.
const std::array<Permutation, 24>& landmark_permutations() {
  static const std::array<Permutation, 24> table = [] {
    std::array<Permutation, 24> out{};
    Permutation p = {0, 1, 2, 3};
    for (std::size_t i = 0; i < out.size(); ++i) {
      out[i] = p;
      std::next_permutation(p.begin(), p.end());
    }
    return out;
  }();
  return table;
}

int factorial(int n) { return n <= 1 ? 1 : n * factorial(n - 1); }

}  // namespace

bool procrustes_bound_ties(double bound, double last) {
  constexpr double kTieRelative = 1e-9, kTieAbsolute = 1e-15;
  return bound <= last + kTieRelative * std::abs(last) + kTieAbsolute;
}

std::vector<PointClustering> procrustes_cluster_levels(const std::vector<Point2>& points,
                                                       const std::vector<double>& weights,
                                                       const ProcrustesOptions& options) {
  std::vector<PointClustering> levels;
  procrustes_cluster_levels(points, weights, options, levels);
  return levels;
}

void procrustes_cluster_levels(const std::vector<Point2>& points, const std::vector<double>& weights,
                               const ProcrustesOptions& options, std::vector<PointClustering>& levels) {
  pnn_cluster_levels(points, weights, options.max_clusters, levels);
  for (PointClustering& level : levels) refine_with_kmeans(points, weights, options.kmeans_iterations, level);
}

LevelTargets::LevelTargets(const PointClustering& level) : count(static_cast<int>(level.clusters.size())) {
  for (int c = 0; c < count; ++c) {
    const WeightedCluster& cluster = level.clusters[static_cast<std::size_t>(c)];
    centres[static_cast<std::size_t>(c)] = cluster.centre;
    weights[static_cast<std::size_t>(c)] = cluster.weight;
  }
}

void append_level_candidates(const PointClustering& level, const LevelTargets& targets,
                             const SimilarityFitter* fitter, const LandmarkCoefficients& landmarks,
                             ProcrustesMethod method, std::vector<ProcrustesCandidate>* out) {
  const int count = targets.count;
  const double scatter = level.total_scatter();
  // svd=tables: one table of the level's (cluster, landmark) terms for this landmark set serves every choice.
  std::optional<CorrespondenceFits> tables;
  if (method == ProcrustesMethod::tables) tables.emplace(*fitter, landmarks);
  std::array<Point2, kFitLandmarkCount> sources;
  const auto& permutations = landmark_permutations();
  // One cluster: the fit is scale 0 at its centre whatever landmark it is matched to, so one candidate suffices.
  const int run = factorial(kFitLandmarkCount - count);
  const std::size_t choice_count = count == 1 ? 1 : permutations.size() / static_cast<std::size_t>(run);
  for (std::size_t choice = 0; choice < choice_count; ++choice) {
    const Permutation& permutation = permutations[choice * static_cast<std::size_t>(run)];
    SimilarityFit fit;
    if (tables) {
      fit = tables->fit(permutation.data());
    } else {
      for (int c = 0; c < count; ++c)
        sources[static_cast<std::size_t>(c)] =
            landmarks.normalised_landmark(permutation[static_cast<std::size_t>(c)]);
      // The closed form through the level's fitter gives fit_weighted_similarity's transform bit for bit.
      fit = fitter != nullptr ? fitter->fit(sources.data())
                              : fit_weighted_similarity(sources.data(), targets.centres.data(), targets.weights.data(),
                                                        count, method);
    }
    // Landmarks 0 and 1 sit at (0, 0) and (1, 0) of the normalised frame: their images are the base points.
    ProcrustesCandidate candidate;
    candidate.error_bound = fit.residual + scatter;
    candidate.level = count;
    candidate.base0 = fit.apply({0.0, 0.0});
    candidate.base1 = fit.apply({1.0, 0.0});
    out->push_back(candidate);
  }
}

void append_level_candidates(const PointClustering& level, const LandmarkCoefficients& landmarks,
                             ProcrustesMethod method, std::vector<ProcrustesCandidate>* out) {
  const LevelTargets targets(level);
  if (method != ProcrustesMethod::eigen_svd) {   // closed_form and tables share the level's target side
    const SimilarityFitter fitter = targets.fitter();
    append_level_candidates(level, targets, &fitter, landmarks, method, out);
  } else {
    append_level_candidates(level, targets, nullptr, landmarks, method, out);
  }
}

}  // namespace blocklab
