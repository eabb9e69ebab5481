// The Problem contract (core/problem.h), reusable by every test that builds a Problem (formats' block errors,
// paper problems): call `check_problem_contract(problem)` inside a TEST. It checks, with GoogleTest assertions,
//   (a) agreement: at random points the double error, the Jet value and the Interval error of the degenerate box
//       [x, x] agree (the interval contains the double value and is only rounding-wide);
//   (b) enclosure: on random sub-boxes of the bounds, the Interval error contains the double error at random
//       points and at the corners of the box (SPECS.md section 6: compare interval bounds with dense sampling);
//   (c) gradients: Jet gradients match central finite differences (Ceres' gradient-checker habit). For errors that
//       declare kSmooth every sampled point is checked; otherwise only points where the differences at two step
//       sizes agree (a kink of a min/clamp between the probes makes them disagree), and enough points must pass
//       that filter for the check to mean something;
//   (d) residuals (when the functor provides them): error == sum of squared residuals, the residuals are the same
//       with and without a Jacobian, and the Jacobian matches finite differences like (c);
//   (e) early exit: at the points of (a), eval_below(x, bound) is the error bit for bit for any bound above it, and
//       at least the bound for bounds at or below it; on the boxes of (b), eval_below(box, bound) encloses the
//       same point errors and is eval(box) bit for bit whenever its lower end is below the bound.
// Requires finite bounds. Deterministic for a given ContractOptions::seed.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/interval.h"
#include "core/problem.h"

namespace blocklab::contract {

struct ContractOptions {
  std::uint64_t seed = 20240611;
  int point_count = 200;        // random points for (a), (c), (d)
  int box_count = 200;          // random boxes for (b)
  int samples_per_box = 100;    // random points per box for (b), plus corners
  int max_corners = 64;         // all 2^dim corners when that many or fewer, otherwise this many random corners
  // Relative agreement of the Jet value with the double error: Jet arithmetic is not always the same sequence of
  // roundings (ceres divides as a * (1 / b)), so a few ulps of difference are legitimate.
  double jet_value_tolerance = 1e-12;
  // Width of the enclosure of a degenerate box [x, x], relative to |error| + error_scale: every operation widens by
  // 1 ulp (4 for exp/log), so a few hundred operations stay far below this.
  double degenerate_width_tolerance = 1e-9;
  // Absolute scale of the error, used as the floor of relative tolerances when the error is near 0.
  double error_scale = 1.0;
  // Jet gradient vs central differences, relative to max(|difference|, max_i |gradient_i|) (step cbrt(eps)|x|
  // gives truncation and cancellation errors around 1e-10 relative for well-scaled errors; 1e-5 leaves room for
  // curvature).
  double gradient_tolerance = 1e-5;
  // Non-smooth errors: fraction of points whose two finite differences must agree for (c) to count as tested.
  double min_checked_gradient_fraction = 0.5;
  // Failures reported per check before the rest are counted silently (keeps a broken problem's output readable).
  int max_reported_failures = 5;
};

namespace contract_detail {

inline std::string point_text(const std::vector<double>& x) {
  std::string text = "(";
  char buffer[40];
  for (std::size_t i = 0; i < x.size(); ++i) {
    std::snprintf(buffer, sizeof buffer, "%.17g", x[i]);
    text += (i ? ", " : "") + std::string(buffer);
  }
  return text + ")";
}

inline std::string box_text(const std::vector<Interval>& box) {
  std::string text = "{";
  for (std::size_t i = 0; i < box.size(); ++i) text += (i ? ", " : "") + to_string(box[i]);
  return text + "}";
}

class FailureBudget {
 public:
  FailureBudget(const char* check, int limit) : check_(check), limit_(limit) {}
  ~FailureBudget() {
    if (count_ > limit_) ADD_FAILURE() << check_ << ": " << count_ - limit_ << " further failures not shown";
  }
  // True when this failure should be printed.
  bool report() { return ++count_ <= limit_; }

