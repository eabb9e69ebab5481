// The type-erased search Problem (DESIGN.md "The one idea").
//
// Every search in blocklab, per block or per image, is a Problem: `dim()` real parameters, a box of bounds, an
// optional storage lattice per parameter (the quantisation the parameters end up on), and ONE error written once as
// a template on the scalar type:
//
//     struct MyError {
//       static constexpr int kDim = 2;                         // number of parameters (also the Jet size)
//       static constexpr bool kSmooth = true;                  // optional (default false): error is C^1 in x
//       static constexpr int kResiduals = 8;                   // optional: least-squares form is available
//       template <typename T> T operator()(const T* x) const;  // the error
//       template <typename T> void residuals(const T* x, T* r) const;   // optional, with kResiduals
//       double eval_below(const double* x, double bound) const;   // optional: early exit (Problem::eval_below)
//       Interval eval_below(const Interval* box, double bound) const;   // optional: the same for enclosures
//     };
//     const auto problem = make_problem(MyError{...}, Bounds{{0, 0}, {1, 1}}, {Lattice::uniform(0, 1, 256), ...});
//     solver.solve(problem, options, start, seed);           // solvers see only `const Problem&`
//
// The same functor is evaluated as double (point error), as blocklab::Interval (an enclosure of the error over a
// box, for branch-and-bound), as ceres::Jet<double, kDim> (value and exact gradient), and, when it declares them,
// its residuals as double and Jet (residuals and Jacobian for Levenberg-Marquardt). Rules for the functor: see
// core/scalar.h (no `if` on T comparisons; select/min/max/clamp/abs/square), wrap constants as T(k), use
// square(x) not x * x, and no log/sqrt/1/x at exactly 0 (named floors instead).
//
// Contracts the adapter relies on (tests/contract/problem_contract.h checks them for any Problem):
//   * the three evaluations agree: the Jet value equals the double error up to rounding, and the Interval error
//     over a box contains the double error at every point of the box;
//   * with residuals, error(x) == sum_i residual_i(x)^2 (up to rounding);
//   * eval_below(x, bound) is the double error bit for bit when that is below the bound, else a value >= bound;
//     eval_below(box, bound) encloses the error over the box and is eval(box) bit for bit whenever its lower end
//     is below the bound;
//   * operator() and residuals are const and touch no shared mutable state, so a Problem is immutable and can be
//     evaluated from many threads at once. Evaluation counts are kept by solvers, not here.
// A NaN point error means "invalid point": solvers skip it. An empty Interval error (Boost's domain errors, NaN
// bounds) is returned as [-inf, +inf] ("no information"), so a search never prunes a box on it.
#pragma once

#include <ceres/jet.h>

#include <array>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/interval.h"
#include "core/scalar.h"

namespace blocklab {

// The storage lattice of one parameter: x_k = origin + k * step for k in [0, count). count == 0 means the
// parameter is continuous (no lattice).
struct Lattice {
  double origin = 0.0;
  double step = 0.0;
  std::int64_t count = 0;

  static Lattice none() { return Lattice{}; }
  // `count` equally spaced points from `first` to `last` (count >= 2), or the single point `first` (count == 1).
  static Lattice uniform(double first, double last, std::int64_t count);

