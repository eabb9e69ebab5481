// `ceres_lm` solver (solvers/ceres_lm/ceres_lm_solver.h): Levenberg-Marquardt through Ceres 2.1 on the Problem's
// residuals and Jet Jacobian.
#include "solvers/ceres_lm/ceres_lm_solver.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "solvers/ceres_lm/problem_cost_function.h"

namespace blocklab {

namespace {

constexpr const char* kName = "ceres_lm";

constexpr const char* kDescription =
    "Levenberg-Marquardt (Ceres 2.1 trust region, dense QR, 1 thread) on the residuals and Jet Jacobian";

// Every option of CeresLmOptions, declared once (core/options.h OptionTable): specs, is_valid and from_resolved.
const OptionTable<CeresLmOptions>& ceres_lm_option_table() {
  static const auto table = OptionTable<CeresLmOptions>()
      .integer("max_iterations", &CeresLmOptions::max_iterations, 1, 1000000000, "maximum number of LM iterations")
      .real("function_tolerance", &CeresLmOptions::function_tolerance, 0.0, 1.0, "stop when |delta cost| / cost falls below this")
      .real("gradient_tolerance", &CeresLmOptions::gradient_tolerance, 0.0, 1.0,
            "stop when the max-norm of the projected gradient falls below this")
      .real("parameter_tolerance", &CeresLmOptions::parameter_tolerance, 0.0, 1.0,
            "stop when |delta x| / (|x| + parameter_tolerance) falls below this")
      .real("initial_trust_region_radius", &CeresLmOptions::initial_trust_region_radius, 0.0, DBL_MAX,
            "initial trust region radius (Ceres' 1/mu of the LM damping)", kLowerOpen)
      .real("time_limit", &CeresLmOptions::time_limit, 0.0, DBL_MAX, kTimeLimitHelp, kLowerOpen);
  return table;
}

std::vector<OptionSpec> ceres_lm_option_specs() { return ceres_lm_option_table().specs(); }

// Start value of parameter p: the given start clamped into the box, else the box centre (see the header).
double start_value(const Problem& problem, int p, const double* start) {
  const double lo = problem.lower(p), hi = problem.upper(p);
  if (start != nullptr) {
    double value = start[p];
    if (!(value >= lo)) value = lo;   // below the box, or NaN: the lower bound (NaN would stay NaN under clamp)
    if (value > hi) value = hi;
    // A NaN start with an infinite lower bound: fall back to the centre rule below.
    if (std::isfinite(value)) return value;
  }
  if (std::isfinite(lo) && std::isfinite(hi)) return lo + 0.5 * (hi - lo);
  if (std::isfinite(lo)) return lo;   // half-infinite box: its finite end
  if (std::isfinite(hi)) return hi;
  return 0.0;                          // no finite bound at all
}

Termination termination_of(ceres::TerminationType type) {
  switch (type) {
    case ceres::CONVERGENCE: return Termination::converged;
    case ceres::NO_CONVERGENCE: return Termination::max_iterations;
    default: return Termination::failed;   // FAILURE (and the USER_* types, which this cost function never uses)
  }
}

}  // namespace

bool CeresLmOptions::is_valid(std::string* why) const { return ceres_lm_option_table().is_valid(*this, why); }

CeresLmOptions CeresLmOptions::from_resolved(const SolverOptions& resolved) {
  return ceres_lm_option_table().from_resolved(resolved);
}

SolveResult solve_ceres_lm(const Problem& problem, const CeresLmOptions& options, const double* start,
                           std::uint64_t seed) {
  const auto started = std::chrono::steady_clock::now();
  require_valid_options(kName, options);
  ProblemCostFunction cost_function(problem, kName);   // throws when the problem has no residuals

  SolveResult result = begin_solve(kName, problem, start, seed);
  Summary& summary = result.summary;
  const int dim = problem.dim();
  std::vector<double>& x = result.parameters;
  x.resize(static_cast<std::size_t>(dim));
  for (int p = 0; p < dim; ++p) x[static_cast<std::size_t>(p)] = start_value(problem, p, start);

  ceres::Problem::Options problem_options;
  // The cost function lives on this stack frame; Ceres must not delete it.
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem ceres_problem(problem_options);
  ceres_problem.AddResidualBlock(&cost_function, nullptr, x.data());
  for (int p = 0; p < dim; ++p) {
    // Only finite bounds are handed to Ceres (an infinite bound is no bound).
    if (std::isfinite(problem.lower(p))) ceres_problem.SetParameterLowerBound(x.data(), p, problem.lower(p));
    if (std::isfinite(problem.upper(p))) ceres_problem.SetParameterUpperBound(x.data(), p, problem.upper(p));
  }

  ceres::Solver::Options solver_options;
  solver_options.minimizer_type = ceres::TRUST_REGION;
  solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.num_threads = 1;
  solver_options.max_num_iterations = static_cast<int>(std::min<std::int64_t>(options.max_iterations, 1 << 30));
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.gradient_tolerance = options.gradient_tolerance;
  solver_options.parameter_tolerance = options.parameter_tolerance;
  solver_options.initial_trust_region_radius = options.initial_trust_region_radius;
  solver_options.max_trust_region_radius = std::max(solver_options.max_trust_region_radius,
                                                    options.initial_trust_region_radius);
  solver_options.max_solver_time_in_seconds = options.time_limit;
  solver_options.logging_type = ceres::SILENT;
  solver_options.minimizer_progress_to_stdout = false;
  std::string ceres_why;
  if (!solver_options.IsValid(&ceres_why)) fail(kName, "Ceres rejected the options: " + ceres_why);

  ceres::Solver::Summary ceres_summary;
  ceres::Solve(solver_options, &ceres_problem, &ceres_summary);
  std::uint64_t iterations = ceres_summary.iterations.empty() ? 0 : ceres_summary.iterations.size() - 1;
  std::uint64_t successful_steps = static_cast<std::uint64_t>(std::max(0, ceres_summary.num_successful_steps));

  // Active-set polish. Ceres enforces bounds by projecting each LM step onto the box, so a step that wants to
  // leave the box along a bound is clipped as a whole and the free parameters stall short of their optimum
  // (measured: constrained Rosenbrock, x0 <= 0.5, stops at x1 = 0.2524 instead of 0.25). Parameters that sit on
  // a bound with the gradient pushing outward are held constant (SubsetManifold) and the rest re-solved, until
  // that set stops changing (at most dim rounds).
  std::vector<int> held;
  for (int round = 0; round < dim && ceres_summary.termination_type != ceres::FAILURE; ++round) {
    std::vector<double> gradient(static_cast<std::size_t>(dim));
    problem.eval_with_gradient(x.data(), gradient.data());
    ++summary.gradient_evaluations;
    std::vector<int> pinned;
    for (int p = 0; p < dim; ++p) {
      const double value = x[static_cast<std::size_t>(p)], slope = gradient[static_cast<std::size_t>(p)];
      // On a bound with descent pointing out of the box: the KKT sign of an active constraint.
      if ((value <= problem.lower(p) && slope > 0.0) || (value >= problem.upper(p) && slope < 0.0)) pinned.push_back(p);
    }
    if (pinned.empty() || pinned == held || static_cast<int>(pinned.size()) == dim) break;
    // The polish rounds share the solve's time limit: each gets what the earlier solves left.
    const double remaining = options.time_limit - seconds_since(started);
    if (!(remaining > 0.0)) break;
    solver_options.max_solver_time_in_seconds = remaining;
    held = pinned;
    ceres_problem.SetManifold(x.data(), new ceres::SubsetManifold(dim, held));   // Ceres owns the manifold
    ceres::Solver::Summary polish_summary;
    ceres::Solve(solver_options, &ceres_problem, &polish_summary);
    iterations += polish_summary.iterations.empty() ? 0 : polish_summary.iterations.size() - 1;
    successful_steps += static_cast<std::uint64_t>(std::max(0, polish_summary.num_successful_steps));
    ceres_summary = polish_summary;
  }

  summary.evaluations += cost_function.residual_evaluations();
  summary.gradient_evaluations = cost_function.jacobian_evaluations();
  summary.termination = termination_of(ceres_summary.termination_type);
  // Ceres reports both budgets as NO_CONVERGENCE; the clock tells the time limit apart.
  const bool time_limit_reached = seconds_since(started) >= options.time_limit &&
                                  ceres_summary.termination_type == ceres::NO_CONVERGENCE;
  if (time_limit_reached) summary.termination = Termination::max_seconds;
  summary.final_error = problem.eval(x.data());
  ++summary.evaluations;
  summary.message = std::to_string(iterations) + " iterations (" + std::to_string(successful_steps) +
                    " successful" + (held.empty() ? std::string() : ", " + std::to_string(held.size()) +
                                                                        " parameters held on a bound") +
                    "); " + ceres_summary.message;
  if (time_limit_reached) summary.message = TimeLimit(started, options.time_limit).message() + "; " + summary.message;
  if (std::isnan(summary.final_error)) summary.termination = Termination::failed;   // never report a NaN answer
  summary.seconds = seconds_since(started);
  return result;
}

const Solver& ceres_lm_solver() {
  static const TypedSolver<CeresLmOptions> solver(kName, kDescription, ceres_lm_option_specs, solve_ceres_lm);
  return solver;
}

}  // namespace blocklab
