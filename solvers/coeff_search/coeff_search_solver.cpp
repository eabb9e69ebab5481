// `coeff_search` solver (solvers/coeff_search/coeff_search_solver.h): grid, zoom refinement, coordinate hill
// climbing; deterministic.
#include "solvers/coeff_search/coeff_search_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"

namespace blocklab {

namespace {

constexpr const char* kName = "coeff_search";

constexpr const char* kDescription =
    "deterministic grid search with zoom refinement and coordinate hill climbing (few parameters)";

// Every option of CoeffSearchOptions, declared once (core/options.h OptionTable): specs, is_valid and from_resolved.
const OptionTable<CoeffSearchOptions>& coeff_search_option_table() {
  static const auto table = OptionTable<CoeffSearchOptions>()
      .integer("grid_points", &CoeffSearchOptions::grid_points, 2, 1000000, "grid points per parameter and level")
      .integer("refinement_levels", &CoeffSearchOptions::refinement_levels, 0, 1000,
               "zooms around the best grid point after the first grid")
      .integer("hill_climb_steps", &CoeffSearchOptions::hill_climb_steps, 0, 1000000000,
               "sweeps of coordinate hill climbing after the grids")
      .real("tolerance", &CoeffSearchOptions::tolerance, 0.0, 1.0,
            "continuous hill-climbing step at convergence, as a fraction of the box width")
      .integer("max_grid_points", &CoeffSearchOptions::max_grid_points, 1, kMaxExactInteger,
               "refuse a grid with more tuples than this")
      .real("time_limit", &CoeffSearchOptions::time_limit, 0.0, DBL_MAX, kTimeLimitHelp, kLowerOpen);
  return table;
}

std::vector<OptionSpec> coeff_search_option_specs() { return coeff_search_option_table().specs(); }

class CoeffSearch {
 public:
  CoeffSearch(const Problem& problem, const CoeffSearchOptions& options, Summary& summary, TimeLimit& time_limit)
      : problem_(problem), options_(options), summary_(summary), time_limit_(time_limit), dim_(problem.dim()) {
    const std::size_t n = static_cast<std::size_t>(dim_);
    x_.assign(n, 0.0);
    best_coordinate_.assign(n, 0.0);
    window_lo_.assign(n, 0.0);
    window_hi_.assign(n, 0.0);
    for (int p = 0; p < dim_; ++p) {
      const Lattice& lattice = problem.lattice(p);
      window_lo_[static_cast<std::size_t>(p)] = lattice.present() ? 0.0 : problem.lower(p);
      window_hi_[static_cast<std::size_t>(p)] =
          lattice.present() ? static_cast<double>(lattice.count - 1) : problem.upper(p);
    }
    best_coordinate_ = window_lo_;   // the answer when no point is valid: the lower corner
  }

  bool on_lattice(int p) const { return problem_.lattice(p).present(); }

  // Parameter value of coordinate u (a lattice index for lattice parameters).
  double value_of(int p, double u) const {
    return on_lattice(p) ? problem_.lattice(p).point(static_cast<std::int64_t>(u)) : u;
  }

  // Evaluates the point with coordinates u[0..dim); a strictly better valid error becomes the incumbent. Past the
  // time limit nothing is evaluated (and the loops below stop).
  bool try_point(const std::vector<double>& u) {
    if (time_limit_.reached()) return false;
    for (int p = 0; p < dim_; ++p) x_[static_cast<std::size_t>(p)] = value_of(p, u[static_cast<std::size_t>(p)]);
    ++summary_.evaluations;
    const double error = problem_.eval(x_.data());
    if (std::isnan(error)) return false;   // invalid point: skipped
    if (found_ && !(error < best_error_)) return false;
    best_error_ = error;
    best_coordinate_ = u;
    found_ = true;
    return true;
  }

  void seed_with_start(const double* start) {
    std::vector<double> u(static_cast<std::size_t>(dim_));
    for (int p = 0; p < dim_; ++p) {
      double value = start[p];
      if (!(value >= problem_.lower(p))) value = problem_.lower(p);   // below the box or NaN
      if (value > problem_.upper(p)) value = problem_.upper(p);
      u[static_cast<std::size_t>(p)] =
          on_lattice(p) ? static_cast<double>(problem_.lattice(p).nearest_index(value)) : value;
    }
    try_point(u);
  }