  bool present() const { return count > 0; }
  double point(std::int64_t index) const { return origin + static_cast<double>(index) * step; }
  // Index of the lattice point nearest to `value`, clamped to [0, count); ties go to the lower index.
  // Precondition: present().
  std::int64_t nearest_index(double value) const {
    // NaN and values below the first point map to index 0; the comparison form keeps NaN out of the cast below.
    if (!(value > origin) || count <= 1 || !(step > 0.0)) return 0;
    const double position = (value - origin) / step;
    if (position >= static_cast<double>(count - 1)) return count - 1;   // at or beyond the last point
    // 0 < position < count - 1 here, so truncation is floor, and both it and the conversion back are exact (count
    // fits in an int64 and positions below 2^53 are exact integers when whole): std::floor without its libm call.
    const std::int64_t lower = static_cast<std::int64_t>(position);
    const double fraction = position - static_cast<double>(lower);
    // Round half down so that a value exactly between two points takes the lower index.
    const std::int64_t index = lower + (fraction > 0.5 ? 1 : 0);
    return index < count ? index : count - 1;
  }
};

// ---- Capability: landmark similarity fit -------------------------------------------------------------------------
// A Problem may declare that it is a LANDMARK SIMILARITY FIT (Problem::landmark_fit), which lets structural solvers
// (`procrustes`: clustering, correspondences, weighted Procrustes) work on its data instead of only evaluating it:
//   * N weighted 2D points p_i in [0, 1]^2 are approximated by up to kFitLandmarkCount landmarks, and each point pays
//     the squared distance to its nearest landmark (after the stretch below);
//   * the 4 parameters are two base points x = (u0, v0, u1, v1), B0 = (u0, v0), B1 = (u1, v1), and landmark k is
//         L_k = B0 + along_k (B1 - B0) + across_k perp(B1 - B0),   perp(d) = (-d_v, d_u),
//     clamped to [0, 1] per coordinate (so landmarks 0 and 1 are the base points: along = (0, 1), across = (0, 0));
//   * each coordinate of points and clamped landmarks may be stretched by f(c) = max(c, kStretchFloor)^exponent
//     before the distance (exponent 1: no stretch, no floor).
// The Problem's own error decides among the candidates such a solver finds; the view only guides the search.
struct Point2 {
  double u = 0.0;
  double v = 0.0;
};

constexpr int kFitLandmarkCount = 4;
constexpr int kLandmarkFitParameterCount = 4;   // u0, v0, u1, v1
// Floor of the stretch f(c) = max(c, floor)^exponent: 2^-30, so f(floor) ~ 7.8e-5 at exponent 0.455 and the Jet
// derivative exponent floor^(exponent - 1) ~ 3.8e4 stays finite.
constexpr double kStretchFloor = 0x1p-30;

// The landmarks in the base-point frame: landmark k = B0 + along(k) (B1 - B0) + across(k) perp(B1 - B0).
struct LandmarkCoefficients {
  std::array<double, kFitLandmarkCount> along_values{};
  std::array<double, kFitLandmarkCount> across_values{};

  double along(int k) const { return along_values[static_cast<std::size_t>(k)]; }
  double across(int k) const { return across_values[static_cast<std::size_t>(k)]; }
  // Landmark k in the base-point frame, (along, across): B0 = (0, 0), B1 = (1, 0).
  Point2 normalised_landmark(int k) const { return {along(k), across(k)}; }
};

// What a landmark-fit Problem shows a solver (pointers into the Problem: valid while it lives).
struct LandmarkFitView {
  const std::vector<Point2>* points = nullptr;    // unstretched, in [0, 1]^2
  const std::vector<double>* weights = nullptr;   // one finite value >= 0 per point
  LandmarkCoefficients landmarks;
  double exponent = 1.0;                          // of the stretch; 1 = none
  // Optional: f(p_i) precomputed by the Problem (the same values a solver would compute, bit for bit), one per
  // point; nullptr when not offered.
  const std::vector<double>* stretched_u = nullptr;
  const std::vector<double>* stretched_v = nullptr;

  bool available() const { return points != nullptr && weights != nullptr; }
};

struct Bounds {
  std::vector<double> lower;
  std::vector<double> upper;
};

class Problem {
 public:
  virtual ~Problem() = default;

  int dim() const { return static_cast<int>(bounds_.lower.size()); }
  double lower(int parameter) const { return bounds_.lower[static_cast<std::size_t>(parameter)]; }
  double upper(int parameter) const { return bounds_.upper[static_cast<std::size_t>(parameter)]; }
  const Bounds& bounds() const { return bounds_; }
  // The lattice of `parameter` (Lattice::none() when it has none).
  const Lattice& lattice(int parameter) const { return lattices_[static_cast<std::size_t>(parameter)]; }
  // True when every parameter has a lattice.
  bool has_full_lattice() const;
  // Number of points of the full lattice (product of the counts); 0 when a parameter has no lattice, and
  // UINT64_MAX when the product does not fit in 64 bits.
  std::uint64_t lattice_point_count() const;

