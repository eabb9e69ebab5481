// Procrustes candidates for SEVERAL template shapes from ONE clustering of the point set (Munkberg et al. 2008
// section 7.1: "The error is evaluated for the best fit of each template shape, and we select the shape with the
// smallest overall error"). The clustering (PNN + k-means, point_clustering.h) depends only on the points, so it is
// computed once; every (template, cluster level, ordered landmark choice) gets its weighted Procrustes fit
// (weighted_procrustes.h), and the candidates of ALL templates are ranked together by the error bound of
// procrustes_solver.h step 3 (Procrustes functional + within-cluster scatter: an upper bound of the continuous
// linear error). The best few are refined by the clamp-aware descent (procrustes_refinement.h); the caller snaps
// and evaluates them in its own error (a format: its reconstruction error), so the expensive work goes to the few
// candidates of any template that fit best instead of the same budget for every template.
//
// With one template, the candidates, their order and the refinement are those of the `procrustes` solver (which
// uses append_level_candidates of solvers/procrustes/level_candidates.h for its step 2, as the ranking does).
#pragma once

#include <vector>

#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "solvers/procrustes/level_candidates.h"
#include "solvers/procrustes/procrustes_refinement.h"
#include "solvers/procrustes/procrustes_solver.h"
#include "solvers/procrustes/procrustes_workspace.h"

namespace blocklab {

struct TemplateCandidate {
  int shape = 0;                   // index into the template list
  ProcrustesCandidate candidate;   // base points (refined for the first `refined`), bound, duplicate flag
};

struct TemplateRankingOptions {
  ProcrustesOptions procrustes;   // max/min_clusters, kmeans_iterations, svd, refine_iterations are used
  int kept = 16;                  // best candidates over all templates returned (>= 1) ...
  int tie_limit = 16;             // ... plus up to this many more that tie with the last kept (exact fits)
  int per_template = 1;           // ... plus each template's own best `per_template` (every template competes)
  int refined = 8;                // of those, the first `refined` are refined (0 = none)
  double exponent = 1.0;          // refinement measure: 1 = linear error, < 1 = stretched (RefineMeasure)
};

// The working buffers of rank_template_candidates (one per worker thread, reused across blocks; cleared before use).
struct TemplateRankingWorkspace {
  std::vector<PointClustering> levels;                   // the cluster levels
  std::vector<TemplateCandidate> all;                    // every candidate, in enumeration order
  std::vector<CandidateKey> keys, chosen;                // their sort keys; the chosen ones
  std::vector<char> chosen_flag;                         // per candidate: chosen already
  std::vector<ProcrustesCandidate> level_candidates;     // one template's candidates on one level
  std::vector<std::size_t> count;                        // per template: chosen candidates
  std::vector<std::vector<CandidateKey>> best;           // per template: its best others
  RefinementBuffers refinement;                          // targets and nearest-landmark scratch
  std::vector<std::vector<std::uint64_t>> seen;          // per template: the refinement's duplicate keys
};

// Ranked candidates of every template (ascending bound; equal bounds keep the enumeration order: cluster levels
// from the top, then templates in list order, then landmark choices in lexicographic order): the best `kept` overall,
// the ones tied with the last of them (at most tie_limit more), and each template's best `per_template`. The k = 1
// candidate is the same transform for every template (scale 0) and is listed once, for template 0. Refined candidates
// whose first assignment repeats an earlier refined candidate's OF THE SAME TEMPLATE are marked duplicate.
// Deterministic. Throws Error on an empty point set, a weight count mismatch, no template or invalid options.
// `workspace` (optional): the caller's buffers; without one the ranking makes its own.
std::vector<TemplateCandidate> rank_template_candidates(const std::vector<Point2>& points,
                                                        const std::vector<double>& weights,
                                                        const std::vector<ShapeTemplate>& shapes,
                                                        const TemplateRankingOptions& options,
                                                        TemplateRankingWorkspace* workspace = nullptr);

}  // namespace blocklab