  // The grid coordinates of parameter p over its current window (lattice: distinct rounded indices).
  std::vector<double> axis(int p) const {
    const std::size_t i = static_cast<std::size_t>(p);
    const double lo = window_lo_[i], hi = window_hi_[i];
    std::vector<double> values;
    const std::int64_t count = options_.grid_points;
    for (std::int64_t j = 0; j < count; ++j) {
      // j = count - 1 lands exactly on hi (no rounding drift past the window).
      const double u = j == count - 1 ? hi : lo + (hi - lo) * (static_cast<double>(j) / static_cast<double>(count - 1));
      const double coordinate = on_lattice(p) ? std::round(u) : u;
      if (values.empty() || coordinate != values.back()) values.push_back(coordinate);   // drop duplicates
    }
    return values;
  }

  // Evaluates the full grid of the current windows; returns the grid spacing per parameter.
  std::vector<double> grid() {
    std::vector<std::vector<double>> axes;
    double tuples = 1.0;
    for (int p = 0; p < dim_; ++p) {
      axes.push_back(axis(p));
      tuples *= static_cast<double>(axes.back().size());
    }
    if (tuples > static_cast<double>(options_.max_grid_points))
      fail(kName, "a grid of " + std::to_string(options_.grid_points) + " points per parameter over " +
                      std::to_string(dim_) + " parameters has more than max_grid_points = " +
                      std::to_string(options_.max_grid_points) + " tuples");
    std::vector<std::size_t> position(static_cast<std::size_t>(dim_), 0);
    std::vector<double> u(static_cast<std::size_t>(dim_));
    for (;;) {
      for (int p = 0; p < dim_; ++p) u[static_cast<std::size_t>(p)] = axes[static_cast<std::size_t>(p)][position[static_cast<std::size_t>(p)]];
      try_point(u);
      if (time_limit_.was_reached()) break;
      int p = dim_ - 1;   // odometer, last parameter fastest
      for (; p >= 0; --p) {
        const std::size_t i = static_cast<std::size_t>(p);
        if (++position[i] < axes[i].size()) break;
        position[i] = 0;
      }
      if (p < 0) break;
    }
    std::vector<double> spacing(static_cast<std::size_t>(dim_));
    for (int p = 0; p < dim_; ++p) {
      const std::size_t i = static_cast<std::size_t>(p);
      spacing[i] = (window_hi_[i] - window_lo_[i]) / static_cast<double>(options_.grid_points - 1);
    }
    return spacing;
  }

  // Shrinks every window to the incumbent +- one spacing, inside the previous window.
  void zoom(const std::vector<double>& spacing) {
    for (int p = 0; p < dim_; ++p) {
      const std::size_t i = static_cast<std::size_t>(p);
      const double centre = best_coordinate_[i];
      double lo = centre - spacing[i], hi = centre + spacing[i];
      if (on_lattice(p)) {
        lo = std::floor(lo);   // whole indices, rounded outward so the zoom never loses a lattice point
        hi = std::ceil(hi);
      }
      window_lo_[i] = std::max(lo, window_lo_[i]);
      window_hi_[i] = std::min(hi, window_hi_[i]);
    }
  }

  // Coordinate hill climbing from the incumbent; returns true when it converged within the sweep budget.
  bool hill_climb(std::vector<double> step) {
    for (int p = 0; p < dim_; ++p) {
      const std::size_t i = static_cast<std::size_t>(p);
      if (on_lattice(p)) step[i] = std::max(1.0, std::round(step[i]));   // whole index steps, at least one
    }
    const auto domain_lo = [&](int p) { return on_lattice(p) ? 0.0 : problem_.lower(p); };
    const auto domain_hi = [&](int p) {
      return on_lattice(p) ? static_cast<double>(problem_.lattice(p).count - 1) : problem_.upper(p);
    };
    // The sweep polls the clock too: once the steps have shrunk to nothing (tolerance 0) a sweep evaluates nothing.
    for (std::int64_t sweep = 0; sweep < options_.hill_climb_steps && !time_limit_.reached(); ++sweep) {
      bool moved = false;
      for (int p = 0; p < dim_; ++p) {
        const std::size_t i = static_cast<std::size_t>(p);
        for (const double direction : {1.0, -1.0}) {
          std::vector<double> u = best_coordinate_;
          // Clamp to the domain; a clamped move that lands on the incumbent is not tried.
          u[i] = std::clamp(best_coordinate_[i] + direction * step[i], domain_lo(p), domain_hi(p));
          if (u[i] == best_coordinate_[i]) continue;
          if (try_point(u)) {
            moved = true;
            break;
          }
        }
      }
      if (moved || time_limit_.was_reached()) continue;
      bool converged = true;
      for (int p = 0; p < dim_; ++p) {
        const std::size_t i = static_cast<std::size_t>(p);
        if (on_lattice(p)) {
          if (step[i] > 1.0) converged = false;
          step[i] = std::max(1.0, std::floor(step[i] / 2.0));
        } else {
          const double width = problem_.upper(p) - problem_.lower(p);
          if (step[i] >= options_.tolerance * width && width > 0.0) converged = false;
          step[i] /= 2.0;
        }
      }
      if (converged) return true;
    }
    return false;
  }