 private:
  const char* check_;
  int limit_;
  int count_ = 0;
};

// Central difference of f along `parameter` with step h (the step actually taken is recomputed from the
// perturbed points so representation error of x +- h does not bias it).
template <typename F>
double central_difference(const F& f, std::vector<double> x, int parameter, double h) {
  const std::size_t p = static_cast<std::size_t>(parameter);
  const double center = x[p];
  const double forward = center + h, backward = center - h;
  x[p] = forward;
  const double f_forward = f(x);
  x[p] = backward;
  const double f_backward = f(x);
  return (f_forward - f_backward) / (forward - backward);
}

// Finite-difference check of one derivative `analytic` of `f` at x; returns false only on a real mismatch.
// `checked` is set when the point was usable (always for smooth functions; for non-smooth ones only when the
// differences at steps h and h/2 agree).
template <typename F>
bool derivative_matches(const F& f, const std::vector<double>& x, int parameter, double analytic, double f_value,
                        double gradient_scale, bool smooth, const ContractOptions& options, bool* checked,
                        double* difference_out) {
  const double eps = std::numeric_limits<double>::epsilon();
  const double h = std::cbrt(eps) * std::max(1.0, std::abs(x[static_cast<std::size_t>(parameter)]));
  const double difference = central_difference(f, x, parameter, h);
  *difference_out = difference;
  // Cancellation error of a central difference: about eps |f| / h; allow a generous multiple of it.
  const double roundoff = 64.0 * eps * (std::abs(f_value) + options.error_scale * eps) / h;
  const double scale = std::max({std::abs(difference), gradient_scale, std::numeric_limits<double>::min()});
  const double allowed = options.gradient_tolerance * scale + roundoff;
  if (!smooth) {
    const double half_step = central_difference(f, x, parameter, h / 2);
    if (std::abs(difference - half_step) > allowed) {
      *checked = false;   // a kink between the probes: the finite difference means nothing here
      return true;
    }
  }
  *checked = true;
  return std::abs(analytic - difference) <= allowed;
}

}  // namespace contract_detail

inline void check_problem_contract(const Problem& problem, const ContractOptions& options = {}) {
  using contract_detail::point_text;
  const int dim = problem.dim();
  const std::size_t n = static_cast<std::size_t>(dim);
  for (int i = 0; i < dim; ++i) {
    ASSERT_TRUE(std::isfinite(problem.lower(i)) && std::isfinite(problem.upper(i)))
        << "the contract samples the bounds, so they must be finite (parameter " << i << ")";
  }
  std::mt19937_64 random(options.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto random_in = [&](double lo, double hi) { return lo + (hi - lo) * unit(random); };
  const auto random_point = [&](double margin_steps) {
    std::vector<double> x(n);
    for (int i = 0; i < dim; ++i) {
      // Keep finite-difference probes inside the bounds: margin of a few steps when the range allows it.
      const double margin = margin_steps * std::cbrt(std::numeric_limits<double>::epsilon()) *
                            std::max({1.0, std::abs(problem.lower(i)), std::abs(problem.upper(i))});
      double lo = problem.lower(i), hi = problem.upper(i);
      if (hi - lo > 4 * margin) { lo += margin; hi -= margin; }
      x[static_cast<std::size_t>(i)] = random_in(lo, hi);
    }
    return x;
  };
  const auto error_at = [&](const std::vector<double>& x) { return problem.eval(x.data()); };

  // (a) double, Jet value and degenerate-interval evaluations agree.
  {
    contract_detail::FailureBudget failures("(a) agreement", options.max_reported_failures);
    std::vector<double> gradient(n);
    std::vector<Interval> box(n);
    for (int k = 0; k < options.point_count; ++k) {
      const std::vector<double> x = random_point(0.0);
      const double value = error_at(x);
      if (std::isnan(value)) continue;   // invalid point: nothing to agree on
      const double jet_value = problem.eval_with_gradient(x.data(), gradient.data());
      const double magnitude = std::abs(value) + options.error_scale;
      if (!(std::abs(jet_value - value) <= options.jet_value_tolerance * magnitude) && failures.report())
        ADD_FAILURE() << "Jet value " << jet_value << " differs from double error " << value << " at "
                      << point_text(x);
      // (e) eval_below: exact above the error, at least the bound at or below it.
      const double above = std::nextafter(value, std::numeric_limits<double>::infinity());
      for (const double bound : {std::numeric_limits<double>::infinity(), above})
        if (!(problem.eval_below(x.data(), bound) == value) && failures.report())
          ADD_FAILURE() << "eval_below(x, " << bound << ") = " << problem.eval_below(x.data(), bound)
                        << " differs from the error " << value << " at " << point_text(x);
      for (const double bound : {value, value - 0.5 * std::abs(value), value - std::abs(value)})
        if (!(problem.eval_below(x.data(), bound) >= bound) && failures.report())
          ADD_FAILURE() << "eval_below(x, " << bound << ") = " << problem.eval_below(x.data(), bound)
                        << " is below its bound at " << point_text(x) << " (the error is " << value << ")";
      for (std::size_t i = 0; i < n; ++i) box[i] = Interval(x[i]);
      const Interval enclosure = problem.eval(box.data());
      if (!contains(enclosure, value) && failures.report())
        ADD_FAILURE() << "degenerate-box error " << to_string(enclosure) << " does not contain double error "
                      << value << " at " << point_text(x);
      else if (!(width(enclosure) <= options.degenerate_width_tolerance * magnitude) && failures.report())
        ADD_FAILURE() << "degenerate-box error " << to_string(enclosure) << " is wider than "
                      << options.degenerate_width_tolerance << " x " << magnitude << " at " << point_text(x);
    }
  }

  // (b) the interval error encloses the double error over random boxes.
  {
    contract_detail::FailureBudget failures("(b) enclosure", options.max_reported_failures);
    std::vector<Interval> box(n);
    std::vector<double> x(n);
    const bool all_corners = dim < 31 && (std::uint64_t{1} << dim) <= static_cast<std::uint64_t>(options.max_corners);
    const int corner_count = all_corners ? (1 << dim) : options.max_corners;
    for (int b = 0; b < options.box_count; ++b) {
      for (int i = 0; i < dim; ++i) {
        double lo = random_in(problem.lower(i), problem.upper(i));
        double hi = random_in(problem.lower(i), problem.upper(i));
        if (hi < lo) std::swap(lo, hi);
        if (unit(random) < 0.1) hi = lo;   // some degenerate sides, as bisection produces near the end
        box[static_cast<std::size_t>(i)] = Interval(lo, hi);
      }
      const Interval enclosure = problem.eval(box.data());
      // eval_below(box, bound): for bounds above, at and below the enclosure's lower end (down to -inf, where any
      // enclosure may be returned), the result is eval(box) bit for bit whenever its lower end is below the bound,
      // and it encloses the same point errors as eval(box) (checked with them below).
      const double low = enclosure.lower();
      const std::array<double, 6> bounds = {std::numeric_limits<double>::infinity(),
                                            std::nextafter(low, std::numeric_limits<double>::infinity()),
                                            low, 0.5 * low, 0.0, -std::numeric_limits<double>::infinity()};
      std::array<Interval, bounds.size()> below;
      for (std::size_t k = 0; k < bounds.size(); ++k) {
        below[k] = problem.eval_below(box.data(), bounds[k]);
        const bool same = below[k].lower() == enclosure.lower() && below[k].upper() == enclosure.upper();
        if (below[k].lower() < bounds[k] && !same && failures.report())
          ADD_FAILURE() << "eval_below(box, " << bounds[k] << ") = " << to_string(below[k])
                        << " is below its bound but differs from the box error " << to_string(enclosure)
                        << " of box " << contract_detail::box_text(box);
      }
      const auto check_point = [&](const char* kind) {
        const double value = error_at(x);
        if (std::isnan(value)) return;   // invalid points are not constrained by the enclosure
        if (!contains(enclosure, value) && failures.report())
          ADD_FAILURE() << kind << " error " << value << " at " << point_text(x) << " is outside the box error "
                        << to_string(enclosure) << " of box " << contract_detail::box_text(box);
        for (std::size_t k = 0; k < bounds.size(); ++k)
          if (!contains(below[k], value) && failures.report())
            ADD_FAILURE() << kind << " error " << value << " at " << point_text(x) << " is outside eval_below(box, "
                          << bounds[k] << ") = " << to_string(below[k]) << " of box "
                          << contract_detail::box_text(box);
      };
      for (int c = 0; c < corner_count; ++c) {
        for (int i = 0; i < dim; ++i) {
          const bool upper_side = all_corners ? ((c >> i) & 1) != 0 : unit(random) < 0.5;
          const Interval& side = box[static_cast<std::size_t>(i)];
          x[static_cast<std::size_t>(i)] = upper_side ? side.upper() : side.lower();
        }
        check_point("corner");
      }
      for (int s = 0; s < options.samples_per_box; ++s) {
        for (int i = 0; i < dim; ++i) {
          const Interval& side = box[static_cast<std::size_t>(i)];
          x[static_cast<std::size_t>(i)] = random_in(side.lower(), side.upper());
        }
        check_point("sample");
      }
    }
  }

  // (c) Jet gradients match central finite differences.
  {
    contract_detail::FailureBudget failures("(c) gradient", options.max_reported_failures);
    std::vector<double> gradient(n);
    int usable = 0, tried = 0;
    for (int k = 0; k < options.point_count; ++k) {
      const std::vector<double> x = random_point(4.0);
      const double value = problem.eval_with_gradient(x.data(), gradient.data());
      if (!std::isfinite(value)) continue;
      double gradient_scale = 0.0;
      for (double g : gradient) gradient_scale = std::max(gradient_scale, std::abs(g));
      bool point_usable = true;
      for (int p = 0; p < dim; ++p) {
        bool checked = false;
        double difference = 0.0;
        const bool ok = contract_detail::derivative_matches(error_at, x, p, gradient[static_cast<std::size_t>(p)],
                                                            value, gradient_scale, problem.is_smooth(), options,
                                                            &checked, &difference);
        point_usable = point_usable && checked;
        if (!ok && failures.report())
          ADD_FAILURE() << "d error / d x" << p << ": Jet " << gradient[static_cast<std::size_t>(p)]
                        << ", central difference " << difference << " at " << point_text(x);
      }
      ++tried;
      if (point_usable) ++usable;
    }
    if (!problem.is_smooth()) {
      EXPECT_GE(usable, static_cast<int>(options.min_checked_gradient_fraction * tried))
          << "too few points where finite differences are stable: the gradient check would be vacuous";
    }
  }

  // (d) least-squares form: residuals, Jacobian and their consistency with the error.
  const int residual_count = problem.residual_count();
  if (residual_count > 0) {
    contract_detail::FailureBudget failures("(d) residuals", options.max_reported_failures);
    const std::size_t m = static_cast<std::size_t>(residual_count);
    std::vector<double> residuals(m), residuals_with_jacobian(m), jacobian(m * n);
    for (int k = 0; k < options.point_count; ++k) {
      const std::vector<double> x = random_point(4.0);
      problem.eval_residuals(x.data(), residuals.data(), nullptr);
      problem.eval_residuals(x.data(), residuals_with_jacobian.data(), jacobian.data());
      double sum_of_squares = 0.0;
      for (std::size_t r = 0; r < m; ++r) {
        sum_of_squares += residuals[r] * residuals[r];
        const double magnitude = std::abs(residuals[r]) + options.error_scale;
        if (!(std::abs(residuals[r] - residuals_with_jacobian[r]) <= options.jet_value_tolerance * magnitude) &&
            failures.report())
          ADD_FAILURE() << "residual " << r << " is " << residuals[r] << " without and "
                        << residuals_with_jacobian[r] << " with a Jacobian at " << point_text(x);
      }
      const double value = error_at(x);
      if (!(std::abs(sum_of_squares - value) <= options.jet_value_tolerance * (std::abs(value) + options.error_scale)) &&
          failures.report())
        ADD_FAILURE() << "error " << value << " is not the sum of squared residuals " << sum_of_squares << " at "
                      << point_text(x);
      for (std::size_t r = 0; r < m; ++r) {
        const auto residual_at = [&](const std::vector<double>& point) {
          std::vector<double> all(m);
          problem.eval_residuals(point.data(), all.data(), nullptr);
          return all[r];
        };
        double row_scale = 0.0;
        for (std::size_t p = 0; p < n; ++p) row_scale = std::max(row_scale, std::abs(jacobian[r * n + p]));
        for (int p = 0; p < dim; ++p) {
          bool checked = false;
          double difference = 0.0;
          const double analytic = jacobian[r * n + static_cast<std::size_t>(p)];
          if (!contract_detail::derivative_matches(residual_at, x, p, analytic, residuals[r], row_scale,
                                                   problem.is_smooth(), options, &checked, &difference) &&
              failures.report())
            ADD_FAILURE() << "d residual" << r << " / d x" << p << ": Jet " << analytic << ", central difference "
                          << difference << " at " << point_text(x);
        }
      }
    }
  }
}

}  // namespace blocklab::contract
