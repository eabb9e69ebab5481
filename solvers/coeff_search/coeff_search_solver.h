// `coeff_search`: deterministic grid search with zoom refinement, then coordinate hill climbing, for problems with
// a few parameters (built for image-level coefficients such as the wavelet format's outlier clamp fraction and
// gamma; usable for any low-dimensional Problem). A classic "coarse grid, zoom, polish" scheme (the grid-then-
// local-polish recipe of SPECS.md section 5, item 2, without an external library).
//
// Each parameter is searched in its own coordinate: its value (continuous, finite bounds required) or its lattice
// index (a parameter with a lattice is only ever evaluated at lattice points).
//   1. Grid: grid_points equally spaced values per parameter over the current window (lattice: the rounded
//      indices, duplicates dropped, so a window with fewer indices than grid_points is enumerated completely);
//      every tuple is evaluated, last parameter fastest. The first window is the whole box.
//   2. Zoom, refinement_levels times: the window shrinks to the best point +- one grid spacing (clipped to the
//      previous window; lattice: rounded outward to whole indices) and step 1 is repeated.
//   3. Hill climbing, at most hill_climb_steps sweeps: each sweep tries best +- step on every parameter in order
//      and moves to the first strictly better point; a sweep without a move halves every step (lattice steps
//      never go below one index). Starting steps are the last grid spacing. It stops, converged, when no
//      parameter moves and every continuous step is below tolerance x box width and every lattice step is one.
// The incumbent starts as the `start` point (clamped, snapped to the lattice) when given and is replaced only by
// a strictly smaller error, so the search is deterministic (no randomness; the seed is only recorded) and ties go
// to the earliest point. NaN errors are skipped. Termination: converged, max_iterations (the sweep budget ran out,
// or hill_climb_steps = 0), failed (no valid point).
#pragma once

#include <cstdint>
#include <string>

#include "solvers/solver.h"

namespace blocklab {

struct CoeffSearchOptions {
  std::int64_t grid_points = 9;          // per parameter and level (>= 2); option `grid_points`
  std::int64_t refinement_levels = 3;    // zooms after the first grid; option `refinement_levels`
  std::int64_t hill_climb_steps = 100;   // sweeps of coordinate hill climbing; option `hill_climb_steps`
  double tolerance = 1e-9;               // continuous step at convergence, fraction of the box width
  std::int64_t max_grid_points = 1000000;   // refuse (Error) a grid of more tuples; option `max_grid_points`
  double time_limit = kDefaultTimeLimit;   // wall-time seconds per solve; option `time_limit`

  bool is_valid(std::string* why) const;
  static CoeffSearchOptions from_resolved(const SolverOptions& resolved);
};

SolveResult solve_coeff_search(const Problem& problem, const CoeffSearchOptions& options, const double* start,
                               std::uint64_t seed);

const Solver& coeff_search_solver();

}  // namespace blocklab