  bool found() const { return found_; }
  double best_error() const { return best_error_; }
  const std::vector<double>& best_coordinate() const { return best_coordinate_; }

 private:
  const Problem& problem_;
  const CoeffSearchOptions& options_;
  Summary& summary_;
  TimeLimit& time_limit_;
  int dim_;
  std::vector<double> x_;
  std::vector<double> best_coordinate_;
  double best_error_ = std::numeric_limits<double>::quiet_NaN();
  bool found_ = false;
  std::vector<double> window_lo_, window_hi_;
};

}  // namespace

bool CoeffSearchOptions::is_valid(std::string* why) const { return coeff_search_option_table().is_valid(*this, why); }

CoeffSearchOptions CoeffSearchOptions::from_resolved(const SolverOptions& resolved) {
  return coeff_search_option_table().from_resolved(resolved);
}

SolveResult solve_coeff_search(const Problem& problem, const CoeffSearchOptions& options, const double* start,
                               std::uint64_t seed) {
  const auto started = std::chrono::steady_clock::now();
  require_valid_options(kName, options);
  const int dim = problem.dim();
  require_finite_box_or_lattice(kName, problem, "a grid needs a box");

  SolveResult result = begin_solve(kName, problem, start, seed);
  Summary& summary = result.summary;
  TimeLimit time_limit(started, options.time_limit);
  CoeffSearch search(problem, options, summary, time_limit);
  if (start != nullptr) search.seed_with_start(start);
  std::vector<double> spacing = search.grid();
  for (std::int64_t level = 0; level < options.refinement_levels && search.found() && !time_limit.was_reached();
       ++level) {
    search.zoom(spacing);
    spacing = search.grid();
  }
  const bool converged = search.found() && search.hill_climb(spacing);

  result.parameters.resize(static_cast<std::size_t>(dim));
  const std::vector<double>& best = search.best_coordinate();
  for (int p = 0; p < dim; ++p) result.parameters[static_cast<std::size_t>(p)] = search.value_of(p, best[static_cast<std::size_t>(p)]);
  if (problem.has_full_lattice()) {
    result.lattice_indices.resize(static_cast<std::size_t>(dim));
    for (int p = 0; p < dim; ++p)
      result.lattice_indices[static_cast<std::size_t>(p)] = static_cast<std::int64_t>(best[static_cast<std::size_t>(p)]);
  }
  if (!search.found()) {
    summary.termination = Termination::failed;
    summary.message = "the error was NaN at every evaluated point";
    if (time_limit.was_reached()) summary.message += " (" + time_limit.message() + ")";
  } else if (time_limit.was_reached()) {
    summary.final_error = search.best_error();
    summary.termination = Termination::max_seconds;
    summary.message = time_limit.message() + " after " + std::to_string(summary.evaluations) + " evaluations";
  } else {
    summary.final_error = search.best_error();
    summary.termination = converged ? Termination::converged : Termination::max_iterations;
    summary.message = std::to_string(options.refinement_levels + 1) + " grid levels of " +
                      std::to_string(options.grid_points) + " points per parameter, then hill climbing";
  }
  summary.seconds = seconds_since(started);
  return result;
}

const Solver& coeff_search_solver() {
  static const TypedSolver<CoeffSearchOptions> solver(kName, kDescription,
                                                      coeff_search_option_specs, solve_coeff_search);
  return solver;
}

}  // namespace blocklab
