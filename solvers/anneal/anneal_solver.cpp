// `anneal` solver (solvers/anneal/anneal_solver.h): simulated annealing (Kirkpatrick et al. 1983) with lattice
// moves, portable SplitMix64 randomness (solvers/seeding.h).
#include "solvers/anneal/anneal_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "core/error.h"
#include "solvers/seeding.h"

namespace blocklab {

namespace {

constexpr const char* kName = "anneal";

template <typename Enum, std::size_t N>
Enum enum_from_string(const char* what, const std::string& name, const Enum (&values)[N]) {
  std::vector<std::string> valid;
  for (Enum value : values) {
    if (to_string(value) == name) return value;
    valid.push_back(to_string(value));
  }
  fail(kName, "unknown " + std::string(what) + " '" + name + "'; valid: " + join_names(valid));
}

constexpr CoolingSchedule kSchedules[] = {CoolingSchedule::geometric, CoolingSchedule::linear,
                                          CoolingSchedule::exponential};
constexpr TemperatureScale kScales[] = {TemperatureScale::relative, TemperatureScale::absolute};
constexpr RestartPoint kRestartPoints[] = {RestartPoint::best, RestartPoint::random};


constexpr const char* kDescription =
    "simulated annealing (Kirkpatrick et al. 1983) on the box and the storage lattice, seeded restarts";

// Every option of AnnealOptions, declared once (core/options.h OptionTable): specs, is_valid and from_resolved.
const OptionTable<AnnealOptions>& anneal_option_table() {
  static const auto table = OptionTable<AnnealOptions>()
      .integer("iterations", &AnnealOptions::iterations, 1, 1000000000,
               "moves per run (at most 1e9, seconds to minutes of moves; time_limit bounds a run too)")
      .integer("restarts", &AnnealOptions::restarts, 0, 1000000000, "runs after the first")
      .real("initial_temperature", &AnnealOptions::initial_temperature, 0.0, DBL_MAX,
            "starting temperature T_0 (a fraction of the run's start error when temperature_scale=relative)")
      .choice("temperature_scale", &AnnealOptions::temperature_scale, named_choices(kScales),
              "relative: T_0 = initial_temperature * |start error|; absolute: T_0 = initial_temperature")
      .real("final_temperature_ratio", &AnnealOptions::final_temperature_ratio, 0.0, 1.0,
            "temperature of the last move over T_0", kLowerOpen)
      .choice("cooling", &AnnealOptions::cooling, named_choices(kSchedules), "cooling schedule")
      .real("step_size", &AnnealOptions::step_size, 0.0, 1.0,
            "initial move size as a fraction of the box width (continuous) or lattice length", kLowerOpen)
      .choice("restart_from", &AnnealOptions::restart_from, named_choices(kRestartPoints),
              "start point of each restart: the best point so far or a random point")
      .real("time_limit", &AnnealOptions::time_limit, 0.0, DBL_MAX, kTimeLimitHelp, kLowerOpen);
  return table;
}

std::vector<OptionSpec> anneal_option_specs() { return anneal_option_table().specs(); }

// The search state of one parameter: lattice index (lattice parameters) and value.
struct Point {
  std::vector<std::int64_t> index;
  std::vector<double> x;
};

class Annealer {
 public:
  Annealer(const Problem& problem, const AnnealOptions& options, std::uint64_t seed, Summary& summary,
           TimeLimit& time_limit)
      : problem_(problem), options_(options), random_(seed), summary_(summary), time_limit_(time_limit) {
    for (int p = 0; p < problem.dim(); ++p) {
      const Lattice& lattice = problem.lattice(p);
      const bool movable = lattice.present() ? lattice.count > 1 : problem.upper(p) > problem.lower(p);
      if (movable) movable_.push_back(p);
    }
  }

  // Clamps `values` into the box and moves lattice parameters to their nearest lattice point.
  Point snap(const double* values) const {
    Point point;
    const int dim = problem_.dim();
    point.index.assign(static_cast<std::size_t>(dim), 0);
    point.x.assign(static_cast<std::size_t>(dim), 0.0);
    for (int p = 0; p < dim; ++p) {
      const std::size_t i = static_cast<std::size_t>(p);
      const Lattice& lattice = problem_.lattice(p);
      // NaN start values (and values outside the box) are clamped; std::clamp would keep a NaN, so compare.
      double value = values[i];
      if (!(value >= problem_.lower(p))) value = problem_.lower(p);
      if (value > problem_.upper(p)) value = problem_.upper(p);
      if (lattice.present()) {
        point.index[i] = lattice.nearest_index(value);
        point.x[i] = lattice.point(point.index[i]);
      } else {
        point.x[i] = value;
      }
    }
    return point;
  }

