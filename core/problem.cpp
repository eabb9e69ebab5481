// Validation and lattice arithmetic of the type-erased Problem (core/problem.h, DESIGN.md "The one idea").
#include "core/problem.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"
#include "core/number_text.h"

namespace blocklab {

namespace {

std::string parameter_name(std::size_t index) { return "make_problem: parameter " + std::to_string(index); }


}  // namespace

Lattice Lattice::uniform(double first, double last, std::int64_t count) {
  if (count < 1) fail("Lattice::uniform", "count must be >= 1, got " + std::to_string(count));
  if (!std::isfinite(first) || !std::isfinite(last))
    fail("Lattice::uniform", "first and last must be finite, got " + exact_number_text(first) + " and " + exact_number_text(last));
  Lattice lattice;
  lattice.origin = first;
  lattice.count = count;
  // A single point has no spacing; step 0 keeps point(0) == first.
  lattice.step = count == 1 ? 0.0 : (last - first) / static_cast<double>(count - 1);
  if (count > 1 && !(lattice.step > 0.0))
    fail("Lattice::uniform", "last (" + exact_number_text(last) + ") must be above first (" + exact_number_text(first) + ")");
  return lattice;
}

Problem::Problem(int dim, Bounds bounds, std::vector<Lattice> lattices)
    : bounds_(std::move(bounds)), lattices_(std::move(lattices)) {
  const std::size_t n = static_cast<std::size_t>(dim);
  if (bounds_.lower.size() != n || bounds_.upper.size() != n)
    fail("make_problem", "the error has " + std::to_string(dim) + " parameters but the bounds give " +
                             std::to_string(bounds_.lower.size()) + " lower and " +
                             std::to_string(bounds_.upper.size()) + " upper values");
  // No lattice at all is spelled as an empty vector; expand it so lattice(i) is always valid.
  if (lattices_.empty()) lattices_.assign(n, Lattice::none());
  if (lattices_.size() != n)
    fail("make_problem", "the error has " + std::to_string(dim) + " parameters but " +
                             std::to_string(lattices_.size()) + " lattices were given (give none or one each)");
  for (std::size_t i = 0; i < n; ++i) {
    const double lo = bounds_.lower[i], hi = bounds_.upper[i];
    if (std::isnan(lo) || std::isnan(hi)) fail(parameter_name(i), "a bound is NaN");
    if (lo > hi) fail(parameter_name(i), "lower bound " + exact_number_text(lo) + " is above upper bound " + exact_number_text(hi));
    const Lattice& lattice = lattices_[i];
    if (lattice.count < 0) fail(parameter_name(i), "lattice count is negative");
    if (!lattice.present()) continue;   // continuous parameter
    if (!std::isfinite(lattice.origin)) fail(parameter_name(i), "lattice origin is not finite");
    if (lattice.count > 1 && !(std::isfinite(lattice.step) && lattice.step > 0.0))
      fail(parameter_name(i), "lattice step must be finite and > 0, got " + exact_number_text(lattice.step));
    const double first = lattice.point(0);
    const double last = lattice.point(lattice.count - 1);
    // Points computed as origin + k * step may land an ulp or two outside bounds computed as their end values;
    // 1e-9 of a step absorbs that without admitting a real point outside the box.
    const double slack = 1e-9 * lattice.step;
    if (!std::isfinite(last) || first < lo - slack || last > hi + slack)
      fail(parameter_name(i), "lattice points [" + exact_number_text(first) + ", " + exact_number_text(last) +
                                  "] are not inside the bounds [" + exact_number_text(lo) + ", " + exact_number_text(hi) + "]");
  }
}

bool Problem::has_full_lattice() const {
  for (const Lattice& lattice : lattices_)
    if (!lattice.present()) return false;
  return true;
}

std::uint64_t Problem::lattice_point_count() const {
  std::uint64_t total = 1;
  for (const Lattice& lattice : lattices_) {
    if (!lattice.present()) return 0;
    const std::uint64_t count = static_cast<std::uint64_t>(lattice.count);
    // Saturate instead of wrapping: callers compare against a maximum.
    if (total > std::numeric_limits<std::uint64_t>::max() / count) return std::numeric_limits<std::uint64_t>::max();
    total *= count;
  }
  return total;
}

void Problem::fail_no_residuals() {
  fail("Problem::eval_residuals", "this error functor declares no residuals (static constexpr int kResiduals)");
}

}  // namespace blocklab
