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
  bool duplicate = false;     // refinement met an earlier candidate's assignment: not evaluated
};

// The measure the refinement descends (step 3 of the header): the block's continuous error for base points
// x = (u0, v0, u1, v1) with the decoded landmarks clamped to [0, 1], each coordinate mapped through
// f(c) = max(c, kStretchFloor)^alpha for the stretched error (alpha < 1) or left as is (alpha = 1, the linear
// error): sum_i w_i min_k |f(p_i) - f(clamp(L_k(x)))|^2, as the shape-fit Problem measures it before the lattice.
struct RefineMeasure {
  double alpha = 1.0;
  double map(double c) const { return alpha == 1.0 ? c : std::pow(std::max(c, kStretchFloor), alpha); }
  // d f / d c at an unclamped c: 1 (linear), alpha c^(alpha - 1) above the floor, 0 below it (constant there).
  double slope(double c) const {
    if (alpha == 1.0) return 1.0;
    return c > kStretchFloor ? alpha * std::pow(c, alpha - 1.0) : 0.0;
  }
};

// Error (see RefineMeasure) at x, the nearest mapped landmark of each point (ties: the lower landmark) and each
// landmark coordinate's raw (unclamped) and mapped (clamped, then mapped) value. `targets` holds the mapped
// points' u values, then their v values.
double measured_error(const std::vector<double>& targets, const std::vector<double>& weights,
                      const RefineMeasure& measure,
                      const std::array<std::array<double, 4>, 2 * kShapeLandmarkCount>& rows, const double* x,
                      std::vector<int>& nearest, double* raw, double* mapped) {
  for (int j = 0; j < 2 * kShapeLandmarkCount; ++j) {
    const auto& r = rows[static_cast<std::size_t>(j)];
    raw[j] = r[0] * x[0] + r[1] * x[1] + r[2] * x[2] + r[3] * x[3];
    mapped[j] = measure.map(std::min(std::max(raw[j], 0.0), 1.0));
  }
  // Structure of arrays (targets[0 .. n) = u, targets[n .. 2n) = v) and branch-free selects, so the compiler can
  // vectorise the loop over points.
  const std::size_t n = weights.size();
  const double* tu = targets.data();
  const double* tv = targets.data() + n;
  double error = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double best = 0.0;
    int k_best = 0;
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      const double du = tu[i] - mapped[2 * k], dv = tv[i] - mapped[2 * k + 1];
      const double d = du * du + dv * dv;
      // Strictly closer to replace: ties go to the lower landmark.
      const bool closer = k == 0 || d < best;
      best = closer ? d : best;
      k_best = closer ? k : k_best;
    }
    nearest[i] = k_best;
    error += weights[i] * best;
  }
  return error;
}

// Solves the 4x4 system a y = b in place (Gaussian elimination, partial pivoting). False when a pivot vanishes.
bool solve4(double (&a)[4][4], double (&b)[4]) {
  for (int c = 0; c < 4; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    // A zero (or NaN) pivot: singular system.
    if (!(std::abs(a[pivot][c]) > 0.0)) return false;
    if (pivot != c) {
      for (int k = 0; k < 4; ++k) std::swap(a[c][k], a[pivot][k]);
      std::swap(b[c], b[pivot]);
    }
    for (int r = c + 1; r < 4; ++r) {
      const double factor = a[r][c] / a[c][c];
      for (int k = c; k < 4; ++k) a[r][k] -= factor * a[c][k];
      b[r] -= factor * b[c];
    }
  }
  for (int c = 3; c >= 0; --c) {
    for (int k = c + 1; k < 4; ++k) b[c] -= a[c][k] * b[k];
    b[c] /= a[c][c];
  }
  return true;
}

