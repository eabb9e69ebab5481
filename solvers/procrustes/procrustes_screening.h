// The `screened` candidate search of the `procrustes` solver (option search=screened; solvers/procrustes/
// procrustes_solver.h step 3): another way to choose which Procrustes candidates of "Practical HDR Texture Compression"
// (2008) section 7.1 (eqs. 12-15) to refine, for the error of section 7.1 (eq. 11, linear) or 7.2 (stretched): closer
// to the certified optimum than the default at about its cost (docs/solver-bench.md, "Speed goals"). The default
// search is search=ranked.
//
// What differs from search=ranked (which refines the best `refined_candidates` by the Procrustes bound and evaluates
// the problem's error at `evaluated_candidates` snapped candidates):
//   1. Box. Every candidate's base points are first projected onto the parameter box [0, 1]^4 (they are stored
//      there: the snap to the lattice clamps them anyway), and the refinement keeps them there (projected
//      Gauss-Newton: each step is clamped to the box before its error is measured). search=ranked refines the
//      unconstrained base points, and a refined transform whose base point leaves [0, 1] is moved by the snap, so
//      its refined error does not predict its stored error.
//   2. Screening. For the first `screened_candidates` candidates in bound order (0 = all), the start error at the
//      boxed base points is estimated on the problem's own continuous measure (RefineMeasure: clamped landmarks,
//      stretched or linear) at the level of the candidate's clusters: each cluster's weighted mean of mapped points
//      to its nearest mapped landmark, times the cluster weight, plus the level's mapped scatter (the exact error
//      when every point keeps its cluster's landmark; 4 x 4 distances instead of 16 x 4). The `refined_candidates`
//      with the lowest estimate are refined (in order of the estimate; ties keep the bound order). Measured on real
//      blocks: the per-point start error picks slightly better candidates (Desk stretched 1.043 instead of 1.065
//      of the optimum with 8 refined) at ~3x the screening cost; the Procrustes bound alone picks worse ones.
//   3. Choice. Each refined candidate is snapped to the lattice and its error at the snapped point is measured on
//      the same continuous measure; only the `evaluated_candidates` best by that go to the Problem's own error
//      (procrustes_solver.h step 4), which decides.
//   4. Cost. The stretch f(c) = max(c, kStretchFloor)^alpha of the refinement measure (RefineMeasure, which
//      search=ranked shares) comes from StretchTable (stretch_table.h, relative error < 1e-13 instead of one libm
//      pow, ~15 ns, per landmark coordinate and evaluation), the Gauss-Newton slope alpha f(c) / c from the stretched
// value instead of a second pow, and trial steps and the
//      snapped points use an exact early exit (an error sum is abandoned once its partial sum, of terms >= 0,
//      reaches the error to beat: the current one for a step, the last of the best `evaluated_candidates` for a
//      snapped point). These change the refinement measure by rounding only; the Problem's own error (exact,
//      step 4) picks the answer.
// Measured on real blocks (docs/solver-bench.md): see "Speed goals".
#pragma once

#include <array>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/problem.h"
#include "solvers/procrustes/point_clustering.h"
#include "solvers/procrustes/procrustes_refinement.h"
#include "solvers/procrustes/stretch_table.h"

namespace blocklab {

// One start of the screened search: base points (in the box), error, and each landmark coordinate's raw and mapped
// value at them.
struct ScreenedStart {
  double x[kLandmarkFitParameterCount];
  double error;
  double raw[2 * kFitLandmarkCount], mapped[2 * kFitLandmarkCount];
};

// The screened search's working buffers (owned by the caller, e.g. ProcrustesWorkspace; cleared before use).
struct ScreeningBuffers {
  std::vector<int> nearest, scratch;                                     // per point: assignment, trial's
  std::vector<std::pair<double, std::size_t>> best_start, best_snapped;  // top lists (error, candidate)
  std::vector<ScreenedStart> states;                                     // the refined starts
  std::vector<std::uint64_t> seen;                                       // duplicate keys
  std::vector<std::array<double, kLandmarkFitParameterCount>> snapped;   // snapped points so far
};

// The screened search (file comment, steps 1-3). `candidates` are ranked by bound (procrustes_solver.h step 3);
// `problem` supplies the lattice of the snap; `targets` the mapped points (all u, then all v; RefineMeasure::map)
// for `measure`. Returns the candidates to evaluate on the problem's error, best (by the measured error at the
// snapped point) first: their base points are the refined, boxed ones. screened = 0 means every candidate;
// evaluated = 0 means every refined (or, without refinement, screened) candidate.
std::vector<ProcrustesCandidate> screen_procrustes_candidates(const Problem& problem,
                                                              const std::vector<double>& targets,
                                                              const std::vector<double>& weights,
                                                              const RefineMeasure& measure,
                                                              const LandmarkCoefficients& landmarks,
                                                              const std::vector<ProcrustesCandidate>& candidates,
                                                              const std::vector<PointClustering>& levels,
                                                              int screened, int refined, int iterations,
                                                              int evaluated, ScreeningBuffers& buffers);

}  // namespace blocklab
