// Termination names, Summary::brief_report and solver option resolution (solvers/solver.h).
#include "solvers/solver.h"

#include <algorithm>
#include <cstdio>
#include <set>

#include "core/error.h"

namespace blocklab {

namespace {

struct TerminationName {
  Termination value;
  const char* name;
};

// The one table both directions of the string round trip read.
constexpr TerminationName kTerminationNames[] = {
    {Termination::optimal, "optimal"},
    {Termination::converged, "converged"},
    {Termination::max_evaluations, "max_evaluations"},
    {Termination::max_iterations, "max_iterations"},
    {Termination::max_seconds, "max_seconds"},
    {Termination::no_progress, "no_progress"},
    {Termination::failed, "failed"},
};

std::string short_number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

}  // namespace

std::string to_string(Termination termination) {
  for (const TerminationName& entry : kTerminationNames)
    if (entry.value == termination) return entry.name;
  fail("Termination", "unknown value " + std::to_string(static_cast<int>(termination)));
}

Termination termination_from_string(const std::string& name) {
  std::vector<std::string> valid;
  for (const TerminationName& entry : kTerminationNames) {
    if (name == entry.name) return entry.value;
    valid.push_back(entry.name);
  }
  throw Error("unknown termination '" + name + "'; valid terminations: " + join_names(valid));
}

const std::vector<Termination>& all_terminations() {
  static const std::vector<Termination> values = [] {
    std::vector<Termination> list;
    for (const TerminationName& entry : kTerminationNames) list.push_back(entry.value);
    return list;
  }();
  return values;
}

std::string Summary::brief_report() const {
  std::string report = (solver.empty() ? "solver" : solver) + ": " + to_string(termination) + ", error " +
                       short_number(initial_error) + " -> " + short_number(final_error);
  if (has_lower_bound())
    report += " (lower bound " + short_number(lower_bound) + ", gap " + short_number(gap) + ")";
  report += ", " + std::to_string(evaluations) + " evaluations";
  if (gradient_evaluations > 0) report += ", " + std::to_string(gradient_evaluations) + " gradient evaluations";
  if (interval_evaluations > 0) report += ", " + std::to_string(interval_evaluations) + " interval evaluations";
  report += ", " + short_number(seconds) + " s, seed " + std::to_string(seed);
  if (!message.empty()) report += "; " + message;
  return report;
}

// Unlike formats, solvers have no common `seed` option: a solver's seed is an argument of solve().
SolverOptions resolve_solver_options(const Solver& solver, const SolverOptions& given) {
  return resolve_options(solver.name(), solver.option_specs(), given);
}

void fail_invalid_options(const char* solver, const std::string& why) { fail(solver, why); }

void require_full_lattice(const char* solver, const Problem& problem, const char* purpose) {
  for (int p = 0; p < problem.dim(); ++p)
    if (!problem.lattice(p).present())
      fail(solver, "parameter " + std::to_string(p) + " has no storage lattice (" + purpose + ")");
}

void require_finite_box_or_lattice(const char* solver, const Problem& problem, const char* purpose) {
  for (int p = 0; p < problem.dim(); ++p)
    if (!problem.lattice(p).present() && !(std::isfinite(problem.lower(p)) && std::isfinite(problem.upper(p))))
      fail(solver, "parameter " + std::to_string(p) + " has no lattice and an infinite bound (" + purpose + ")");
}

SolveResult begin_solve(const char* solver, const Problem& problem, const double* start, std::uint64_t seed) {
  SolveResult result;
  result.summary.solver = solver;
  result.summary.seed = seed;
  if (start != nullptr) {
    result.summary.initial_error = problem.eval(start);
    ++result.summary.evaluations;
  }
  return result;
}

double seconds_since(std::chrono::steady_clock::time_point started) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

std::string TimeLimit::message() const { return "time limit of " + canonical_real_text(seconds_) + " s reached"; }

}  // namespace blocklab