  Point centre() const {
    std::vector<double> middle(static_cast<std::size_t>(problem_.dim()));
    for (int p = 0; p < problem_.dim(); ++p)
      middle[static_cast<std::size_t>(p)] = problem_.lower(p) + 0.5 * (problem_.upper(p) - problem_.lower(p));
    return snap(middle.data());
  }

  Point random_point() {
    Point point = centre();
    for (int p = 0; p < problem_.dim(); ++p) {
      const std::size_t i = static_cast<std::size_t>(p);
      const Lattice& lattice = problem_.lattice(p);
      if (lattice.present()) {
        point.index[i] = static_cast<std::int64_t>(random_.uniform_index(static_cast<std::uint64_t>(lattice.count)));
        point.x[i] = lattice.point(point.index[i]);
      } else {
        point.x[i] = std::min(random_.uniform(problem_.lower(p), problem_.upper(p)), problem_.upper(p));
      }
    }
    return point;
  }

  double evaluate(const Point& point) {
    ++summary_.evaluations;
    const double error = problem_.eval(point.x.data());
    // Keep the best valid point; strict comparison keeps the earliest of equal errors.
    if (!std::isnan(error) && (!found_ || error < best_error_)) {
      best_error_ = error;
      best_ = point;
      found_ = true;
    }
    return error;
  }

  // One annealing run of options.iterations moves from `current`.
  void run(Point current) {
    double current_error = evaluate(current);
    const double reference =
        (std::isfinite(current_error) && current_error != 0.0) ? std::abs(current_error) : 1.0;
    const double initial_temperature = options_.temperature_scale == TemperatureScale::relative
                                           ? options_.initial_temperature * reference
                                           : options_.initial_temperature;
    if (movable_.empty()) return;   // nothing can move: the start point is the only candidate
    const int movable_count = static_cast<int>(movable_.size());
    Point candidate = current;
    for (std::int64_t k = 0; k < options_.iterations && !time_limit_.reached(); ++k) {
      const double temperature = anneal_temperature(options_, initial_temperature, k, movable_count);
      // Step scale sqrt(T_k / T_0); a zero T_0 (absolute temperature 0: greedy descent) keeps full steps.
      const double step_scale = initial_temperature > 0.0 ? std::sqrt(temperature / initial_temperature) : 1.0;
      const int p = movable_[static_cast<std::size_t>(random_.uniform_index(movable_.size()))];
      const std::size_t i = static_cast<std::size_t>(p);
      const Lattice& lattice = problem_.lattice(p);
      if (lattice.present()) {
        const double sigma = options_.step_size * static_cast<double>(lattice.count - 1) * step_scale;
        // |N(0,1)| * sigma can exceed the lattice many times over; cap before the integer conversion.
        const double extra = std::min(std::floor(std::abs(random_.normal()) * sigma), static_cast<double>(lattice.count));
        const std::int64_t distance = 1 + static_cast<std::int64_t>(extra);
        const std::int64_t last = lattice.count - 1;
        std::int64_t index = current.index[i] + ((random_.next_word() >> 63) != 0 ? distance : -distance);
        if (index < 0) index = -index;                       // reflect at the first lattice point
        if (index > last) index = 2 * last - index;          // reflect at the last lattice point
        index = std::clamp<std::int64_t>(index, 0, last);    // a move longer than the lattice: clamp
        candidate.index[i] = index;
        candidate.x[i] = lattice.point(index);
      } else {
        const double lo = problem_.lower(p), hi = problem_.upper(p);
        double value = current.x[i] + random_.normal() * options_.step_size * (hi - lo) * step_scale;
        if (value < lo) value = lo + (lo - value);   // reflect at the lower bound
        if (value > hi) value = hi - (value - hi);   // reflect at the upper bound
        value = std::clamp(value, lo, hi);           // a step longer than the box: clamp
        candidate.x[i] = value;
      }
      const double candidate_error = evaluate(candidate);
      bool accept = false;
      if (std::isnan(candidate_error)) {
        accept = false;                                    // invalid point: never accepted
      } else if (std::isnan(current_error) || candidate_error <= current_error) {
        accept = true;                                     // downhill (or leaving an invalid point)
      } else if (temperature > 0.0) {
        // Metropolis; the uniform draw is taken only here so the stream does not depend on exp's rounding.
        accept = random_.uniform01() < std::exp(-(candidate_error - current_error) / temperature);
      }
      if (accept) {
        current.index[i] = candidate.index[i];
        current.x[i] = candidate.x[i];
        current_error = candidate_error;
        ++accepted_;
      } else {
        candidate.index[i] = current.index[i];
        candidate.x[i] = current.x[i];
      }
    }
  }

  bool found() const { return found_; }
  double best_error() const { return best_error_; }
  const Point& best() const { return best_; }
  std::uint64_t accepted() const { return accepted_; }

