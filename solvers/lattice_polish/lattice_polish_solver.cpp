// `lattice_polish` solver (solvers/lattice_polish/lattice_polish_solver.h): snap to the storage lattice and
// search a radius of quantised values ("Practical HDR Texture Compression" (2008) section 7.1, last paragraph before
// "Procrustes Analysis and Clustering").
#include "solvers/lattice_polish/lattice_polish_solver.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "core/error.h"

namespace blocklab {

namespace {

constexpr const char* kName = "lattice_polish";

constexpr const char* kDescription =
    "snap to the storage lattice, then search +-radius quantised values around it (Practical HDR Texture "
    "Compression, sec. 7.1)";

// Every option of LatticePolishOptions, declared once (core/options.h OptionTable): specs, is_valid and from_resolved.
const OptionTable<LatticePolishOptions>& lattice_polish_option_table() {
  static const auto table = OptionTable<LatticePolishOptions>()
      .integer("radius", &LatticePolishOptions::radius, 1, 1 << 20,
               "lattice steps searched per parameter (1: all 3^dim neighbours; more: coordinate descent)")
      .integer("max_passes", &LatticePolishOptions::max_passes, 1, 1 << 20,
               "repeat the search around each new best point at most this many times")
      .integer("full_neighbourhood_limit", &LatticePolishOptions::full_neighbourhood_limit, 1, kMaxExactInteger,
               "largest 3^dim enumerated in full at radius 1 (above: coordinate descent)")
      .real("time_limit", &LatticePolishOptions::time_limit, 0.0, DBL_MAX, kTimeLimitHelp, kLowerOpen);
  return table;
}

std::vector<OptionSpec> lattice_polish_option_specs() { return lattice_polish_option_table().specs(); }

// The search state: the incumbent lattice point, its error and the evaluation count.
class Incumbent {
 public:
  Incumbent(const Problem& problem, std::vector<std::int64_t> index, TimeLimit& time_limit)
      : problem_(problem), time_limit_(time_limit), index_(std::move(index)), x_(index_.size()) {
    error_ = evaluate(index_);
    found_ = !std::isnan(error_);
  }

  // Evaluates the lattice point `index`; replaces the incumbent when its error is strictly lower (or the
  // incumbent is invalid). Returns true on replacement. Past the time limit nothing more is evaluated.
  bool offer(const std::vector<std::int64_t>& index) {
    if (time_limit_.reached()) return false;
    // Only a strictly lower error replaces a valid incumbent, so the evaluation may stop once it cannot be lower.
    const double error = evaluate(index, found_ ? error_ : std::numeric_limits<double>::infinity());
    if (std::isnan(error)) return false;   // invalid point: never the answer
    if (found_ && !(error < error_)) return false;
    error_ = error;
    index_ = index;
    found_ = true;
    return true;
  }

  const std::vector<std::int64_t>& index() const { return index_; }
  double error() const { return error_; }
  bool found() const { return found_; }
  std::uint64_t evaluations() const { return evaluations_; }

 private:
  // The error at lattice point `index` when below `bound` (Problem::eval_below), else a value >= bound.
  double evaluate(const std::vector<std::int64_t>& index, double bound = std::numeric_limits<double>::infinity()) {
    for (std::size_t p = 0; p < index.size(); ++p) x_[p] = problem_.lattice(static_cast<int>(p)).point(index[p]);
    ++evaluations_;
    return bound < std::numeric_limits<double>::infinity() ? problem_.eval_below(x_.data(), bound)
                                                           : problem_.eval(x_.data());
  }

