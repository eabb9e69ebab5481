// The Solver interface: a search over a type-erased Problem (core/problem.h) that returns parameters and a
// Summary (DESIGN.md "A solver takes a Problem and options and returns parameters plus a Summary").
//
// Modelled on Ceres: each solver has a typed options struct with `bool is_valid(std::string* why) const`, a
// Summary with a termination reason and `brief_report()`, and enums that round-trip through strings (an unknown
// name is an Error listing the valid ones). Options arrive as a string map, the same keys on the command line and
// in YAML, declared with the OptionSpec of formats/format.h and resolved with the same rules as format options
// (defaults filled in, values checked and written in one canonical spelling, unknown keys rejected).
//
// Solvers never include a format and never print; a Problem a solver cannot handle (e.g. `exhaustive` on a
// parameter without a lattice) is an Error naming the solver and the reason. Evaluation counts live in the
// Summary (a Problem is immutable and shared between threads).
#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/problem.h"
#include "core/options.h"   // OptionSpec, OptionType and the typed option accessors (option_int, ...)

namespace blocklab {

using SolverOptions = Options;

// Why a solve stopped.
enum class Termination {
  optimal,           // proven optimal: every candidate was examined, or the lower bound meets the incumbent
  converged,         // a local method met its convergence tolerance (not a proof of global optimality)
  max_evaluations,   // evaluation budget exhausted
  max_iterations,    // iteration budget exhausted
  max_seconds,       // time budget exhausted
  no_progress,       // stopped because further steps did not improve the error
  failed,            // no valid answer (e.g. the error was NaN everywhere); Summary::message says why
};

std::string to_string(Termination termination);
// Inverse of to_string; throws Error("unknown termination 'x'; valid terminations: optimal, ...").
Termination termination_from_string(const std::string& name);
const std::vector<Termination>& all_terminations();

struct Summary {
  std::string solver;                          // registry name of the solver that produced it
  Termination termination = Termination::failed;
  double initial_error = std::numeric_limits<double>::quiet_NaN();   // error at the start point; NaN without one
  double final_error = std::numeric_limits<double>::quiet_NaN();     // error at the returned parameters
  std::uint64_t evaluations = 0;               // point (double) error evaluations
  std::uint64_t gradient_evaluations = 0;      // error + gradient (Jet) evaluations
  std::uint64_t interval_evaluations = 0;      // interval enclosures over boxes
  double seconds = 0.0;                        // wall time of solve(); reported, never compared in tests
  std::uint64_t seed = 0;                      // the seed solve() was given
  // Proven lower bound of the error over the solver's search domain and gap = final_error - lower_bound (>= 0);
  // NaN when nothing is proven. The domain is the box for branch-and-bound and the lattice for `exhaustive`.
  double lower_bound = std::numeric_limits<double>::quiet_NaN();
  double gap = std::numeric_limits<double>::quiet_NaN();
  std::string message;                         // one line of detail; empty when there is nothing to add

  bool has_lower_bound() const { return !std::isnan(lower_bound); }
  // One line, e.g. "exhaustive: optimal, error 0.25 -> 0.0123 (lower bound 0.0123, gap 0), 4096 evaluations,
  // 0.0012 s, seed 7".
  std::string brief_report() const;
};

struct SolveResult {
  std::vector<double> parameters;              // dim() values inside the bounds
  // Lattice index of each parameter when the solver returns a lattice point (exhaustive, lattice searches), so a
  // format can pack the exact stored values; empty otherwise.
  std::vector<std::int64_t> lattice_indices;
  Summary summary;
};

class Solver {
 public:
  virtual ~Solver() = default;
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;   // one line, cites the paper / spec it implements
  // Must not declare the formats' common keys (common_option_specs(): `seed`), which solvers do not take.
  virtual std::vector<OptionSpec> option_specs() const = 0;

