// `nlopt`: any NLopt 2.7.1 algorithm by its NLopt name (Johnson, "The NLopt nonlinear-optimization package",
// https://github.com/stevengj/nlopt; SPECS.md section 5 recommends LN_NELDERMEAD / LN_SBPLX with a large initial
// step, or GN_DIRECT_L, to polish quantised objectives).
//
// The algorithm option takes NLopt's own names ("LN_NELDERMEAD", "LN_SBPLX", "LN_BOBYQA", "LN_COBYLA",
// "GN_DIRECT_L", "GN_CRS2_LM", "LD_LBFGS", "LD_MMA", ...: every nlopt_algorithm_to_string name of the library);
// an unknown name is an Error listing the valid ones. Gradient algorithms (LD_*, GD_*) get the exact Jet gradient
// (Problem::eval_with_gradient), derivative-free ones the double error (Problem::eval). Bounds are the Problem's
// (infinite bounds allowed for local algorithms; global ones, G*, need a finite box: Error otherwise). Algorithms
// that drive a subsidiary optimiser (AUGLAG*, *MLSL*) get `local_algorithm` with the same xtol/ftol.
//
// Decisions:
//   * NaN error (invalid point) is returned to NLopt as DBL_MAX with a zero gradient, so every algorithm treats
//     it as a very bad point instead of stopping; the answer is the best valid point evaluated (ties: earliest).
//   * Start: `start` clamped into the box; without one, the box centre (0 / the finite end for infinite bounds).
//   * initial_step is a fraction of each parameter's box width (0: NLopt's own heuristic), so it scales with the
//     lattice; it needs finite bounds when > 0.
//   * Continuous search: lattices are ignored and lattice_indices stays empty.
//   * SEEDING AND THREADS: NLopt's random generator is library-global state (thread-local only when the library
//     was built with TLS support, which this code does not rely on). The solves of STOCHASTIC algorithms
//     (GN_CRS2_LM, GN_ISRES, GN_ESCH, *_RAND, *MLSL*, LN_PRAXIS, GD_STOGO_RAND, or a stochastic local_algorithm)
//     call nlopt_srand(seed) right before nlopt_optimize and are serialised by one process-wide mutex held from
//     nlopt_srand to the end of the solve: a stochastic solve is deterministic for its seed at any thread count,
//     at the price of running one at a time. Deterministic algorithms never draw random numbers, so they are not
//     seeded (seeding them would reset the generator under a concurrent stochastic solve) and never take the
//     mutex. NLopt seeds itself from the clock on its first solve unless nlopt_srand was called, so the generator
//     is seeded once (under the mutex) before the first solve of any algorithm.
// Termination: NLOPT_SUCCESS / STOPVAL / FTOL / XTOL -> converged, MAXEVAL -> max_evaluations, MAXTIME ->
// max_seconds, ROUNDOFF_LIMITED -> no_progress, FAILURE / FORCED_STOP -> failed; INVALID_ARGS is an Error with
// NLopt's message.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solvers/solver.h"

namespace blocklab {

struct NloptOptions {
  std::string algorithm = "LN_SBPLX";          // option `algorithm`
  std::string local_algorithm = "LN_BOBYQA";   // subsidiary optimiser of AUGLAG / MLSL; option `local_algorithm`
  std::int64_t max_evaluations = 2000;         // objective evaluations (NLopt maxeval); option `max_evaluations`
  double xtol_rel = 1e-10;                     // relative parameter tolerance; option `xtol_rel` (0: off)
  double ftol_rel = 1e-14;                     // relative error tolerance; option `ftol_rel` (0: off)
  double initial_step = 0.0;                   // fraction of the box width; 0: NLopt's default; `initial_step`
  std::int64_t population = 0;                 // CRS / ISRES / ESCH / MLSL population; 0: NLopt's default
  double time_limit = kDefaultTimeLimit;       // wall-time seconds per solve (NLopt maxtime); `time_limit`

  bool is_valid(std::string* why) const;
  static NloptOptions from_resolved(const SolverOptions& resolved);
};

// Every algorithm name of the linked NLopt, in NLopt's enum order.
const std::vector<std::string>& nlopt_algorithm_names();
// True for the algorithms that draw from NLopt's random generator (serialised, see above).
bool nlopt_algorithm_is_stochastic(const std::string& name);

SolveResult solve_nlopt(const Problem& problem, const NloptOptions& options, const double* start,
                        std::uint64_t seed);

const Solver& nlopt_solver();

}  // namespace blocklab