  const Problem& problem_;
  TimeLimit& time_limit_;
  std::vector<std::int64_t> index_;
  std::vector<double> x_;
  double error_ = 0.0;
  bool found_ = false;
  std::uint64_t evaluations_ = 0;
};

// One pass over all 3^dim neighbours of `centre` (offsets -1, 0, +1 per parameter, last parameter fastest).
// `previous_centre` (empty on the first pass) is the centre of the pass before, which moved the centre here. Every
// point within one step of it was evaluated in that pass, and that pass ended with the strictly best of them as
// the incumbent, so none of them can be strictly better than the incumbent now (it only decreases): they are
// skipped, which changes the evaluation count but never the answer.
bool full_neighbourhood_pass(const Problem& problem, const std::vector<std::int64_t>& previous_centre,
                             Incumbent& incumbent) {
  const std::vector<std::int64_t> centre = incumbent.index();
  const std::size_t dim = centre.size();
  std::vector<int> offset(dim, -1);
  std::vector<std::int64_t> index(dim);
  bool improved = false;
  while (true) {
    bool inside = true, is_centre = true, searched_before = !previous_centre.empty();
    for (std::size_t p = 0; p < dim; ++p) {
      index[p] = centre[p] + offset[p];
      // Clipped at the lattice ends.
      if (index[p] < 0 || index[p] >= problem.lattice(static_cast<int>(p)).count) inside = false;
      if (offset[p] != 0) is_centre = false;
      if (searched_before && (index[p] < previous_centre[p] - 1 || index[p] > previous_centre[p] + 1))
        searched_before = false;
    }
    if (inside && !is_centre && !searched_before && incumbent.offer(index)) improved = true;
    std::size_t p = dim;
    while (p > 0) {
      --p;
      if (++offset[p] <= 1) break;
      offset[p] = -1;   // carry into the next slower parameter
      if (p == 0) return improved;
    }
  }
}

// One pass of coordinate-wise descent: each parameter in turn tries every index within +-radius of the current.
bool coordinate_descent_pass(const Problem& problem, int radius, Incumbent& incumbent) {
  bool improved = false;
  const std::size_t dim = incumbent.index().size();
  for (std::size_t p = 0; p < dim; ++p) {
    const std::vector<std::int64_t> centre = incumbent.index();
    std::vector<std::int64_t> index = centre;
    const std::int64_t count = problem.lattice(static_cast<int>(p)).count;
    for (std::int64_t offset = -radius; offset <= radius; ++offset) {
      index[p] = centre[p] + offset;
      if (offset == 0 || index[p] < 0 || index[p] >= count) continue;   // the centre is known; clip at the ends
      if (incumbent.offer(index)) improved = true;
    }
  }
  return improved;
}

}  // namespace

bool LatticePolishOptions::is_valid(std::string* why) const { return lattice_polish_option_table().is_valid(*this, why); }

LatticePolishOptions LatticePolishOptions::from_resolved(const SolverOptions& resolved) {
  return lattice_polish_option_table().from_resolved(resolved);
}

SolveResult solve_lattice_polish(const Problem& problem, const LatticePolishOptions& options, const double* start,
                                 std::uint64_t seed) {
  const auto started = std::chrono::steady_clock::now();
  require_valid_options(kName, options);
  const int dim = problem.dim();
  require_full_lattice(kName, problem, "lattice_polish searches lattice points");

  SolveResult result = begin_solve(kName, problem, start, seed);
  Summary& summary = result.summary;
  std::vector<std::int64_t> snapped(static_cast<std::size_t>(dim));
  for (int p = 0; p < dim; ++p) {
    const Lattice& lattice = problem.lattice(p);
    // No start: the middle of the lattice stands in (documented in the header).
    snapped[static_cast<std::size_t>(p)] = start != nullptr ? lattice.nearest_index(start[p]) : (lattice.count - 1) / 2;
  }

  // 3^dim, saturating above the limit.
  std::int64_t neighbourhood = 1;
  for (int p = 0; p < dim && neighbourhood <= options.full_neighbourhood_limit; ++p) neighbourhood *= 3;
  const bool full = options.radius == 1 && neighbourhood <= options.full_neighbourhood_limit;

  TimeLimit time_limit(started, options.time_limit);
  Incumbent incumbent(problem, snapped, time_limit);
  const double snapped_error = incumbent.error();
  int passes = 0;
  bool improved = true;
  std::vector<std::int64_t> previous_centre;   // the full search's centre of the pass before (none before pass 1)
  while (improved && passes < options.max_passes && !time_limit.was_reached()) {
    if (full) {
      const std::vector<std::int64_t> centre = incumbent.index();
      improved = full_neighbourhood_pass(problem, previous_centre, incumbent);
      previous_centre = centre;
    } else {
      improved = coordinate_descent_pass(problem, options.radius, incumbent);
    }
    ++passes;
  }
  summary.evaluations += incumbent.evaluations();

  result.lattice_indices = incumbent.index();
  result.parameters.resize(static_cast<std::size_t>(dim));
  for (int p = 0; p < dim; ++p)
    result.parameters[static_cast<std::size_t>(p)] = problem.lattice(p).point(result.lattice_indices[static_cast<std::size_t>(p)]);
  char snapped_text[64];
  std::snprintf(snapped_text, sizeof snapped_text, "%.6g", snapped_error);
  summary.message = std::string(start != nullptr ? "snapped start" : "no start: lattice middle") + " error " +
                    snapped_text + ", " + std::to_string(passes) + (passes == 1 ? " pass" : " passes") + " of " +
                    (full ? "full 3^" + std::to_string(dim) + " neighbourhood"
                          : "coordinate descent, radius " + std::to_string(options.radius));
  if (time_limit.was_reached()) summary.message = time_limit.message() + " in " + summary.message;
  if (!incumbent.found()) {
    summary.termination = Termination::failed;
    summary.message += "; the error was NaN at every point searched";
  } else {
    summary.final_error = incumbent.error();
    // The last pass found nothing better: a local minimum for this neighbourhood. Otherwise the pass budget ran out.
    summary.termination = time_limit.was_reached() ? Termination::max_seconds
                          : improved                ? Termination::max_iterations
                                                    : Termination::converged;
  }
  summary.seconds = seconds_since(started);
  return result;
}

const Solver& lattice_polish_solver() {
  static const TypedSolver<LatticePolishOptions> solver(kName, kDescription,
                                                        lattice_polish_option_specs, solve_lattice_polish);
  return solver;
}

}  // namespace blocklab
