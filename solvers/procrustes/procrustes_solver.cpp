// `procrustes` solver (solvers/procrustes/procrustes_solver.h): clustering, the k! correspondence search and
// weighted Procrustes of Munkberg et al. 2008 section 7.1 (eqs. 12-15), then a snap to the storage lattice.
#include "solvers/procrustes/procrustes_solver.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"
#include "solvers/procrustes/point_clustering.h"
#include "solvers/procrustes/procrustes_refinement.h"
#include "solvers/procrustes/procrustes_templates.h"
#include "solvers/procrustes/weighted_procrustes.h"

namespace blocklab {

namespace {

constexpr const char* kName = "procrustes";

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
                         "best-ranked candidates whose snapped error is evaluated (0 = all)"),
          integer_option("refined_candidates", d.refined_candidates, 0, 1000,
                         "best-ranked candidates refined by alternating nearest-landmark assignment and refit"),
          integer_option("refine_iterations", d.refine_iterations, 0, 1000,
                         "assignment + refit rounds per refined candidate (stops early when the error stalls)"),
          choice_option("svd", to_string(d.svd), {"closed_form", "eigen"},
                        "how each weighted Procrustes fit is solved: closed form (atan2 of the cross/dot sums) or "
                        "Eigen's 2x2 Jacobi SVD (same transform)")};
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
         check_integer_option("evaluated_candidates", evaluated_candidates, 0, INT_MAX, why) &&
         check_integer_option("refined_candidates", refined_candidates, 0, INT_MAX, why) &&
         check_integer_option("refine_iterations", refine_iterations, 0, INT_MAX, why);
}

ProcrustesOptions ProcrustesOptions::from_resolved(const SolverOptions& resolved) {
  ProcrustesOptions options;
  options.max_clusters = static_cast<int>(option_int(resolved, "max_clusters"));
  options.min_clusters = static_cast<int>(option_int(resolved, "min_clusters"));
  options.kmeans_iterations = static_cast<int>(option_int(resolved, "kmeans_iterations"));
  options.evaluated_candidates = static_cast<int>(option_int(resolved, "evaluated_candidates"));
  options.refined_candidates = static_cast<int>(option_int(resolved, "refined_candidates"));
  options.refine_iterations = static_cast<int>(option_int(resolved, "refine_iterations"));
  options.svd = option_text(resolved, "svd") == "eigen" ? ProcrustesMethod::eigen_svd : ProcrustesMethod::closed_form;
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
  const std::vector<PointClustering> levels = procrustes_cluster_levels(points, weights, options);
  const int top_level = static_cast<int>(levels.size());
  const int bottom_level = std::min(options.min_clusters, top_level);

  // 2. Candidates: one weighted Procrustes fit per level and ordered landmark choice.
  std::vector<ProcrustesCandidate> candidates;
  candidates.reserve(64);
  for (int level = top_level; level >= bottom_level; --level)
    append_level_candidates(levels[static_cast<std::size_t>(level - 1)], shape, options.svd, &candidates);

  // 3. Rank by the error bound; stable, so ties keep the enumeration order (levels from the top, choices in
  //    lexicographic landmark order).
  // Insertion sort: stable, in place (no buffer allocation, unlike std::stable_sort) and fast for <= 61 candidates.
  for (std::size_t i = 1; i < candidates.size(); ++i) {
    const ProcrustesCandidate moving = candidates[i];
    std::size_t j = i;
    for (; j > 0 && moving.error_bound < candidates[j - 1].error_bound; --j) candidates[j] = candidates[j - 1];
    candidates[j] = moving;
  }
  //    The best `refined_candidates` are refined in place (keeping their rank) and all of them are evaluated.
  const std::size_t refined = std::min(candidates.size(), static_cast<std::size_t>(options.refined_candidates));
  if (refined > 0 && options.refine_iterations > 0) {
    RefineMeasure measure;
    measure.alpha = point_set.fit_exponent();
    std::vector<double> targets(2 * points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      targets[i] = measure.map(points[i].u);
      targets[points.size() + i] = measure.map(points[i].v);
    }
    std::vector<std::uint64_t> seen;
    seen.reserve(refined);
    std::vector<int> nearest(points.size()), next_nearest(points.size());
    for (std::size_t i = 0; i < refined; ++i)
      candidates[i] =
          refine_procrustes_candidate(targets, weights, measure, shape, candidates[i], options.refine_iterations, seen,
                                      nearest, next_nearest);
  }
  std::size_t evaluated = options.evaluated_candidates == 0
                              ? candidates.size()
                              : std::min(candidates.size(), static_cast<std::size_t>(options.evaluated_candidates));
  // Candidates TIED with the last one evaluated are evaluated too: exact fits (two colours fit by any pair of
  // landmarks, three by many triples) all have bound ~0, and which of them survives the snap to the lattice best
  // is only known from the error itself (procrustes_bound_ties).
  evaluated = std::max(evaluated, refined);
  if (evaluated > 0) {
    const double last = candidates[evaluated - 1].error_bound;
    while (evaluated < candidates.size() && procrustes_bound_ties(candidates[evaluated].error_bound, last)) ++evaluated;
  }

  // 4. Snap and evaluate the problem's own error; strictly better replaces (first of equals wins).
  bool found = false;
  double best_error = 0.0;
  std::array<double, kShapeFitParameterCount> best_x{};
  std::array<std::int64_t, kShapeFitParameterCount> best_index{};
  for (std::size_t i = 0; i < evaluated; ++i) {
    const ProcrustesCandidate& candidate = candidates[i];
    if (candidate.duplicate) continue;   // refined to the same transform as an earlier candidate
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