 private:
  const Problem& problem_;
  const AnnealOptions& options_;
  RandomStream random_;
  Summary& summary_;
  TimeLimit& time_limit_;
  std::vector<int> movable_;
  Point best_;
  double best_error_ = std::numeric_limits<double>::quiet_NaN();
  bool found_ = false;
  std::uint64_t accepted_ = 0;
};

}  // namespace

std::string to_string(CoolingSchedule schedule) {
  switch (schedule) {
    case CoolingSchedule::geometric: return "geometric";
    case CoolingSchedule::linear: return "linear";
    case CoolingSchedule::exponential: return "exponential";
  }
  fail(kName, "unknown cooling schedule value " + std::to_string(static_cast<int>(schedule)));
}
std::string to_string(TemperatureScale scale) {
  return scale == TemperatureScale::relative ? "relative" : "absolute";
}
std::string to_string(RestartPoint point) { return point == RestartPoint::best ? "best" : "random"; }

CoolingSchedule cooling_schedule_from_string(const std::string& name) {
  return enum_from_string("cooling schedule", name, kSchedules);
}
TemperatureScale temperature_scale_from_string(const std::string& name) {
  return enum_from_string("temperature scale", name, kScales);
}
RestartPoint restart_point_from_string(const std::string& name) {
  return enum_from_string("restart point", name, kRestartPoints);
}

bool AnnealOptions::is_valid(std::string* why) const { return anneal_option_table().is_valid(*this, why); }

AnnealOptions AnnealOptions::from_resolved(const SolverOptions& resolved) {
  return anneal_option_table().from_resolved(resolved);
}

double anneal_temperature(const AnnealOptions& options, double initial_temperature, std::int64_t k,
                          int movable_count) {
  // A one-move run has no schedule: it runs at T_0 (t = 0).
  if (options.iterations <= 1) return initial_temperature;
  const double last = static_cast<double>(options.iterations - 1);
  const double t = static_cast<double>(k) / last;
  const double ratio = options.final_temperature_ratio;
  switch (options.cooling) {
    case CoolingSchedule::geometric:
      return initial_temperature * std::pow(ratio, t);
    case CoolingSchedule::linear:
      return initial_temperature * (1.0 - t * (1.0 - ratio));
    case CoolingSchedule::exponential: {
      const double inverse_dim = 1.0 / static_cast<double>(std::max(movable_count, 1));
      const double rate = -std::log(ratio) / std::pow(last, inverse_dim);
      return initial_temperature * std::exp(-rate * std::pow(static_cast<double>(k), inverse_dim));
    }
  }
  return initial_temperature;
}

SolveResult solve_anneal(const Problem& problem, const AnnealOptions& options, const double* start,
                         std::uint64_t seed) {
  const auto started = std::chrono::steady_clock::now();
  require_valid_options(kName, options);
  require_finite_box_or_lattice(kName, problem, "continuous moves are scaled by the box width");

  SolveResult result = begin_solve(kName, problem, start, seed);
  Summary& summary = result.summary;
  TimeLimit time_limit(started, options.time_limit);
  Annealer annealer(problem, options, seed, summary, time_limit);
  Point first = start != nullptr ? annealer.snap(start) : annealer.centre();
  std::int64_t runs_started = 0;
  for (std::int64_t run = 0; run <= options.restarts && !time_limit.was_reached(); ++run, ++runs_started) {
    if (run == 0) {
      annealer.run(first);
    } else if (options.restart_from == RestartPoint::best && annealer.found()) {
      annealer.run(annealer.best());
    } else {
      annealer.run(annealer.random_point());   // random restart (or no valid point yet to restart from)
    }
  }

  std::string runs = std::to_string(options.restarts + 1) + " runs x " + std::to_string(options.iterations) +
                     " moves, " + std::to_string(annealer.accepted()) + " accepted";
  if (time_limit.was_reached())
    runs = time_limit.message() + " in run " + std::to_string(runs_started) + " of " + runs;
  if (annealer.found()) {
    const Point& best = annealer.best();
    result.parameters = best.x;
    if (problem.has_full_lattice()) result.lattice_indices = best.index;
    summary.final_error = annealer.best_error();
    summary.termination = time_limit.was_reached() ? Termination::max_seconds : Termination::max_iterations;
    summary.message = runs;
  } else {
    // No valid point anywhere: return the (snapped) first point rather than inventing one.
    result.parameters = first.x;
    if (problem.has_full_lattice()) result.lattice_indices = first.index;
    summary.termination = Termination::failed;
    summary.message = runs + "; the error was NaN at every evaluated point";
  }
  summary.seconds = seconds_since(started);
  return result;
}

const Solver& anneal_solver() {
  static const TypedSolver<AnnealOptions> solver(kName, kDescription, anneal_option_specs, solve_anneal);
  return solver;
}

}  // namespace blocklab
