// `procrustes`: the landmark-fit heuristic of "Practical HDR Texture Compression" (2008) section 7.1 ("Procrustes
// Analysis and Clustering", eqs. 12-15) for Problems that declare the landmark-fit capability (Problem::landmark_fit,
// core/problem.h: weighted 2D points, landmark coefficients in the base-point frame, the stretch exponent).
//
// Algorithm (deterministic; the seed is only recorded):
//   1. Cluster the weighted points with PNN into k = 1 .. max_clusters groups (at most 4, the landmark
//      count) and refine each partition with k-means (point_clustering.h).
//   2. For every cluster level k >= min_clusters and every ordered choice of k distinct landmarks (the
//      paper's "4! = 24 mappings"; 4!/(4-k)! for k < 4; a single one for k = 1, where the fit is scale 0 at the
//      centre), fit the similarity with weighted Procrustes (weighted_procrustes.h; cluster weight = its total
//      point weight), by default in closed form (option svd=closed_form; svd=eigen uses Eigen's 2x2 SVD, same
//      transform; svd=tables the closed form of all of a level's correspondences from shared terms,
//      correspondence_fits.h, same transforms up to rounding). Its base points are the images of landmarks 0 and 1.
//   3. Rank the candidates by an upper bound of the block's continuous linear error with that transform: the
//      Procrustes functional plus the level's within-cluster scatter (every point keeps its cluster's landmark,
//      so the nearest-landmark error can only be lower). Ties keep the earlier candidate.
//      Refinement (refined_candidates > 0, default 12): the best-ranked candidates are refined in place by a
//      clamp-aware descent of the Problem's own continuous error (linear or stretched, LandmarkFitView::exponent):
//      assign points to their nearest clamped landmark, Gauss-Newton step on the base points with clamped
//      coordinates dropped, keep it if the error decreased (refine_iterations rounds). Procrustes ignores the clamp
//      of decoded landmarks to [0, 1], and on real HDR chroma, which hugs the u = 0 border, the best transforms put
//      landmarks outside [0, 1] and let the clamp project them back (docs/solver-bench.md: mean error 1.07-1.38x
//      the certified optimum without refinement, 1.02-1.04x with it). Refined candidates whose first assignment
//      repeats an earlier one's are dropped as duplicates.
//      search=screened (procrustes_screening.h) replaces the choice of the refined and evaluated candidates:
//      the `refined_candidates` lowest start errors (base points projected onto [0, 1]^4, the problem's continuous
//      measure, estimated per cluster) among the first `screened_candidates` in bound order are refined inside the
//      box, and step 4
//      evaluates the `evaluated_candidates` of them whose snapped points measure best (0 = all refined).
//      search=start_error (start_error_screening.h) ranks every candidate by its start error instead (the
//      refinement measure at its base points clamped to [0, 1]^4, in single precision, four points per SSE2
//      register) and refines the lowest ones until `refined_candidates` distinct ones are refined; step 4 evaluates
//      those only. The start error predicts the refined error far better than the bound (docs/solver-bench.md:
//      6 refined by start error are about as close to the certified optimum as 12 by bound).
//   4. Snap the `evaluated_candidates` best (at least the refined ones; 0 = all; plus every candidate whose bound
//      ties with the last of them, e.g. the many exact fits of a two-colour block) to the storage lattice (nearest
//      value per coordinate) and return the one with the lowest error of the PROBLEM itself (linear or stretched,
//      or whatever error the Problem implements). Without a lattice on a parameter the continuous value is
//      returned (clamped to the bounds). A candidate that snaps to the same point as an earlier evaluated one is
//      not evaluated again (same error, so never strictly better).
// The stretched error (section 7.2) is not a Procrustes functional: clustering and fitting happen in the linear
// chroma plane; the refinement and step 4 see the stretched error. Termination is `converged` (a heuristic: no proof).
#pragma once

#include <cstdint>
#include <string>

#include "core/problem.h"
#include "solvers/procrustes/procrustes_workspace.h"
#include "solvers/procrustes/weighted_procrustes.h"
#include "solvers/solver.h"

namespace blocklab {

struct ProcrustesOptions {
  int max_clusters = kFitLandmarkCount;   // option max_clusters, 1..4
  int min_clusters = 1;                     // option min_clusters, 1..max_clusters
  int kmeans_iterations = 8;                // option kmeans_iterations, 0 = PNN only
  int evaluated_candidates = 8;             // option evaluated_candidates, 0 = every candidate
  ProcrustesMethod svd = ProcrustesMethod::closed_form;   // option svd: closed_form | eigen | tables
  int refined_candidates = 12;              // option refined_candidates, 0 = no refinement
  int refine_iterations = 2;                // option refine_iterations, 0 = no refinement
  // option search: which candidates are refined and evaluated (step 3). ranked (default): the best
  // `refined_candidates` by bound, then the problem's error at `evaluated_candidates`; screened
  // (procrustes_screening.h): the best `refined_candidates` by start error among `screened_candidates`, refined
  // inside the box [0, 1]^4, and the problem's error at the `evaluated_candidates` best by the measured error at
  // their snapped points.
  // start_error (start_error_screening.h): the `refined_candidates` lowest start errors among all candidates,
  // refined and evaluated (evaluated_candidates and screened_candidates are not used).
  enum class Search { ranked, screened, start_error };
  Search search = Search::ranked;
  int screened_candidates = 0;              // option screened_candidates (search=screened), 0 = every candidate
  double time_limit = kDefaultTimeLimit;    // option time_limit: wall-time seconds per solve

  bool is_valid(std::string* why) const;
  static ProcrustesOptions from_resolved(const SolverOptions& resolved);
};

// The explicit entry: `problem` must declare the landmark-fit capability (its 4 parameters are the base points
// u0, v0, u1, v1 of core/problem.h). `workspace` (optional) holds the solve's scratch and may be reused across solves
// on one thread; without one the solve allocates its own. Throws Error on invalid options, a problem without the
// capability or of the wrong dimension.
SolveResult solve_procrustes(const Problem& problem, const ProcrustesOptions& options, const double* start,
                             std::uint64_t seed, ProcrustesWorkspace* workspace = nullptr);

// Registry entry: solve_procrustes with a workspace of its own; a Problem without the capability is an Error
// ("procrustes: needs the landmark_fit capability ...").
const Solver& procrustes_solver();

}  // namespace blocklab
