// `procrustes` solver (solvers/procrustes/procrustes_solver.h): clustering, the k! correspondence search and
// weighted Procrustes of Munkberg et al. 2008 section 7.1 (eqs. 12-15), then a snap to the storage lattice.
#include "solvers/procrustes/procrustes_solver.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "solvers/procrustes/point_clustering.h"
#include "solvers/procrustes/weighted_procrustes.h"

namespace blocklab {

namespace {

constexpr const char* kName = "procrustes";

// Ranking ties (step 3): relative 1e-9, and 1e-15 absolute (squared chroma distance: far below one 8-bit step,
// (1/255)^2 ~ 1.5e-5) for bounds that are 0 up to rounding.
constexpr double kTieRelative = 1e-9;
constexpr double kTieAbsolute = 1e-15;

using Permutation = std::array<int, kShapeLandmarkCount>;

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

struct Candidate {
  double error_bound = 0.0;   // Procrustes functional + scatter of the level
  Point2 base0, base1;
};

constexpr const char* kDescription =
    "weighted Procrustes on pnn + k-means clusters with the k! landmark correspondence search, snapped to the "
    "lattice (Munkberg 2008 sec. 7.1, eqs. 12-15)";

std::vector<OptionSpec> procrustes_option_specs() {
  const ProcrustesOptions d;
  return {integer_option("max_clusters", d.max_clusters, 1, kShapeLandmarkCount,
                         "largest number of point clusters matched to template landmarks"),
          integer_option("min_clusters", d.min_clusters, 1, kShapeLandmarkCount,
                         "smallest cluster count tried (<= max_clusters)"),
          integer_option("kmeans_iterations", d.kmeans_iterations, 0, 1000,
                         "Lloyd iterations refining each PNN partition (0 = PNN only)"),
          integer_option("evaluated_candidates", d.evaluated_candidates, 0, 1000,
                         "best-ranked candidates whose snapped error is evaluated (0 = all)")};
}

// The registry's entry: the Problem must expose its point set.
SolveResult solve_point_set_problem(const Problem& problem, const ProcrustesOptions& options, const double* start,
                                    std::uint64_t seed) {
  const auto* point_set = dynamic_cast<const PointSetFit*>(&problem);
  if (point_set == nullptr)
    fail(kName, "needs a point-set problem (a Problem implementing PointSetFit, e.g. ShapeFitProblem of "
                "core/shape_fit_problem.h); this problem exposes no points");
  return solve_procrustes(problem, *point_set, options, start, seed);
}

// Nearest lattice point of `value` for parameter p (clamped to the bounds; continuous parameters keep the value).
double snap(const Problem& problem, int p, double value, std::int64_t* index) {
  const double clamped = std::min(std::max(value, problem.lower(p)), problem.upper(p));
  const Lattice& lattice = problem.lattice(p);
  if (!lattice.present()) return clamped;
  *index = lattice.nearest_index(clamped);
  return lattice.point(*index);
}

}  // namespace

bool ProcrustesOptions::is_valid(std::string* why) const {
  return check_integer_option("max_clusters", max_clusters, 1, kShapeLandmarkCount, why) &&
         check_integer_option("min_clusters", min_clusters, 1, max_clusters, why) &&
         check_integer_option("kmeans_iterations", kmeans_iterations, 0, INT_MAX, why) &&
         check_integer_option("evaluated_candidates", evaluated_candidates, 0, INT_MAX, why);
}

ProcrustesOptions ProcrustesOptions::from_resolved(const SolverOptions& resolved) {
  ProcrustesOptions options;
  options.max_clusters = static_cast<int>(option_int(resolved, "max_clusters"));
  options.min_clusters = static_cast<int>(option_int(resolved, "min_clusters"));
  options.kmeans_iterations = static_cast<int>(option_int(resolved, "kmeans_iterations"));
  options.evaluated_candidates = static_cast<int>(option_int(resolved, "evaluated_candidates"));
  return options;
}

SolveResult solve_procrustes(const Problem& problem, const PointSetFit& point_set, const ProcrustesOptions& options,
                             const double* start, std::uint64_t seed) {
  const auto started = std::chrono::steady_clock::now();
  require_valid_options(kName, options);
  if (problem.dim() != kShapeFitParameterCount)
    fail(kName, "the problem has " + std::to_string(problem.dim()) +
                    " parameters; a point-set fit has 4 (base points u0, v0, u1, v1)");
  const std::vector<Point2>& points = point_set.fit_points();
  const std::vector<double>& weights = point_set.fit_weights();
  if (points.empty() || weights.size() != points.size())
    fail(kName, "the point set needs at least one point and one weight per point");
  const ShapeTemplate& shape = point_set.fit_template();

  SolveResult result = begin_solve(kName, problem, start, seed);
  Summary& summary = result.summary;

  // 1. Cluster levels k = 1 .. top (nested PNN partitions, each refined by k-means).
  std::vector<PointClustering> levels = pnn_cluster_levels(points, weights, options.max_clusters);
  const int top_level = static_cast<int>(levels.size());
  const int bottom_level = std::min(options.min_clusters, top_level);

  // 2. Candidates: one weighted Procrustes fit per level and ordered landmark choice.
  std::array<Point2, kShapeLandmarkCount> normalised_landmarks;
  for (int k = 0; k < kShapeLandmarkCount; ++k)
    normalised_landmarks[static_cast<std::size_t>(k)] = shape.normalised_landmark(k);
  std::vector<Candidate> candidates;
  candidates.reserve(64);
  const auto& permutations = landmark_permutations();
  for (int level = top_level; level >= bottom_level; --level) {
    PointClustering& clustering = levels[static_cast<std::size_t>(level - 1)];
    refine_with_kmeans(points, weights, options.kmeans_iterations, clustering);
    const double scatter = clustering.total_scatter();
    std::array<Point2, kShapeLandmarkCount> centres, sources;
    std::array<double, kShapeLandmarkCount> cluster_weights{};
    for (int c = 0; c < level; ++c) {
      const WeightedCluster& cluster = clustering.clusters[static_cast<std::size_t>(c)];
      centres[static_cast<std::size_t>(c)] = cluster.centre;
      cluster_weights[static_cast<std::size_t>(c)] = cluster.weight;
    }
    // One cluster: the fit is scale 0 at its centre whatever landmark it is matched to, so one candidate suffices.
    const int run = factorial(kShapeLandmarkCount - level);
    const std::size_t choice_count = level == 1 ? 1 : permutations.size() / static_cast<std::size_t>(run);
    for (std::size_t choice = 0; choice < choice_count; ++choice) {
      const Permutation& permutation = permutations[choice * static_cast<std::size_t>(run)];
      for (int c = 0; c < level; ++c)
        sources[static_cast<std::size_t>(c)] = normalised_landmarks[static_cast<std::size_t>(permutation[c])];
      const SimilarityFit fit = fit_weighted_similarity(sources.data(), centres.data(), cluster_weights.data(), level);
      // Landmarks 0 and 1 sit at (0, 0) and (1, 0) of the normalised frame: their images are the base points.
      candidates.push_back({fit.residual + scatter, fit.apply({0.0, 0.0}), fit.apply({1.0, 0.0})});
    }
  }

  // 3. Rank by the error bound; stable, so ties keep the enumeration order (levels from the top, choices in
  //    lexicographic landmark order).
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.error_bound < b.error_bound; });
  std::size_t evaluated = options.evaluated_candidates == 0
                              ? candidates.size()
                              : std::min(candidates.size(), static_cast<std::size_t>(options.evaluated_candidates));
  // Candidates TIED with the last one evaluated are evaluated too: exact fits (two colours fit by any pair of
  // landmarks, three by many triples) all have bound ~0, and which of them survives the snap to the lattice best
  // is only known from the error itself. Tie = within kTieRelative relative (plus kTieAbsolute for bounds ~0).
  if (evaluated > 0) {
    const double last = candidates[evaluated - 1].error_bound;
    while (evaluated < candidates.size() &&
           candidates[evaluated].error_bound <= last + kTieRelative * std::abs(last) + kTieAbsolute)
      ++evaluated;
  }

  // 4. Snap and evaluate the problem's own error; strictly better replaces (first of equals wins).
  bool found = false;
  double best_error = 0.0;
  std::array<double, kShapeFitParameterCount> best_x{};
  std::array<std::int64_t, kShapeFitParameterCount> best_index{};
  for (std::size_t i = 0; i < evaluated; ++i) {
    const Candidate& candidate = candidates[i];
    const double ideal[kShapeFitParameterCount] = {candidate.base0.u, candidate.base0.v, candidate.base1.u,
                                                   candidate.base1.v};
    std::array<double, kShapeFitParameterCount> x{};
    std::array<std::int64_t, kShapeFitParameterCount> index{};
    for (int p = 0; p < kShapeFitParameterCount; ++p)
      x[static_cast<std::size_t>(p)] = snap(problem, p, ideal[p], &index[static_cast<std::size_t>(p)]);
    const double error = problem.eval(x.data());
    ++summary.evaluations;
    if (std::isnan(error)) continue;   // an invalid point is never the answer
    if (!found || error < best_error) {
      found = true;
      best_error = error;
      best_x = x;
      best_index = index;
    }
  }

  result.parameters.assign(best_x.begin(), best_x.end());
  if (problem.has_full_lattice()) result.lattice_indices.assign(best_index.begin(), best_index.end());
  summary.message = std::to_string(candidates.size()) + " candidates from cluster levels " +
                    std::to_string(top_level) + ".." + std::to_string(bottom_level) + ", " +
                    std::to_string(evaluated) + " evaluated";
  if (found) {
    summary.termination = Termination::converged;
    summary.final_error = best_error;
  } else {
    summary.termination = Termination::failed;
    summary.message += "; the error was NaN at every evaluated candidate";
  }
  summary.seconds = seconds_since(started);
  return result;
}

const Solver& procrustes_solver() {
  static const TypedSolver<ProcrustesOptions> solver(kName, kDescription, procrustes_option_specs,
                                                     solve_point_set_problem);
  return solver;
}

}  // namespace blocklab
