// Clamp-aware refinement of a Procrustes candidate transform ("Practical HDR Texture Compression" (2008) section 7.1;
// the refinement step of the `procrustes` solver, solvers/procrustes/procrustes_solver.h step 3), shared by the solver
// and callers that rank the candidates of several landmark sets (e.g. a format ranking several landmark sets).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/problem.h"
#include "solvers/procrustes/stretch_table.h"

namespace blocklab {

// One candidate similarity transform, as its base points (the images of landmarks 0 and 1).
struct ProcrustesCandidate {
  double error_bound = 0.0;   // Procrustes functional + scatter of the level
  Point2 base0, base1;
  bool duplicate = false;     // refinement met an earlier candidate's assignment: not evaluated
  int level = 0;              // cluster count of the level it was fit to (0: unknown)
};

// The measure the refinement descends (procrustes_solver.h step 3): the block's continuous error for base points
// x = (u0, v0, u1, v1) with the decoded landmarks clamped to [0, 1], each coordinate mapped through
// f(c) = max(c, kStretchFloor)^alpha for the stretched error (alpha < 1) or left as is (alpha = 1, the linear
// error): sum_i w_i min_k |f(p_i) - f(clamp(L_k(x)))|^2, as a landmark-fit Problem measures it before the lattice.
// The stretch comes from StretchTable (stretch_table.h, within 2e-13 relative of std::pow; a stretched solve maps
// hundreds of landmark coordinates, and libm pow was ~40 % of its time) and the slope from the mapped value, so
// this guide differs from the Problem's error by rounding only; the Problem's own error decides the answer.
struct RefineMeasure {
  double alpha = 1.0;
  const StretchTable* table = nullptr;   // the stretch of alpha != 1 (shared_stretch_table); nullptr: linear

  RefineMeasure() = default;
  explicit RefineMeasure(double exponent)
      : alpha(exponent), table(exponent == 1.0 ? nullptr : &shared_stretch_table(exponent)) {}

  // f(c) for c in [0, 1] (a clamped coordinate); a NaN stays NaN (the table must not see it).
  double map(double c) const {
    if (table == nullptr || c != c) return c;
    return (*table)(c);
  }
  // d f / d c at an unclamped c with f(c) = mapped: 1 (linear); alpha c^(alpha - 1) = alpha f(c) / c above the
  // floor; 0 at or below it (f is constant there).
  double slope(double c, double mapped) const {
    if (table == nullptr) return 1.0;
    return c > kStretchFloor ? alpha * mapped / c : 0.0;
  }
};

// Clamp-aware refinement of one candidate (procrustes options refined_candidates, refine_iterations; step 3 of
// procrustes_solver.h). `targets` holds the mapped points (RefineMeasure::map): all u values, then all v values;
// `nearest` and `next_nearest` are scratch of weights.size() entries; `seen` collects the duplicate keys (below).
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
// descent with the landmark set as constraint). The candidate keeps its ranking bound.
//
// Duplicates: the first assignment and clamp pattern of each refined candidate is recorded in `seen` (exactly, as
// 2 bits per point and per landmark coordinate, for up to 24 points; hashed for more). A candidate that starts from
// a pattern seen before would take the same least-squares step (for the linear error exactly, up to the ridge) and
// is marked `duplicate` and not refined further or evaluated.
// Solves the 4x4 system a y = b in place (Gaussian elimination, partial pivoting); y replaces b. False when a pivot
// vanishes (singular or non-finite system). The Gauss-Newton step of both refinements (this one and search=screened).
bool solve4(double (&a)[4][4], double (&b)[4]);

// Landmark coordinate rows (the landmark-fit capability of core/problem.h): coordinate 2k (u) and 2k + 1 (v) of
// landmark k as linear
// functions of the base points (u0, v0, u1, v1).
using LandmarkRows = std::array<std::array<double, 4>, 2 * kFitLandmarkCount>;
LandmarkRows landmark_rows(const LandmarkCoefficients& landmarks);

// One ridge-damped Gauss-Newton step of both refinements (this one and search=screened): from the per-coordinate
// weight sums W_j and residual sums R_j, N = sum_j W_j s_j^2 r_j r_j^T and rhs = sum_j R_j s_j r_j over the
// coordinates with weight, raw value inside [0, 1] (a clamped coordinate is constant in x) and non-zero slope
// s_j = measure.slope(raw_j, mapped_j) (computed for those coordinates only);
// a ridge of 1e-9 x the mean diagonal keeps unconstrained directions still. `step` receives N^-1 rhs. False when
// nothing is constrained or the system is singular (the caller keeps x).
bool landmark_gauss_newton_step(const double* coordinate_weight, const double* coordinate_residual, const double* raw,
                                const double* mapped, const RefineMeasure& measure, const LandmarkRows& rows,
                                double (&step)[4]);

ProcrustesCandidate refine_procrustes_candidate(const std::vector<double>& targets, const std::vector<double>& weights,
                                                const RefineMeasure& measure, const LandmarkCoefficients& landmarks,
                                                const ProcrustesCandidate& start, int iterations,
                                                std::vector<std::uint64_t>& seen, std::vector<int>& nearest,
                                                std::vector<int>& next_nearest);

}  // namespace blocklab
