// `ceres_lm`: Levenberg-Marquardt through Ceres Solver 2.1 (trust region, LEVENBERG_MARQUARDT strategy, dense QR,
// one thread) on a Problem's least-squares form (Levenberg 1944, Marquardt 1963; Ceres "Solver::Options").
//
// The Problem's residuals and their exact Jacobian (Problem::eval_residuals: ceres::Jet automatic differentiation
// of the functor's `residuals`) are wrapped in one ceres::CostFunction with a single parameter block of dim()
// values; finite bounds become SetParameterLowerBound / SetParameterUpperBound (Ceres projects steps onto the box).
// Ceres minimises 1/2 sum r_i^2; Summary errors are the Problem's error, sum r_i^2.
//
// Decisions:
//   * A Problem without residuals (functor without kResiduals) is an Error naming the solver and the reason; use
//     `nlopt` (e.g. LD_LBFGS on the Jet gradient) for plain scalar errors.
//   * The search is continuous: lattices are ignored and lattice_indices stays empty (snap with a lattice solver
//     afterwards). SPECS.md section 5: through a quantiser the Jet Jacobian is zero and LM stops at once, so use
//     ceres_lm on smooth surrogates and polish the quantised objective with a derivative-free solver.
//   * Start: `start` clamped into the box; without one, the box centre (0 for a parameter with no finite bound,
//     the finite bound for a half-infinite one). Ceres requires a feasible start.
//   * Bounds: Ceres projects each LM step onto the box, which can stall the free parameters when the optimum lies
//     on a bound. After Ceres stops, parameters on a bound whose gradient points out of the box are held constant
//     (ceres::SubsetManifold) and the others re-solved, until that active set stops changing (an active-set
//     polish, at most dim rounds; counted in the Summary).
//   * A non-finite residual or Jacobian entry makes the evaluation fail (Ceres then shrinks the trust region).
//   * Deterministic and thread-safe: each solve builds its own ceres::Problem, runs single-threaded, logs nothing
//     (logging_type = SILENT); the seed is only recorded.
// Termination: Ceres CONVERGENCE -> converged, NO_CONVERGENCE -> max_iterations, FAILURE -> failed (message is
// Ceres' own).
#pragma once

#include <cstdint>
#include <string>

#include "solvers/solver.h"

namespace blocklab {

struct CeresLmOptions {
  std::int64_t max_iterations = 200;     // option `max_iterations`
  // Ceres' three convergence tests (Solver::Options with the same names), tighter than Ceres' defaults
  // (1e-6, 1e-10, 1e-8) so certified problems are met to about 1e-12 relative. The cost test is off by default:
  // on a problem with a large residual at the optimum it stops while the parameters are still ~1e-9 off
  // (measured: the one-outlier mean stopped 7e-10 away, cost change 3e-16 relative), and the parameter test
  // ends the zero-residual problems.
  double function_tolerance = 0.0;       // |delta cost| / cost (0: off)
  double gradient_tolerance = 1e-14;     // max-norm of the projected gradient
  double parameter_tolerance = 1e-12;    // |delta x| / (|x| + parameter_tolerance)
  double initial_trust_region_radius = 1e4;   // Ceres' default; option `initial_trust_region_radius`
  double time_limit = kDefaultTimeLimit;      // wall-time seconds per solve (Ceres' max_solver_time_in_seconds)

  bool is_valid(std::string* why) const;
  static CeresLmOptions from_resolved(const SolverOptions& resolved);
};

SolveResult solve_ceres_lm(const Problem& problem, const CeresLmOptions& options, const double* start,
                           std::uint64_t seed);

const Solver& ceres_lm_solver();

}  // namespace blocklab