  // Solves `problem`. `options` may be given or already resolved (resolution is idempotent). `start` is
  // dim() values or null (no start: initial_error stays NaN). `seed` drives every random choice, so equal inputs
  // give equal results. Throws Error on invalid options or a problem the solver cannot handle.
  virtual SolveResult solve(const Problem& problem, const SolverOptions& options, const double* start,
                            std::uint64_t seed) const = 0;
};

// Fills defaults, validates every value against the solver's option_specs(), writes it in canonical form (the rules
// of resolve_format_options) and rejects unknown keys: "<solver>: unknown option 'x'; valid options: a, b".
// Unlike formats, solvers have no common `seed` option: the seed is an argument of solve().
SolverOptions resolve_solver_options(const Solver& solver, const SolverOptions& given);

// ---- Pieces every solver shares -------------------------------------------------------------------------------

// A Solver built from a typed options struct (with `bool is_valid(std::string*) const` and
// `static T from_resolved(const SolverOptions&)`), an option_specs() list and a typed solve function: solve()
// resolves the string options and hands the typed ones on. Every solver of the registry is one of these.
template <typename TypedOptions>
class TypedSolver final : public Solver {
 public:
  using SpecsFunction = std::vector<OptionSpec> (*)();
  using SolveFunction = SolveResult (*)(const Problem&, const TypedOptions&, const double*, std::uint64_t);

  TypedSolver(std::string name, std::string description, SpecsFunction specs, SolveFunction solve)
      : name_(std::move(name)), description_(std::move(description)), specs_(specs), solve_(solve) {}

  std::string name() const override { return name_; }
  std::string description() const override { return description_; }
  std::vector<OptionSpec> option_specs() const override { return specs_(); }
  SolveResult solve(const Problem& problem, const SolverOptions& options, const double* start,
                    std::uint64_t seed) const override {
    return solve_(problem, TypedOptions::from_resolved(resolve_solver_options(*this, options)), start, seed);
  }

 private:
  std::string name_, description_;
  SpecsFunction specs_;
  SolveFunction solve_;
};

// Throws Error("<solver>: <reason>") when the typed options are invalid.
[[noreturn]] void fail_invalid_options(const char* solver, const std::string& why);
template <typename TypedOptions>
void require_valid_options(const char* solver, const TypedOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) fail_invalid_options(solver, why);
}

// Throws Error("<solver>: parameter p has no storage lattice (<purpose>)") unless every parameter has a lattice.
void require_full_lattice(const char* solver, const Problem& problem, const char* purpose);
// Throws Error("<solver>: parameter p has no lattice and an infinite bound (<purpose>)") for such a parameter.
void require_finite_box_or_lattice(const char* solver, const Problem& problem, const char* purpose);

// The result every solve starts from: Summary::solver and seed set and, when `start` is given, initial_error
// evaluated there (one evaluation counted).
SolveResult begin_solve(const char* solver, const Problem& problem, const double* start, std::uint64_t seed);

// Seconds since `started` (for Summary::seconds).
double seconds_since(std::chrono::steady_clock::time_point started);

// Every solver's `time_limit` option: wall-time seconds per solve, finite and > 0. At the limit a solver stops and
// returns its best answer so far with Termination::max_seconds. The default is never reached by the default
// searches (they take milliseconds per block), so it leaves every result unchanged; a limit that is reached makes
// the result depend on the machine and its load.
constexpr double kDefaultTimeLimit = 10.0;
constexpr const char* kTimeLimitHelp =
    "wall-time limit of one solve in seconds; at the limit the best answer so far is returned (max_seconds)";

// The clock of one solve's time limit. reached() reads steady_clock only once every `poll_interval` calls (default
// 256: cheap enough for a solver's innermost loop; 1 for loops whose every step is expensive); once reached it stays
// reached.
class TimeLimit {
 public:
  static constexpr unsigned kPollInterval = 256;
  TimeLimit(std::chrono::steady_clock::time_point started, double seconds, unsigned poll_interval = kPollInterval)
      : started_(started), seconds_(seconds), poll_interval_(poll_interval) {}
  bool reached() {
    if (reached_) return true;
    if (++calls_ % poll_interval_ != 0) return false;
    reached_ = seconds_since(started_) >= seconds_;
    return reached_;
  }
  bool was_reached() const { return reached_; }
  // "time limit of 0.05 s reached" (for Summary::message).
  std::string message() const;

 private:
  std::chrono::steady_clock::time_point started_;
  double seconds_;
  unsigned poll_interval_;
  unsigned calls_ = 0;
  bool reached_ = false;
};

}  // namespace blocklab