// Clamp-aware refinement of one candidate (options refined_candidates, refine_iterations; step 3 of the header).
// The Procrustes fits ignore the clamp of decoded landmarks to [0, 1] and the stretch of the stretched error; near
// the border of the chroma plane the best transforms put a landmark OUTSIDE it and let the clamp project it onto
// the border (measured: on memorial.hdr blocks whose chroma hugs u = 0 the optimum is 2x below every Procrustes
// candidate). Each round, on the Problem's own measure (RefineMeasure: linear or stretched):
//   * assign every point to its nearest mapped, clamped landmark;
//   * with that assignment and each landmark coordinate's clamp state fixed, take a Gauss-Newton step: landmark
//     coordinates are linear in the base points x, a clamped one is constant and drops out, the stretch is
//     linearised at the current x (for the linear error the step is the exact least-squares solution); solve
//     the 4x4 normal equations, with a 1e-9 relative ridge so that directions the data leave free (e.g. every
//     point on one landmark: rotation and scale) stay where they are;
//   * keep the new x only if the error decreased (clamp states and assignments may change), else stop.
// For the linear error without clamps this is alternating assignment + weighted Procrustes refit (an ICP / k-means
// descent with the template as constraint). The candidate keeps its ranking bound.
//
// Duplicates: the first assignment and clamp pattern of each refined candidate is recorded in `seen` (exactly, as
// 2 bits per point and per landmark coordinate, for up to 24 points; hashed for more). A candidate that starts from
// a pattern seen before would take the same least-squares step (for the linear error exactly, up to the ridge) and
// is marked `duplicate` and not refined further or evaluated.
Candidate refine_candidate(const std::vector<double>& targets, const std::vector<double>& weights,
                           const RefineMeasure& measure, const ShapeTemplate& shape, const Candidate& start,
                           int iterations, std::vector<std::uint64_t>& seen, std::vector<int>& nearest,
                           std::vector<int>& next_nearest) {
  // Landmark coordinate rows (core/shape_fit_problem.h): u = (1 - a) u0 + b v0 + a u1 - b v1,
  // v = -b u0 + (1 - a) v0 + b u1 + a v1.
  std::array<std::array<double, 4>, 2 * kShapeLandmarkCount> rows;
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const double a = shape.along(k), b = shape.across(k);
    rows[static_cast<std::size_t>(2 * k)] = {1.0 - a, b, a, -b};
    rows[static_cast<std::size_t>(2 * k + 1)] = {-b, 1.0 - a, b, a};
  }
  double x[4] = {start.base0.u, start.base0.v, start.base1.u, start.base1.v};
  // `nearest` and `next_nearest` are scratch of weights.size() entries (allocated once per solve).
  double raw[2 * kShapeLandmarkCount], mapped[2 * kShapeLandmarkCount];
  double error = measured_error(targets, weights, measure, rows, x, nearest, raw, mapped);
  std::uint64_t key = 0;
  for (int j = 0; j < 2 * kShapeLandmarkCount; ++j)
    key = key << 2 | (raw[j] < 0.0 ? 1u : raw[j] > 1.0 ? 2u : 0u);   // 16 bits of clamp states
  for (std::size_t i = 0; i < nearest.size(); ++i) {
    // 2 bits per point while they fit in the remaining 48 bits; beyond, a multiplicative hash mixes them in.
    key = nearest.size() <= 24 ? key << 2 | static_cast<std::uint64_t>(nearest[i])
                               : (key ^ static_cast<std::uint64_t>(nearest[i] + 1)) * 0x100000001b3ull;
  }
  if (std::find(seen.begin(), seen.end(), key) != seen.end()) {
    Candidate duplicate = start;
    duplicate.duplicate = true;
    return duplicate;
  }
  seen.push_back(key);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    double slopes[2 * kShapeLandmarkCount];
    for (int j = 0; j < 2 * kShapeLandmarkCount; ++j) slopes[j] = measure.slope(raw[j]);
    // Normal equations for the step delta = x_new - x. Every point on landmark coordinate j shares its row r_j and
    // slope s_j, so the per-coordinate sums W_j = sum w_i and R_j = sum w_i residual_i give
    // N = sum_j W_j s_j^2 r_j r_j^T and rhs = sum_j R_j s_j r_j.
    double coordinate_weight[2 * kShapeLandmarkCount] = {}, coordinate_residual[2 * kShapeLandmarkCount] = {};
    for (std::size_t i = 0; i < weights.size(); ++i) {
      if (!(weights[i] > 0.0)) continue;   // weightless points constrain nothing
      for (int c = 0; c < 2; ++c) {
        const int j = 2 * nearest[i] + c;
        coordinate_weight[j] += weights[i];
        // raw[j] is unclamped wherever the sum is used (clamped coordinates are skipped below).
        coordinate_residual[j] += weights[i] * (targets[static_cast<std::size_t>(c) * weights.size() + i] - mapped[j]);
      }
    }
    double normal[4][4] = {}, rhs[4] = {};
    for (int j = 0; j < 2 * kShapeLandmarkCount; ++j) {
      if (coordinate_weight[j] == 0.0) continue;        // no point on this coordinate
      if (raw[j] < 0.0 || raw[j] > 1.0) continue;       // clamped: constant in x, drops out
      const double slope = slopes[j];
      if (slope == 0.0) continue;                        // below the stretch floor the mapped value is constant
      const auto& r = rows[static_cast<std::size_t>(j)];
      const double curvature = coordinate_weight[j] * slope * slope, pull = coordinate_residual[j] * slope;
      for (int p = 0; p < 4; ++p) {
        rhs[p] += pull * r[static_cast<std::size_t>(p)];
        for (int q = 0; q < 4; ++q)
          normal[p][q] += curvature * r[static_cast<std::size_t>(p)] * r[static_cast<std::size_t>(q)];
      }
    }
    const double ridge = 1e-9 * (normal[0][0] + normal[1][1] + normal[2][2] + normal[3][3]) / 4.0;
    // Nothing unclamped at all: no direction is constrained.
    if (!(ridge > 0.0)) break;
    for (int p = 0; p < 4; ++p) normal[p][p] += ridge;
    if (!solve4(normal, rhs)) break;   // singular even with the ridge (non-finite data): keep x
    double next[4];
    for (int p = 0; p < 4; ++p) next[p] = x[p] + rhs[p];
    double next_raw[2 * kShapeLandmarkCount], next_mapped[2 * kShapeLandmarkCount];
    const double next_error =
        measured_error(targets, weights, measure, rows, next, next_nearest, next_raw, next_mapped);
    if (!(next_error < error)) break;   // no progress (or NaN): keep the better x
    error = next_error;
    std::copy(next, next + 4, x);
    nearest.swap(next_nearest);
    std::copy(next_raw, next_raw + 2 * kShapeLandmarkCount, raw);
    std::copy(next_mapped, next_mapped + 2 * kShapeLandmarkCount, mapped);
  }
  // The ranking bound stays the original one (step 3 of the header ranks by it; the refined error is on another
  // measure for the stretched error).
  Candidate refined = start;
  refined.base0 = {x[0], x[1]};
  refined.base1 = {x[2], x[3]};
  return refined;
}

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
      const SimilarityFit fit = fit_weighted_similarity(sources.data(), centres.data(), cluster_weights.data(), level,
                                                         options.svd);
      // Landmarks 0 and 1 sit at (0, 0) and (1, 0) of the normalised frame: their images are the base points.
      candidates.push_back({fit.residual + scatter, fit.apply({0.0, 0.0}), fit.apply({1.0, 0.0})});
    }
  }

  // 3. Rank by the error bound; stable, so ties keep the enumeration order (levels from the top, choices in
  //    lexicographic landmark order).
  // Insertion sort: stable, in place (no buffer allocation, unlike std::stable_sort) and fast for <= 61 candidates.
  for (std::size_t i = 1; i < candidates.size(); ++i) {
    const Candidate moving = candidates[i];
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
          refine_candidate(targets, weights, measure, shape, candidates[i], options.refine_iterations, seen, nearest,
                           next_nearest);
  }
  std::size_t evaluated = options.evaluated_candidates == 0
                              ? candidates.size()
                              : std::min(candidates.size(), static_cast<std::size_t>(options.evaluated_candidates));
  // Candidates TIED with the last one evaluated are evaluated too: exact fits (two colours fit by any pair of
  // landmarks, three by many triples) all have bound ~0, and which of them survives the snap to the lattice best
  // is only known from the error itself. Tie = within kTieRelative relative (plus kTieAbsolute for bounds ~0).
  evaluated = std::max(evaluated, refined);
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
