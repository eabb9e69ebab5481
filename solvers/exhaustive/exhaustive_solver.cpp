// `exhaustive` solver (solvers/exhaustive/exhaustive_solver.h): full enumeration of the storage lattice, the
// brute-force reference for the searches of the HDR texture papers of 2006 and 2008 (SPECS.md section 6) and every
// later solver.
#include "solvers/exhaustive/exhaustive_solver.h"

#include <chrono>
#include <cmath>
#include <vector>

#include "core/error.h"

namespace blocklab {

namespace {

constexpr const char* kName = "exhaustive";

constexpr const char* kDescription =
    "every point of the storage lattice, best kept (ties: lowest index); the brute-force oracle";

// Every option of ExhaustiveOptions, declared once (core/options.h OptionTable): specs, is_valid and from_resolved.
const OptionTable<ExhaustiveOptions>& exhaustive_option_table() {
  static const auto table = OptionTable<ExhaustiveOptions>()
      .integer("max_points", &ExhaustiveOptions::max_points, 1, kMaxExactInteger,
               "refuse (error) a lattice with more points than this")
      .real("time_limit", &ExhaustiveOptions::time_limit, 0.0, DBL_MAX, kTimeLimitHelp, kLowerOpen);
  return table;
}

std::vector<OptionSpec> exhaustive_option_specs() { return exhaustive_option_table().specs(); }

std::string lattice_extent(const Problem& problem) {
  std::string extent;
  for (int i = 0; i < problem.dim(); ++i) extent += (i ? " x " : "") + std::to_string(problem.lattice(i).count);
  return extent;
}

}  // namespace

bool ExhaustiveOptions::is_valid(std::string* why) const { return exhaustive_option_table().is_valid(*this, why); }

ExhaustiveOptions ExhaustiveOptions::from_resolved(const SolverOptions& resolved) {
  return exhaustive_option_table().from_resolved(resolved);
}

SolveResult solve_exhaustive(const Problem& problem, const ExhaustiveOptions& options, const double* start,
                             std::uint64_t seed) {
  const auto started = std::chrono::steady_clock::now();
  require_valid_options(kName, options);
  const int dim = problem.dim();
  require_full_lattice(kName, problem, "exhaustive enumerates lattice points");
  const std::uint64_t point_count = problem.lattice_point_count();
  if (point_count > static_cast<std::uint64_t>(options.max_points))
    fail(kName, "the lattice has " +
                    (point_count == UINT64_MAX ? std::string("more than 2^64") : std::to_string(point_count)) +
                    " points (" + lattice_extent(problem) + "), more than max_points = " +
                    std::to_string(options.max_points));

  SolveResult result = begin_solve(kName, problem, start, seed);
  Summary& summary = result.summary;

  // Odometer over index tuples, last parameter fastest; x holds the lattice points of the current tuple.
  std::vector<std::int64_t> index(static_cast<std::size_t>(dim), 0);
  std::vector<double> x(static_cast<std::size_t>(dim));
  for (int i = 0; i < dim; ++i) x[static_cast<std::size_t>(i)] = problem.lattice(i).point(0);
  std::vector<std::int64_t> best_index = index;
  double best_error = 0.0;
  bool found = false;
  std::uint64_t invalid_count = 0;
  TimeLimit time_limit(started, options.time_limit);
  std::uint64_t visited = 0;
  for (; visited < point_count && !time_limit.reached(); ++visited) {
    const double error = problem.eval(x.data());
    if (std::isnan(error)) {
      ++invalid_count;   // NaN marks an invalid point: never the answer
    } else if (!found || error < best_error) {   // strict: an equal error keeps the earlier (lower) index
      best_error = error;
      best_index = index;
      found = true;
    }
    for (int i = dim - 1; i >= 0; --i) {
      const std::size_t p = static_cast<std::size_t>(i);
      const Lattice& lattice = problem.lattice(i);
      if (++index[p] < lattice.count) {
        x[p] = lattice.point(index[p]);
        break;
      }
      index[p] = 0;   // carry into the next slower parameter
      x[p] = lattice.point(0);
    }
  }
  summary.evaluations += visited;

  result.lattice_indices = best_index;
  result.parameters.resize(static_cast<std::size_t>(dim));
  for (int i = 0; i < dim; ++i)
    result.parameters[static_cast<std::size_t>(i)] = problem.lattice(i).point(best_index[static_cast<std::size_t>(i)]);
  if (found && time_limit.was_reached()) {
    // Only the first `visited` points (odometer order) were examined: the best of them, no proof.
    summary.termination = Termination::max_seconds;
    summary.final_error = best_error;
    summary.message = time_limit.message() + " after " + std::to_string(visited) + " of " +
                      std::to_string(point_count) + " lattice points (" + lattice_extent(problem) + ")";
  } else if (found) {
    summary.termination = Termination::optimal;
    summary.final_error = best_error;
    // Every lattice point was evaluated, so the minimum over the lattice is proven.
    summary.lower_bound = best_error;
    summary.gap = 0.0;
    summary.message = std::to_string(point_count) + " lattice points (" + lattice_extent(problem) + ")";
    if (invalid_count > 0) summary.message += ", " + std::to_string(invalid_count) + " with a NaN error skipped";
  } else {
    // No valid point: return the first lattice point with a NaN error rather than inventing a value.
    summary.termination = Termination::failed;
    summary.message = "the error is NaN at all " + std::to_string(visited) + " lattice points";
    if (time_limit.was_reached()) summary.message += " evaluated (" + time_limit.message() + ")";
  }
  summary.seconds = seconds_since(started);
  return result;
}

const Solver& exhaustive_solver() {
  static const TypedSolver<ExhaustiveOptions> solver(kName, kDescription, exhaustive_option_specs, solve_exhaustive);
  return solver;
}

}  // namespace blocklab
