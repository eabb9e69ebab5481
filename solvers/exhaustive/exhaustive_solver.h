// `exhaustive`: evaluates the error at every point of a problem's storage lattice and keeps the best.
//
// The brute-force oracle every other solver is checked against on small lattices: its answer is the exact
// minimum of the point error over the lattice (not over the continuous box). Points are visited in
// lexicographic order of their index tuples (k_0, ..., k_{dim-1}) with the last parameter varying fastest, and a
// strictly smaller error is needed to replace the incumbent, so among equal errors the lexicographically lowest
// index tuple wins and the result is deterministic. Points with a NaN error are invalid and skipped.
#pragma once

#include <cstdint>
#include <string>

#include "solvers/solver.h"

namespace blocklab {

struct ExhaustiveOptions {
  // Refuse lattices with more points than this (the solve would take too long); option `max_points`.
  std::int64_t max_points = std::int64_t{1} << 22;
  // Wall-time seconds per solve (option `time_limit`); at the limit the best point so far is returned.
  double time_limit = kDefaultTimeLimit;

  // False (with the reason in *why when why is not null) when an option is out of range.
  bool is_valid(std::string* why) const;
  // Reads a resolved option map (resolve_solver_options(exhaustive_solver(), ...)).
  static ExhaustiveOptions from_resolved(const SolverOptions& resolved);
};

// Throws Error("exhaustive: ...") when the options are invalid, a parameter has no lattice, or the lattice has
// more than options.max_points points. The seed is only recorded (the search is deterministic).
SolveResult solve_exhaustive(const Problem& problem, const ExhaustiveOptions& options, const double* start,
                             std::uint64_t seed);

const Solver& exhaustive_solver();

}  // namespace blocklab
