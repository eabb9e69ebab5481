// `lattice_polish`: snap a continuous answer to the storage lattice, then search the nearby lattice points
// ("Practical HDR Texture Compression" (2008) section 7.1: "To further improve the solution, we search in a small
// radius of quantized values around each base point to minimize the mean square error"; MISSION.md "Lattice polish").
//
// Algorithm (deterministic; the seed is only recorded):
//   * Start: the start point snapped per parameter to the nearest lattice index (Lattice::nearest_index, ties to
//     the lower index). Without a start point the lattice's middle index of each parameter is used (said in the
//     Summary message).
//   * radius 1: the full neighbourhood, every index tuple within +-1 of the centre per parameter (3^dim points,
//     clipped at the lattice ends), visited in lexicographic order of the offsets (last parameter fastest).
//   * radius > 1: coordinate-wise descent, because (2r+1)^dim grows too fast: for each parameter in turn, every
//     index within +-radius of the current one with the other parameters fixed.
//   * A strictly lower error moves the incumbent (ties keep the earlier point). With max_passes > 1 the search is
//     repeated around the new incumbent until a pass finds no improvement (termination `converged`: a local
//     minimum of the lattice for that neighbourhood) or max_passes passes ran (termination `max_iterations`).
// Requires a lattice on every parameter (Error otherwise). NaN errors mark invalid points and are skipped.
#pragma once

#include <cstdint>
#include <string>

#include "solvers/solver.h"

namespace blocklab {

struct LatticePolishOptions {
  int radius = 1;        // option radius, >= 1: lattice steps searched around the incumbent per parameter
  int max_passes = 16;   // option max_passes, >= 1: 1 = one search around the snapped start (the paper's step)
  // Largest neighbourhood enumerated in full; dim with (2r+1)^dim above it falls back to coordinate descent even
  // at radius 1 (3^12 = 531441). Option full_neighbourhood_limit.
  std::int64_t full_neighbourhood_limit = 531441;
  double time_limit = kDefaultTimeLimit;   // option time_limit: wall-time seconds per solve

  bool is_valid(std::string* why) const;
  static LatticePolishOptions from_resolved(const SolverOptions& resolved);
};

// Throws Error("lattice_polish: ...") on invalid options or a parameter without a lattice.
SolveResult solve_lattice_polish(const Problem& problem, const LatticePolishOptions& options, const double* start,
                                 std::uint64_t seed);

const Solver& lattice_polish_solver();

}  // namespace blocklab
