// `interval_bb`: best-first interval branch-and-bound over the storage lattice of any Problem, certified optimal
// ON the lattice ("Practical HDR Texture Compression" (2008) section 7.1, "Simulated Annealing and Exhaustive Search":
// "we redefine the problem using interval arithmetic ... recursively split the search space into two halves. The
// traversal of splits are sorted by error intervals, and when we find a solution, it can be used to cull further
// traversal ... we continue the recursion until we reach the resolution used to store the base colors"; SPECS.md
// section 6).
//
// Algorithm (deterministic; the seed is only recorded):
//   * Boxes are ranges of lattice INDICES per parameter, [lo_p, hi_p]; the interval error is evaluated over the
//     box spanned by their lattice points [point(lo_p), point(hi_p)]. Only lattice points are candidates, so this
//     box (not the continuous cell around it) is all that needs bounding.
//   * Best-first: a priority queue on the box's interval lower bound; among equal bounds the most recently created
//     box pops first (depth-first on ties, deterministic).
//   * Incumbent: the start point (when given) snapped to the nearest lattice point, and the lattice point at the
//     centre index of every box created (mid = lo + (hi - lo) / 2 per parameter); a strictly lower point error
//     replaces it (NaN errors mark invalid points and are skipped).
//   * Split: the widest parameter in lattice units (hi - lo; ties: the lowest parameter) into [lo, mid] and
//     [mid + 1, hi]. A box holding a single lattice point is evaluated exactly (point error) instead of bounded.
//   * Leaves: a popped box holding at most `leaf_points` lattice points (default 32) is not split but enumerated:
//     every lattice point of it is evaluated exactly (odometer order, last parameter fastest). That proves as much
//     as bounding its subtree (no point of it lies below the incumbent afterwards) and costs less, since a point
//     error is 10-100x cheaper than an enclosure. Default measured on the chroma landmark fit (docs/solver-bench.md,
//     2026-11-26): with the pair bound, 32 takes 7 % fewer instructions than 64 for the stretched error and 2 %
//     for the linear one (16 is as good; 128 is 10 % worse). leaf_points = 1 bounds every box.
//   * Prune: a box whose lower bound >= incumbent - relative_gap * |incumbent| is discarded. With the default
//     relative_gap = 0, boxes that can only TIE the incumbent are discarded too: the answer is a lattice point of
//     minimal error, not necessarily the lowest-index one among equals (unlike `exhaustive`).
//   * Stop: the queue is empty or its best lower bound meets the prune threshold -> termination `optimal`,
//     lower_bound = min(incumbent, lower bounds of every pruned box), gap = final_error - lower_bound (0 with
//     relative_gap = 0). A budget (max_boxes interval evaluations -> `max_evaluations`, time_limit ->
//     `max_seconds`) stops early with the current incumbent and the proven lower bound (min over pruned and
//     queued boxes) and gap.
// What "certified" means: the interval enclosures are rigorous (core/interval.h, outward rounding), so no pruned
// box holds a lattice point whose exact error is below its bound; the incumbent's error is a double evaluation, so
// the result is the lattice minimum up to the rounding of one point evaluation (~1e-15 relative).
// time_limit (every solver's option, solvers/solver.h) defaults to 10 s, which the searches of the formats never
// reach; a limit that is reached makes the result depend on the machine and its load, so such results are not
// reproducible.
#pragma once

#include <cstdint>
#include <string>

#include "solvers/solver.h"

namespace blocklab {

struct IntervalBbOptions {
  std::int64_t max_boxes = std::int64_t{1} << 30;   // option max_boxes: interval evaluations budget
  double time_limit = kDefaultTimeLimit;            // option time_limit: wall-time seconds per solve
  double relative_gap = 0.0;                        // option relative_gap: prune margin relative to |incumbent|
  std::int64_t leaf_points = 32;                    // option leaf_points: popped boxes this small are enumerated

  bool is_valid(std::string* why) const;
  static IntervalBbOptions from_resolved(const SolverOptions& resolved);
};

// Throws Error("interval_bb: ...") on invalid options or a parameter without a lattice.
SolveResult solve_interval_bb(const Problem& problem, const IntervalBbOptions& options, const double* start,
                              std::uint64_t seed);

const Solver& interval_bb_solver();

}  // namespace blocklab