  // Point error at x[0..dim). NaN marks an invalid point.
  virtual double eval(const double* x) const = 0;
  // eval(x) when it is below `bound`, bit for bit; otherwise a value >= bound (or NaN) that may be a partial sum: a
  // search that only accepts strictly better points asks with its incumbent's error and stops paying for a point
  // once it cannot win. Default: eval(x); an error functor with a method `double eval_below(const double* x,
  // double bound) const` of that contract (early exit over non-negative terms) supplies it through ErrorProblem.
  virtual double eval_below(const double* x, double bound) const {
    (void)bound;
    return eval(x);
  }
  // Enclosure of the error over the box box[0..dim): contains eval(x) for every x in the box. Never empty (an
  // empty or NaN enclosure is returned as [-inf, +inf]).
  virtual Interval eval(const Interval* box) const = 0;
  // An enclosure of the error over the box that is eval(box), bit for bit, whenever its lower end is below
  // `bound`; otherwise it may be any enclosure with its lower end >= bound (wider above, up to +inf). A
  // branch-and-bound that discards boxes bounded at or above its incumbent asks with that threshold: it stops
  // paying for a box once a cheaper part of the bound has discarded it, and every box it keeps has the bound
  // eval(box) would give. Default: eval(box); an error functor with a method `Interval eval_below(const Interval*
  // box, double bound) const` of that contract supplies it through ErrorProblem.
  virtual Interval eval_below(const Interval* box, double bound) const {
    (void)bound;
    return eval(box);
  }
  // Error at x and its exact gradient (ceres::Jet automatic differentiation) into gradient[0..dim).
  virtual double eval_with_gradient(const double* x, double* gradient) const = 0;
  // Whether the error functor declared itself continuously differentiable (kSmooth). Non-smooth errors (min over
  // a palette, clamps) still have Jet gradients: the gradient of the branch taken at x.
  virtual bool is_smooth() const = 0;

  // Number of residuals of the least-squares form; 0 when the functor provides none.
  virtual int residual_count() const = 0;
  // residuals[0..residual_count()) at x and, when `jacobian` is not null, the Jacobian in row-major order
  // (jacobian[r * dim() + p] = d residual_r / d x_p). Throws Error when residual_count() == 0.
  virtual void eval_residuals(const double* x, double* residuals, double* jacobian) const = 0;

  // Capabilities a Problem may declare for solvers that need more than evaluations (default: none).
  // landmark_fit: the Problem is a landmark similarity fit (above); its parameters are then (u0, v0, u1, v1).
  virtual LandmarkFitView landmark_fit() const { return {}; }

 protected:
  // Validates (throws Error naming the parameter): lower.size() == upper.size() == dim, no NaN bound,
  // lower <= upper; lattices empty (none at all) or one per parameter; each present lattice has a finite origin,
  // a finite step > 0 when count > 1, and all its points inside [lower, upper] up to 1e-9 step.
  Problem(int dim, Bounds bounds, std::vector<Lattice> lattices);
  [[noreturn]] static void fail_no_residuals();

