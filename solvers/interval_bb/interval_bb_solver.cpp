// `interval_bb` solver (solvers/interval_bb/interval_bb_solver.h): best-first interval branch-and-bound on the
// storage lattice ("Practical HDR Texture Compression" (2008) section 7.1, "Simulated Annealing and Exhaustive Search";
// SPECS.md section 6).
#include "solvers/interval_bb/interval_bb_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>
#include <vector>

#include "core/error.h"

namespace blocklab {

namespace {

constexpr const char* kName = "interval_bb";

// Largest accepted leaf_points: 2^20 point evaluations per enumerated box.
constexpr long long kMaxLeafPoints = 1 << 20;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

constexpr const char* kDescription =
    "best-first interval branch-and-bound down to the storage lattice, certified optimal on the lattice "
    "(Practical HDR Texture Compression, sec. 7.1)";

// Every option of IntervalBbOptions, declared once (core/options.h OptionTable): specs, is_valid and from_resolved.
const OptionTable<IntervalBbOptions>& interval_bb_option_table() {
  static const auto table = OptionTable<IntervalBbOptions>()
      .integer("max_boxes", &IntervalBbOptions::max_boxes, 1, kMaxExactInteger,
               "interval evaluations before stopping with termination max_evaluations and the current gap")
      .real("time_limit", &IntervalBbOptions::time_limit, 0.0, DBL_MAX, kTimeLimitHelp, kLowerOpen)
      .real("relative_gap", &IntervalBbOptions::relative_gap, 0.0, 1.0,
            "prune boxes whose lower bound >= incumbent - relative_gap * |incumbent| (0 = exact)")
      .integer("leaf_points", &IntervalBbOptions::leaf_points, 1, kMaxLeafPoints,
               "boxes holding at most this many lattice points are enumerated point by point instead of "
               "bounded (1 = bound every box of two or more points)");
  return table;
}

std::vector<OptionSpec> interval_bb_option_specs() { return interval_bb_option_table().specs(); }

// A queued box: its lower bound, creation number (the tie-break) and slot in the index-range arena.
struct QueuedBox {
  double lower_bound;
  std::uint64_t order;
  std::size_t slot;
};
// std::priority_queue pops the "largest": order so that the smallest bound comes first and, among equal bounds,
// the NEWEST box (depth-first on ties). FIFO ties would expand all boxes of bound 0 of a zero-error problem level by
// level; LIFO dives to a lattice point, whose error then prunes them all.
struct PopsLater {
  bool operator()(const QueuedBox& a, const QueuedBox& b) const {
    if (a.lower_bound != b.lower_bound) return a.lower_bound > b.lower_bound;
    return a.order < b.order;
  }
};

// The search state. Index ranges of boxes live in one arena (2 * dim integers per box: lo_0, hi_0, lo_1, ...)
// with a free list, so the hot loop allocates only when the queue grows past its largest size so far.
class BranchAndBound {
 public:
  BranchAndBound(const Problem& problem, const IntervalBbOptions& options)
      : problem_(problem),
        options_(options),
        dim_(static_cast<std::size_t>(problem.dim())),
        point_(dim_),
        box_(dim_),
        index_(dim_),
        best_index_(dim_, 0),
        child_(2 * dim_) {}

  void offer_start(const double* start) {
    for (std::size_t p = 0; p < dim_; ++p) index_[p] = problem_.lattice(static_cast<int>(p)).nearest_index(start[p]);
    offer_point(index_);
  }

  Termination run(TimeLimit& time_limit) {
    for (std::size_t p = 0; p < dim_; ++p) {
      child_[2 * p] = 0;
      child_[2 * p + 1] = problem_.lattice(static_cast<int>(p)).count - 1;
    }
    consider_box(child_.data());
    while (!queue_.empty()) {
      const QueuedBox top = queue_.top();
      // Best-first: once the smallest queued bound reaches the threshold, every queued box is pruned.
      if (top.lower_bound >= prune_threshold()) {
        pruned_lower_bound_ = std::min(pruned_lower_bound_, top.lower_bound);
        return Termination::optimal;
      }
      if (interval_evaluations_ >= static_cast<std::uint64_t>(options_.max_boxes)) return Termination::max_evaluations;
      if (time_limit.reached()) return Termination::max_seconds;
      queue_.pop();
      // A small box that survived its bound: every lattice point is evaluated exactly, which costs less than
      // bounding its subtree and proves as much (no point of the box lies below the incumbent).
      const std::int64_t* ranges = arena_.data() + top.slot * 2 * dim_;
      if (lattice_point_count(ranges) <= static_cast<std::uint64_t>(options_.leaf_points)) {
        free_slots_.push_back(top.slot);
        enumerate(ranges);
      } else {
        split(top.slot);
      }
    }
    return Termination::optimal;
  }

