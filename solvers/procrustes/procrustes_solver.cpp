// `procrustes` solver (solvers/procrustes/procrustes_solver.h): clustering, the k! correspondence search and
// weighted Procrustes of "Practical HDR Texture Compression" (2008) section 7.1 (eqs. 12-15), then a snap to the
// storage lattice.
#include "solvers/procrustes/procrustes_solver.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "core/error.h"
#include "solvers/procrustes/point_clustering.h"
#include "solvers/procrustes/procrustes_refinement.h"
#include "solvers/procrustes/procrustes_screening.h"
#include "solvers/procrustes/level_candidates.h"
#include "solvers/procrustes/start_error_screening.h"
#include "solvers/procrustes/weighted_procrustes.h"

namespace blocklab {

namespace {

constexpr const char* kName = "procrustes";

constexpr const char* kDescription =
    "weighted Procrustes on pnn + k-means clusters with the k! landmark correspondence search, snapped to the "
    "lattice (Practical HDR Texture Compression, sec. 7.1, eqs. 12-15)";

// Every option of ProcrustesOptions, declared once (core/options.h OptionTable): specs, is_valid and from_resolved.
const OptionTable<ProcrustesOptions>& procrustes_option_table() {
  static const auto table = OptionTable<ProcrustesOptions>()
      .integer("max_clusters", &ProcrustesOptions::max_clusters, 1, kFitLandmarkCount,
               "largest number of point clusters matched to landmarks")
      .integer("min_clusters", &ProcrustesOptions::min_clusters, 1, kFitLandmarkCount,
               "smallest cluster count tried (<= max_clusters)")
      .integer("kmeans_iterations", &ProcrustesOptions::kmeans_iterations, 0, 1000,
               "Lloyd iterations refining each PNN partition (0 = PNN only)")
      .integer("evaluated_candidates", &ProcrustesOptions::evaluated_candidates, 0, 1000,
               "best-ranked candidates whose snapped error is evaluated (0 = all)")
      .integer("refined_candidates", &ProcrustesOptions::refined_candidates, 0, 1000,
               "best-ranked candidates refined by alternating nearest-landmark assignment and refit")
      .integer("refine_iterations", &ProcrustesOptions::refine_iterations, 0, 1000,
               "assignment + refit rounds per refined candidate (stops early when the error stalls)")
      .choice("svd", &ProcrustesOptions::svd,
              {{"closed_form", ProcrustesMethod::closed_form}, {"eigen", ProcrustesMethod::eigen_svd},
               {"tables", ProcrustesMethod::tables}},
              "how each weighted Procrustes fit is solved: closed form (the cross/dot sums), Eigen's 2x2 "
              "Jacobi SVD (same transform), or tables (the closed form of all correspondences of a cluster "
              "level from shared per-cluster, per-landmark terms: same transforms up to rounding, ~4x "
              "fewer operations)")
      .choice("search", &ProcrustesOptions::search,
              {{"ranked", ProcrustesOptions::Search::ranked}, {"screened", ProcrustesOptions::Search::screened},
               {"start_error", ProcrustesOptions::Search::start_error}},
              "which candidates are refined and evaluated: ranked (the best refined_candidates by the "
              "Procrustes bound), screened (the lowest start errors, refined inside [0, 1]^4, and only the "
              "evaluated_candidates whose snapped points measure best go to the problem's error) or "
              "start_error (every candidate's start error at its base points clamped to [0, 1]^4, in single "
              "precision; the refined_candidates lowest are refined and evaluated, nothing else)")
      .integer("screened_candidates", &ProcrustesOptions::screened_candidates, 0, 1000,
               "search=screened: candidates (in bound order) whose start error is measured (0 = all)")
      .real("time_limit", &ProcrustesOptions::time_limit, 0.0, DBL_MAX, kTimeLimitHelp, kLowerOpen)
      .rule([](ProcrustesOptions const& options, std::string* why) {
        return check_integer_option("min_clusters", options.min_clusters, 1, options.max_clusters, why);
      });
  return table;
}

std::vector<OptionSpec> procrustes_option_specs() { return procrustes_option_table().specs(); }

// The registry's entry: a workspace of its own.
SolveResult solve_landmark_fit_problem(const Problem& problem, const ProcrustesOptions& options, const double* start,
                                       std::uint64_t seed) {
  return solve_procrustes(problem, options, start, seed, nullptr);
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

bool ProcrustesOptions::is_valid(std::string* why) const { return procrustes_option_table().is_valid(*this, why); }

ProcrustesOptions ProcrustesOptions::from_resolved(const SolverOptions& resolved) {
  return procrustes_option_table().from_resolved(resolved);
}

SolveResult solve_procrustes(const Problem& problem, const ProcrustesOptions& options, const double* start,
                             std::uint64_t seed, ProcrustesWorkspace* workspace) {
  const auto started = std::chrono::steady_clock::now();
  require_valid_options(kName, options);
  const LandmarkFitView fit = problem.landmark_fit();
  if (!fit.available())
    fail(kName, "needs a problem with the landmark_fit capability (weighted 2D points fit by landmarks of two base "
                "points, core/problem.h); this problem does not declare it");
  if (problem.dim() != kLandmarkFitParameterCount)
    fail(kName, "the problem has " + std::to_string(problem.dim()) +
                    " parameters; a landmark fit has 4 (base points u0, v0, u1, v1)");
  const std::vector<Point2>& points = *fit.points;
  const std::vector<double>& weights = *fit.weights;
  if (points.empty() || weights.size() != points.size())
    fail(kName, "the point set needs at least one point and one weight per point");
  const LandmarkCoefficients& landmarks = fit.landmarks;
  std::optional<ProcrustesWorkspace> own_workspace;   // made only when the caller gives none
  if (workspace == nullptr) own_workspace.emplace();
  ProcrustesWorkspace& w = workspace != nullptr ? *workspace : *own_workspace;

  SolveResult result = begin_solve(kName, problem, start, seed);
  Summary& summary = result.summary;
  // Checked before each refined candidate of the ranked search (a refinement costs far more than a clock read) and
  // in the evaluation loop once a valid candidate is known; the clustering and the screened searches are bounded by
  // their option ranges.
  TimeLimit time_limit(started, options.time_limit, 1);

  // 1. Cluster levels k = 1 .. top (nested PNN partitions, each refined by k-means).
  std::vector<PointClustering>& levels = w.levels;
  procrustes_cluster_levels(points, weights, options, levels);
  const int top_level = static_cast<int>(levels.size());
  const int bottom_level = std::min(options.min_clusters, top_level);

  // 2. Candidates: one weighted Procrustes fit per level and ordered landmark choice.
  std::vector<ProcrustesCandidate>& candidates = w.candidates;
  candidates.clear();
  for (int level = top_level; level >= bottom_level; --level)
    append_level_candidates(levels[static_cast<std::size_t>(level - 1)], landmarks, options.svd, &candidates);

  // 3. Rank by the error bound; stable, so ties keep the enumeration order (levels from the top, choices in
  //    lexicographic landmark order). search=start_error orders by its own measure instead.
  // Insertion sort of (bound, index) keys, then one permutation of the candidates: stable, no allocation once the
  // scratch is warm, and 16-byte moves instead of whole candidates (the same order as sorting the candidates).
  if (options.search != ProcrustesOptions::Search::start_error) {
    using Key = CandidateKey;
    std::vector<Key>& keys = w.keys;
    std::vector<ProcrustesCandidate>& unsorted = w.unsorted;
    keys.resize(candidates.size());
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const Key moving{candidates[i].error_bound, i};
      std::size_t j = i;
      // Strictly smaller moves up (a NaN bound never moves and is never passed, as in a sort of the candidates).
      for (; j > 0 && moving.bound < keys[j - 1].bound; --j) keys[j] = keys[j - 1];
      keys[j] = moving;
    }
    unsorted.swap(candidates);
    candidates.resize(unsorted.size());
    for (std::size_t i = 0; i < keys.size(); ++i) candidates[i] = unsorted[keys[i].index];
  }
  // The refinement measure's targets: the mapped points, all u values, then all v values. The problem may offer
  // them already (LandmarkFitView::stretched_u/v: the same pow(max(c, kStretchFloor), exponent), bit for bit).
  const RefineMeasure measure(fit.exponent);
  std::vector<double>& targets = w.refinement.targets;
  const auto fill_targets = [&] {
    targets.resize(2 * points.size());
    if (fit.stretched_u != nullptr && fit.stretched_v != nullptr &&
        fit.stretched_u->size() == points.size() && fit.stretched_v->size() == points.size()) {
      std::copy(fit.stretched_u->begin(), fit.stretched_u->end(), targets.begin());
      std::copy(fit.stretched_v->begin(), fit.stretched_v->end(),
                targets.begin() + static_cast<std::ptrdiff_t>(points.size()));
      return;
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      targets[i] = measure.map(points[i].u);
      targets[points.size() + i] = measure.map(points[i].v);
    }
  };
  std::size_t evaluated = 0;
  if (options.search == ProcrustesOptions::Search::screened) {
    // search=screened (procrustes_screening.h): the candidates to evaluate replace the ranked list.
    fill_targets();
    candidates = screen_procrustes_candidates(problem, targets, weights, measure, landmarks, candidates, levels,
                                              options.screened_candidates, options.refined_candidates,
                                              options.refine_iterations, options.evaluated_candidates, w.screening);
    evaluated = candidates.size();
  } else if (options.search == ProcrustesOptions::Search::start_error) {
    // search=start_error (start_error_screening.h): the candidates refined by start error replace the list and
    // are all evaluated.
    fill_targets();
    refine_by_start_error(targets, weights, measure, landmarks, options.refined_candidates, options.refine_iterations,
                          candidates, w.start_error);
    evaluated = candidates.size();
  } else {
    //    The best `refined_candidates` are refined in place (keeping their rank) and all of them are evaluated.
    const std::size_t refined = std::min(candidates.size(), static_cast<std::size_t>(options.refined_candidates));
    if (refined > 0 && options.refine_iterations > 0) {
      fill_targets();
      std::vector<std::uint64_t>& seen = w.refinement.seen;
      seen.clear();
      std::vector<int>& nearest = w.refinement.nearest;
      std::vector<int>& next_nearest = w.refinement.next_nearest;
      nearest.resize(points.size());
      next_nearest.resize(points.size());
      // Past the time limit the remaining candidates keep their unrefined fits.
      for (std::size_t i = 0; i < refined && !time_limit.reached(); ++i)
        candidates[i] = refine_procrustes_candidate(targets, weights, measure, landmarks, candidates[i],
                                                    options.refine_iterations, seen, nearest, next_nearest);
    }
    evaluated = options.evaluated_candidates == 0
                    ? candidates.size()
                    : std::min(candidates.size(), static_cast<std::size_t>(options.evaluated_candidates));
    // Candidates TIED with the last one evaluated are evaluated too: exact fits (two colours fit by any pair of
    // landmarks, three by many triples) all have bound ~0, and which of them survives the snap to the lattice best
    // is only known from the error itself (procrustes_bound_ties).
    evaluated = std::max(evaluated, refined);
    if (evaluated > 0) {
      const double last = candidates[evaluated - 1].error_bound;
      while (evaluated < candidates.size() && procrustes_bound_ties(candidates[evaluated].error_bound, last))
        ++evaluated;
    }
  }

  // 4. Snap and evaluate the problem's own error; strictly better replaces (first of equals wins).
  bool found = false;
  double best_error = 0.0;
  std::array<double, kLandmarkFitParameterCount> best_x{};
  std::array<std::int64_t, kLandmarkFitParameterCount> best_index{};
  std::vector<std::array<double, kLandmarkFitParameterCount>>& snapped = w.snapped;   // points evaluated so far
  snapped.clear();
  for (std::size_t i = 0; i < evaluated && !(found && time_limit.reached()); ++i) {
    const ProcrustesCandidate& candidate = candidates[i];
    if (candidate.duplicate) continue;   // refined to the same transform as an earlier candidate
    const double ideal[kLandmarkFitParameterCount] = {candidate.base0.u, candidate.base0.v, candidate.base1.u,
                                                   candidate.base1.v};
    std::array<double, kLandmarkFitParameterCount> x{};
    std::array<std::int64_t, kLandmarkFitParameterCount> index{};
    for (int p = 0; p < kLandmarkFitParameterCount; ++p)
      x[static_cast<std::size_t>(p)] = snap(problem, p, ideal[p], &index[static_cast<std::size_t>(p)]);
    // The same point as an earlier candidate: the same error (eval is a function of x), never strictly better.
    if (std::find(snapped.begin(), snapped.end(), x) != snapped.end()) continue;
    snapped.push_back(x);
    // Only a strictly lower error replaces the best, so the evaluation may stop once it cannot be lower.
    const double error = found ? problem.eval_below(x.data(), best_error) : problem.eval(x.data());
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
  if (found && time_limit.was_reached()) {
    summary.termination = Termination::max_seconds;
    summary.final_error = best_error;
    summary.message = time_limit.message() + "; " + summary.message + " at most";
  } else if (found) {
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
                                                     solve_landmark_fit_problem);
  return solver;
}

}  // namespace blocklab