 private:
  Bounds bounds_;
  std::vector<Lattice> lattices_;
};

namespace problem_detail {

template <typename E, typename = void>
struct ResidualCount : std::integral_constant<int, 0> {};
template <typename E>
struct ResidualCount<E, std::void_t<decltype(E::kResiduals)>> : std::integral_constant<int, E::kResiduals> {};

template <typename E, typename = void>
struct HasEvalBelow : std::false_type {};
template <typename E>
struct HasEvalBelow<E, std::void_t<decltype(std::declval<const E&>().eval_below(static_cast<const double*>(nullptr),
                                                                                  0.0))>> : std::true_type {};

template <typename E, typename = void>
struct HasBoxEvalBelow : std::false_type {};
template <typename E>
struct HasBoxEvalBelow<
    E, std::void_t<decltype(std::declval<const E&>().eval_below(static_cast<const Interval*>(nullptr), 0.0))>>
    : std::true_type {};

template <typename E, typename = void>
struct Smooth : std::false_type {};
template <typename E>
struct Smooth<E, std::void_t<decltype(E::kSmooth)>> : std::integral_constant<bool, E::kSmooth> {};

}  // namespace problem_detail

// The error of a least-squares functor from its residuals: sum_i r_i(x)^2. A functor with kResiduals writes
//     template <typename T> T operator()(const T* x) const { return sum_of_squared_residuals<kResiduals>(*this, x); }
// so the error and the residual form cannot disagree.
template <int kResidualCount, typename E, typename T>
T sum_of_squared_residuals(const E& error, const T* x) {
  std::array<T, kResidualCount> r;
  error.residuals(x, r.data());
  T sum = T(0.0);
  for (const T& value : r) sum = sum + square(value);
  return sum;
}

// The adapter: a Problem evaluating the templated error functor E with each scalar type.
template <typename E>
class ErrorProblem final : public Problem {
 public:
  static constexpr int kDim = E::kDim;
  static constexpr int kResiduals = problem_detail::ResidualCount<E>::value;
  static constexpr bool kSmooth = problem_detail::Smooth<E>::value;
  static_assert(kDim >= 1, "an error functor needs at least one parameter (static constexpr int kDim >= 1)");
  static_assert(kResiduals >= 0, "kResiduals must be >= 0");
  using Jet = ceres::Jet<double, kDim>;

  ErrorProblem(E error, Bounds bounds, std::vector<Lattice> lattices)
      : Problem(kDim, std::move(bounds), std::move(lattices)), error_(std::move(error)) {}

  const E& error() const { return error_; }

  double eval(const double* x) const override { return error_(x); }

  double eval_below(const double* x, double bound) const override {
    if constexpr (problem_detail::HasEvalBelow<E>::value) {
      return error_.eval_below(x, bound);
    } else {
      (void)bound;
      return error_(x);
    }
  }

  Interval eval(const Interval* box) const override {
    const Interval enclosure = error_(box);
    // Empty (NaN bounds) carries no information: widen to the whole line so no search prunes on it.
    return is_empty(enclosure) ? Interval::whole() : enclosure;
  }

  Interval eval_below(const Interval* box, double bound) const override {
    if constexpr (problem_detail::HasBoxEvalBelow<E>::value) {
      const Interval enclosure = error_.eval_below(box, bound);
      return is_empty(enclosure) ? Interval::whole() : enclosure;
    } else {
      (void)bound;
      return eval(box);
    }
  }

  double eval_with_gradient(const double* x, double* gradient) const override {
    std::array<Jet, kDim> jet_x;
    for (int i = 0; i < kDim; ++i) jet_x[static_cast<std::size_t>(i)] = Jet(x[i], i);
    const Jet value = error_(jet_x.data());
    for (int i = 0; i < kDim; ++i) gradient[i] = value.v[i];
    return value.a;
  }

  bool is_smooth() const override { return kSmooth; }
  int residual_count() const override { return kResiduals; }

  void eval_residuals(const double* x, double* residuals, double* jacobian) const override {
    if constexpr (kResiduals == 0) {
      fail_no_residuals();
    } else {
      if (jacobian == nullptr) {
        error_.residuals(x, residuals);
        return;
      }
      std::array<Jet, kDim> jet_x;
      for (int i = 0; i < kDim; ++i) jet_x[static_cast<std::size_t>(i)] = Jet(x[i], i);
      std::array<Jet, kResiduals> jet_r;
      error_.residuals(jet_x.data(), jet_r.data());
      for (int r = 0; r < kResiduals; ++r) {
        const Jet& residual = jet_r[static_cast<std::size_t>(r)];
        residuals[r] = residual.a;
        for (int p = 0; p < kDim; ++p) jacobian[r * kDim + p] = residual.v[p];
      }
    }
  }

 private:
  E error_;
};

// Wraps `error` with its bounds and (optional) lattices; throws Error on inconsistent bounds or lattices.
template <typename E>
ErrorProblem<E> make_problem(E error, Bounds bounds, std::vector<Lattice> lattices = {}) {
  return ErrorProblem<E>(std::move(error), std::move(bounds), std::move(lattices));
}

}  // namespace blocklab