  // Proven lower bound over the lattice: min of the incumbent, every pruned box and every box still queued.
  double lower_bound() const {
    double bound = std::min(pruned_lower_bound_, found_ ? best_error_ : kInfinity);
    if (!queue_.empty()) bound = std::min(bound, queue_.top().lower_bound);
    return bound;
  }

  bool found() const { return found_; }
  double best_error() const { return best_error_; }
  const std::vector<std::int64_t>& best_index() const { return best_index_; }
  std::uint64_t evaluations() const { return evaluations_; }
  std::uint64_t interval_evaluations() const { return interval_evaluations_; }
  std::size_t largest_queue() const { return largest_queue_; }
  std::uint64_t invalid_points() const { return invalid_points_; }

 private:
  double prune_threshold() const {
    // No valid point yet: nothing can be pruned.
    if (!found_) return kInfinity;
    return best_error_ - options_.relative_gap * std::abs(best_error_);
  }

  void offer_point(const std::vector<std::int64_t>& index) {
    for (std::size_t p = 0; p < dim_; ++p) point_[p] = problem_.lattice(static_cast<int>(p)).point(index[p]);
    // Only a strictly lower error replaces the incumbent, so the evaluation may stop once it cannot be lower.
    const double error = found_ ? problem_.eval_below(point_.data(), best_error_) : problem_.eval(point_.data());
    ++evaluations_;
    if (std::isnan(error)) {
      ++invalid_points_;   // an invalid point is never the answer
      return;
    }
    if (!found_ || error < best_error_) {
      best_error_ = error;
      best_index_ = index;
      found_ = true;
    }
  }

  // Evaluates a new box given as index ranges (lo_0, hi_0, lo_1, ...): a single lattice point exactly, otherwise
  // its centre point (incumbent) and its interval bound (queued unless pruned).
  void consider_box(const std::int64_t* ranges) {
    bool single_point = true;
    for (std::size_t p = 0; p < dim_; ++p) {
      const std::int64_t lo = ranges[2 * p], hi = ranges[2 * p + 1];
      if (lo != hi) single_point = false;
      index_[p] = lo + (hi - lo) / 2;
    }
    if (single_point) {
      offer_point(index_);   // the one lattice point of the box, evaluated exactly
      return;
    }
    offer_point(index_);
    for (std::size_t p = 0; p < dim_; ++p) {
      const Lattice& lattice = problem_.lattice(static_cast<int>(p));
      box_[p] = Interval(lattice.point(ranges[2 * p]), lattice.point(ranges[2 * p + 1]));
    }
    // Problem::eval_below: the full enclosure for every box that survives, a cheaper one for a box already
    // discarded by part of it (the same boxes are kept, with the same bounds).
    const Interval enclosure = problem_.eval_below(box_.data(), prune_threshold());
    ++interval_evaluations_;
    // A NaN lower bound carries no information (Problem already maps empty enclosures to the whole line).
    const double lower_bound = std::isnan(enclosure.lower()) ? -kInfinity : enclosure.lower();
    if (lower_bound >= prune_threshold()) {
      pruned_lower_bound_ = std::min(pruned_lower_bound_, lower_bound);
      return;
    }
    std::size_t slot;
    if (!free_slots_.empty()) {
      slot = free_slots_.back();
      free_slots_.pop_back();
    } else {
      slot = arena_.size() / (2 * dim_);
      arena_.resize(arena_.size() + 2 * dim_);
    }
    std::copy(ranges, ranges + 2 * dim_, arena_.begin() + static_cast<std::ptrdiff_t>(slot * 2 * dim_));
    queue_.push({lower_bound, next_order_++, slot});
    largest_queue_ = std::max(largest_queue_, queue_.size());
  }

  // Number of lattice points of a box (each span is at most the lattice count, so the product is capped before it
  // could overflow: any value above leaf_points only has to compare as larger).
  std::uint64_t lattice_point_count(const std::int64_t* ranges) const {
    std::uint64_t count = 1;
    for (std::size_t p = 0; p < dim_; ++p) {
      count *= static_cast<std::uint64_t>(ranges[2 * p + 1] - ranges[2 * p] + 1);
      if (count > static_cast<std::uint64_t>(kMaxLeafPoints)) return count;   // saturate: already above any limit
    }
    return count;
  }

  // Evaluates every lattice point of the box (odometer order, last parameter fastest).
  void enumerate(const std::int64_t* ranges) {
    for (std::size_t p = 0; p < dim_; ++p) index_[p] = ranges[2 * p];
    while (true) {
      offer_point(index_);
      std::size_t p = dim_;
      while (true) {
        if (p == 0) return;
        --p;
        if (++index_[p] <= ranges[2 * p + 1]) break;
        index_[p] = ranges[2 * p];   // carry into the next slower parameter
      }
    }
  }

  // Bisects the widest parameter (in lattice units; ties: the lowest parameter) of the box in `slot`.
  void split(std::size_t slot) {
    const std::int64_t* ranges = arena_.data() + slot * 2 * dim_;
    std::copy(ranges, ranges + 2 * dim_, child_.begin());
    free_slots_.push_back(slot);
    std::size_t widest = 0;
    std::int64_t widest_span = -1;
    for (std::size_t p = 0; p < dim_; ++p) {
      const std::int64_t span = child_[2 * p + 1] - child_[2 * p];
      if (span > widest_span) {
        widest_span = span;
        widest = p;
      }
    }
    const std::int64_t lo = child_[2 * widest], hi = child_[2 * widest + 1];
    const std::int64_t mid = lo + (hi - lo) / 2;
    child_[2 * widest + 1] = mid;   // lower half [lo, mid]
    consider_box(child_.data());
    child_[2 * widest] = mid + 1;   // upper half [mid + 1, hi]
    child_[2 * widest + 1] = hi;
    consider_box(child_.data());
  }

  const Problem& problem_;
  const IntervalBbOptions& options_;
  const std::size_t dim_;
  std::vector<double> point_;
  std::vector<Interval> box_;
  std::vector<std::int64_t> index_;
  std::vector<std::int64_t> best_index_;
  std::vector<std::int64_t> child_;
  std::vector<std::int64_t> arena_;
  std::vector<std::size_t> free_slots_;
  std::priority_queue<QueuedBox, std::vector<QueuedBox>, PopsLater> queue_;
  std::uint64_t next_order_ = 0;
  bool found_ = false;
  double best_error_ = kInfinity;
  double pruned_lower_bound_ = kInfinity;
  std::uint64_t evaluations_ = 0;
  std::uint64_t interval_evaluations_ = 0;
  std::uint64_t invalid_points_ = 0;
  std::size_t largest_queue_ = 0;
};

}  // namespace

bool IntervalBbOptions::is_valid(std::string* why) const { return interval_bb_option_table().is_valid(*this, why); }

IntervalBbOptions IntervalBbOptions::from_resolved(const SolverOptions& resolved) {
  return interval_bb_option_table().from_resolved(resolved);
}

SolveResult solve_interval_bb(const Problem& problem, const IntervalBbOptions& options, const double* start,
                              std::uint64_t seed) {
  const auto started = std::chrono::steady_clock::now();
  require_valid_options(kName, options);
  const int dim = problem.dim();
  require_full_lattice(kName, problem, "interval_bb certifies the optimum on the lattice");

  SolveResult result = begin_solve(kName, problem, start, seed);
  Summary& summary = result.summary;
  BranchAndBound search(problem, options);
  if (start != nullptr) search.offer_start(start);
  TimeLimit time_limit(started, options.time_limit);
  const Termination termination = search.run(time_limit);
  summary.evaluations += search.evaluations();
  summary.interval_evaluations = search.interval_evaluations();

  result.lattice_indices = search.best_index();
  result.parameters.resize(static_cast<std::size_t>(dim));
  for (int p = 0; p < dim; ++p)
    result.parameters[static_cast<std::size_t>(p)] =
        problem.lattice(p).point(result.lattice_indices[static_cast<std::size_t>(p)]);
  summary.message = std::to_string(search.interval_evaluations()) + " boxes bounded, largest queue " +
                    std::to_string(search.largest_queue());
  if (time_limit.was_reached()) summary.message = time_limit.message() + "; " + summary.message;
  if (search.invalid_points() > 0)
    summary.message += ", " + std::to_string(search.invalid_points()) + " points with a NaN error skipped";
  if (!search.found()) {
    // Every point met was invalid (or a budget stopped before any valid one).
    summary.termination = Termination::failed;
    summary.message += "; no lattice point with a valid error was found";
  } else {
    summary.termination = termination;
    summary.final_error = search.best_error();
    summary.lower_bound = search.lower_bound();
    // Finished with relative_gap = 0: every pruned bound is >= the incumbent, so lower bound = error, gap 0.
    summary.gap = summary.final_error - summary.lower_bound;
  }
  summary.seconds = seconds_since(started);
  return result;
}

const Solver& interval_bb_solver() {
  static const TypedSolver<IntervalBbOptions> solver(kName, kDescription,
                                                     interval_bb_option_specs, solve_interval_bb);
  return solver;
}

}  // namespace blocklab
