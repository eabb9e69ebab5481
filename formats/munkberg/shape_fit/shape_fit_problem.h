// The 2D chroma shape-fit problem of Munkberg et al. 2008, "Practical HDR Texture Compression", section 7.1
// (eq. 11) and section 7.2 (the non-linear error f(x) = x^alpha), as a blocklab Problem and as a structured
// point-set object the `procrustes` solver reads.
//
// THE MODEL
//   N chroma points p_i = (u_i, v_i) in [0, 1]^2 with weights w_i >= 0 (default 1; e.g. luminance-based) are
//   approximated by a template shape of 4 landmarks transformed by a similarity (uniform scale, rotation,
//   translation; reflections excluded). Each point snaps to its nearest transformed landmark.
//
// PARAMETERISATION (chosen for both the solver maths and the storage lattice)
//   The 4 parameters are the two stored base points, x = (u0, v0, u1, v1): B0 = (u0, v0) and B1 = (u1, v1) are
//   the images of template landmarks 0 and 1, exactly what the format stores (paper 7.1: "the transform
//   parameters ... are implicitly encoded by storing the location of two base colors"). The template is kept in
//   its base-point frame: landmark k has coefficients (a_k, b_k) with
//       L_k = B0 + a_k (B1 - B0) + b_k perp(B1 - B0),   perp(d) = (-d_v, d_u)   (a counter-clockwise quarter turn),
//   so (a_0, b_0) = (0, 0) and (a_1, b_1) = (1, 0). Written per coordinate,
//       L_k.u = (1 - a_k) u0 + a_k u1 + b_k v0 - b_k v1,    L_k.v = -b_k u0 + (1 - a_k) v0 + b_k u1 + a_k v1,
//   every landmark coordinate is LINEAR in x and each parameter occurs once, so its interval enclosure over a box
//   is tight (only rounding-wide), which is what makes branch-and-bound on this problem effective. B0 == B1 is a
//   valid (degenerate) transform: all landmarks collapse onto B0 (scale 0).
//   Decoded landmarks are clamped to [0, 1] per coordinate (chroma is never negative and the stored range is
//   [0, 1]); the error is measured on the clamped landmarks.
//   Storage lattice: each base-point coordinate on `lattice_bits` bits, 2^bits equally spaced values in [0, 1]
//   (default 8 bits: Munkberg's "base colors quantized to 8 bits per component", 2^32 combinations).
//
// ERRORS (ShapeErrorKind)
//   linear     eq. 11 with weights: E = sum_i w_i min_k |p_i - L_k|^2.
//   stretched  section 7.2: the same distance measured after f(c) = max(c, kStretchFloor)^alpha applied to each
//              coordinate of the data points and of the clamped landmarks (alpha = 0.455 by default). The floor
//              keeps pow's Jet derivative finite at c = 0 and is applied to both sides, so a landmark exactly on a
//              point still gives 0.
//   Both are ONE functor (ShapeFitError) templated on the scalar type (core/scalar.h rules: min, clamp, square,
//   no branch on T).
//
// HOW SOLVERS SEE IT
//   * As a Problem: ShapeFitProblem IS a Problem (dim 4, bounds [0, 1]^4, the lattice above); or build the plain
//     adapter yourself with make_problem(ShapeFitError::from_data(data), shape_fit_bounds(), shape_fit_lattices(b)).
//   * As a landmark similarity fit: ShapeFitProblem declares the capability Problem::landmark_fit (core/problem.h:
//     points, weights, the template's coefficients, the stretch exponent and the stretched targets), which
//     `procrustes` reads; it refuses problems without it. Any other Problem (e.g. a format's own chroma error) can
//     declare it too, as long as its 4 parameters follow the base-point convention above; procrustes then ranks its
//     candidates with that problem's own error.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "core/problem.h"
#include "core/scalar.h"

namespace blocklab {

constexpr int kShapeLandmarkCount = kFitLandmarkCount;
constexpr int kShapeFitParameterCount = kLandmarkFitParameterCount;   // u0, v0, u1, v1
constexpr int kDefaultShapeLatticeBits = 8;
constexpr int kMaxShapeLatticeBits = 24;
// Munkberg 2008 section 7.2: "We use a value alpha = 0.455".
constexpr double kDefaultStretchExponent = 0.455;

// The stretch f(c) = max(c, kStretchFloor)^alpha of section 7.2 at the points of a storage lattice (shape_fit_lattices
// (bits)), computed once with std::pow: the stretched point error maps the base points (landmarks 0 and 1, lattice
// values at every lattice point a search visits) through it instead of calling std::pow, bit for bit the same.
struct LatticeStretch {
  static constexpr int kMaxBits = 12;   // 4,096 values; finer lattices call std::pow
  double alpha = 1.0;
  int bits = 0;
  double scale = 0.0;              // count - 1: a lattice point's index is c * scale, rounded
  std::vector<double> points;      // the lattice points, exactly as Lattice::point gives them
  std::vector<double> values;      // std::pow(max(point, kStretchFloor), alpha)

  // f(c): the table's value when c is a lattice point, otherwise ShapeFitError::stretch's (NaN stays NaN). Defined
  // after ShapeFitError, whose stretch it falls back to.
  double operator()(double c) const;
};
// The table for (alpha, bits), built on first use and shared by every thread for the process's lifetime (constant
// data; the lookup takes a lock, so ShapeFitError::from_data looks it up once); nullptr when bits >
// LatticeStretch::kMaxBits.
const LatticeStretch* shared_lattice_stretch(double alpha, int bits);

// A template shape of 4 landmarks, stored in its base-point frame (coefficients (a_k, b_k), see the file comment).
// Default-constructed: the unit square (0,0), (1,0), (1,1), (0,1), a placeholder for tests; formats define their
// own template sets.
class ShapeTemplate {
 public:
  ShapeTemplate();
  // Landmarks in any frame; landmarks 0 and 1 become the base points. Throws Error when a coordinate is not
  // finite or landmarks 0 and 1 coincide (the base points could not determine the transform).
  static ShapeTemplate from_landmarks(const std::array<Point2, kShapeLandmarkCount>& landmarks);
  // Coefficients directly: landmark k = B0 + along[k] (B1 - B0) + across[k] perp(B1 - B0). along[0] = across[0] =
  // across[1] = 0 and along[1] = 1 are required (throws Error otherwise).
  static ShapeTemplate from_coefficients(const std::array<double, kShapeLandmarkCount>& along,
                                         const std::array<double, kShapeLandmarkCount>& across);

  double along(int k) const { return coefficients_.along(k); }
  double across(int k) const { return coefficients_.across(k); }
  // Landmark k in the base-point frame, (along, across): B0 = (0, 0), B1 = (1, 0).
  Point2 normalised_landmark(int k) const { return coefficients_.normalised_landmark(k); }
  // The coefficients as the landmark-fit capability shows them (core/problem.h).
  const LandmarkCoefficients& coefficients() const { return coefficients_; }
  // A template is a landmark set: it goes wherever the solver library takes one (procrustes' fits and refinements).
  operator const LandmarkCoefficients&() const { return coefficients_; }   // NOLINT(google-explicit-constructor)
  // The landmarks decoded for base points b0, b1 (not clamped).
  std::array<Point2, kShapeLandmarkCount> landmarks_for(Point2 b0, Point2 b1) const;

 private:
  LandmarkCoefficients coefficients_;
};

enum class ShapeErrorKind { linear, stretched };
std::string to_string(ShapeErrorKind kind);   // "linear", "stretched"
// Throws Error("unknown shape error kind 'x'; valid kinds: linear, stretched").
ShapeErrorKind shape_error_kind_from_string(const std::string& name);

// The structured problem: what a format fills in for one block and one template.
struct ShapeFitData {
  std::vector<Point2> points;                           // in [0, 1]^2
  std::vector<double> weights;                          // empty (all 1) or one finite value >= 0 per point
  ShapeTemplate shape;
  ShapeErrorKind error_kind = ShapeErrorKind::linear;
  double exponent = kDefaultStretchExponent;            // alpha of the stretched error, in (0, 1]
  int lattice_bits = kDefaultShapeLatticeBits;          // per base-point coordinate, 1..kMaxShapeLatticeBits

  // Throws Error("shape fit: <field>: <reason>") on: no point, a point outside [0, 1]^2 or NaN, a weight count
  // other than 0 or points.size(), a negative/non-finite weight, exponent outside (0, 1], lattice_bits out of range.
  void validate() const;
};

// The templated error (core/problem.h rules). Per-point targets are precomputed (stretched for the stretched
// kind) so the hot loop is 4 landmark distances, a min and a weighted sum per point.
struct ShapeFitError {
  static constexpr int kDim = kShapeFitParameterCount;

  std::vector<double> target_u, target_v;   // data points, after the stretch when `stretched`
  std::vector<double> weights;              // one per point
  // Landmark coordinate = sum_p coefficient[k][p] * x[p] (p = u0, v0, u1, v1), from the template coefficients.
  std::array<std::array<double, kDim>, kShapeLandmarkCount> u_coefficients{};
  std::array<std::array<double, kDim>, kShapeLandmarkCount> v_coefficients{};
  bool stretched = false;
  double exponent = kDefaultStretchExponent;
  int lattice_bits = kDefaultShapeLatticeBits;   // the storage lattice's (LatticeStretch of the point error)
  // The stretch at the storage lattice's points (shared_lattice_stretch(exponent, lattice_bits), set by from_data);
  // nullptr: every stretch calls std::pow (the same values).
  const LatticeStretch* lattice_stretch = nullptr;
  // Per point and coordinate (index 2 i for u, 2 i + 1 for v), enclosures of w_i t and w_i t^2 (t the target
  // coordinate), read by box_enclosure's aggregation.
  std::vector<double> weighted_target_lower, weighted_target_upper;
  std::vector<double> weighted_square_lower, weighted_square_upper;
  // Per point and coordinate: (1 - exponent) times the (stretched) target, rounded down (stretched kind's
  // convexity test in box_enclosure).
  std::vector<double> convexity_floor;
  // The points of weight > 0 in ascending order of the (stretched) target coordinate with the larger spread (u on
  // ties; equal values by index): the order box_enclosure's pair bound pairs points in
  // (formats/munkberg/shape_fit/shape_fit_pair_bound.h).
  std::vector<int> pair_order;

  // Validates `data` (ShapeFitData::validate) and precomputes the targets and coefficients.
  static ShapeFitError from_data(const ShapeFitData& data);

  // The stretch f(c) = max(c, kStretchFloor)^exponent of section 7.2 (c >= 0 here).
  template <typename T>
  static T stretch(const T& c, double exponent) {
    using std::pow;   // std for double; ADL finds ceres' (Jet) and blocklab's (Interval) pow(x, double)
    return pow(max(c, T(kStretchFloor)), exponent);
  }

  // Landmark coordinate sum_p coefficients[p] x[p]; a zero coefficient adds nothing and a unit one needs no
  // multiplication (both exact, so the interval enclosure stays as tight as the data allow).
  template <typename T>
  static T linear_form(const std::array<double, kDim>& coefficients, const T* x) {
    T sum = T(0.0);
    bool first = true;
    for (int p = 0; p < kDim; ++p) {
      const double c = coefficients[static_cast<std::size_t>(p)];
      if (c == 0.0) continue;   // exact zero term: skipped (a branch on the template, never on T)
      const T term = c == 1.0 ? x[p] : c * x[p];   // double * T: no interval x interval product
      sum = first ? term : sum + term;
      first = false;
    }
    return sum;
  }

  // The decoded landmark coordinates, clamped to [0, 1] (and stretched when `stretched`).
  // For double, the stretch of a coordinate on the storage lattice (every base point a lattice search visits) comes
  // from LatticeStretch: the same std::pow value, computed once per process.
  template <typename T>
  void landmarks(const T* x, T* u, T* v) const {
    const LatticeStretch* lattice = nullptr;
    if constexpr (std::is_same_v<T, double>) {
      if (stretched) lattice = lattice_stretch;
    }
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      const std::size_t kk = static_cast<std::size_t>(k);
      u[k] = clamp(linear_form(u_coefficients[kk], x), T(0.0), T(1.0));
      v[k] = clamp(linear_form(v_coefficients[kk], x), T(0.0), T(1.0));
      if (!stretched) continue;   // a branch on the error kind, fixed for the problem
      if constexpr (std::is_same_v<T, double>) {
        if (lattice != nullptr) {
          u[k] = (*lattice)(u[k]);
          v[k] = (*lattice)(v[k]);
          continue;
        }
      }
      u[k] = stretch(u[k], exponent);
      v[k] = stretch(v[k], exponent);
    }
  }

  // The natural interval extension (and the plain error for double and Jet): eq. 11 written once on T. For double,
  // an optional early exit (eval_below): every point's term is >= 0, so once the partial sum reaches `bound` the
  // full error cannot end below it and the partial sum is returned (NaN stops the sum too); below the bound the
  // value is the full sum, bit for bit.
  template <typename T>
  T natural_error(const T* x, double bound = std::numeric_limits<double>::infinity()) const {
    T landmark_u[kShapeLandmarkCount], landmark_v[kShapeLandmarkCount];
    landmarks(x, landmark_u, landmark_v);
    T sum = T(0.0);
    const std::size_t n = target_u.size();
    for (std::size_t i = 0; i < n; ++i) {
      // double - T (no conversion of the target to T; Boost has the mixed operators, ceres too).
      T best = square(target_u[i] - landmark_u[0]) + square(target_v[i] - landmark_v[0]);
      for (int k = 1; k < kShapeLandmarkCount; ++k)
        best = min(best, square(target_u[i] - landmark_u[k]) + square(target_v[i] - landmark_v[k]));
      // Unit weights (the default) need no multiplication.
      sum += weights[i] == 1.0 ? best : weights[i] * best;
      if constexpr (std::is_same_v<T, double>) {
        if (!(sum < bound)) return sum;
      }
    }
    return sum;
  }

  // Problem::eval_below: natural_error<double> stopped once its partial sum reaches `bound`.
  double eval_below(const double* x, double bound) const { return natural_error(x, bound); }
  // Problem::eval_below for boxes: box_enclosure stopped once the natural extension's lower bound reaches `bound`.
  Interval eval_below(const Interval* box, double bound) const { return box_enclosure(box, bound); }

  // The error. For intervals: box_enclosure (the natural extension with a tighter lower bound, below).
  template <typename T>
  T operator()(const T* x) const {
    if constexpr (std::is_same_v<T, Interval>) {
      return box_enclosure(x);
    } else {
      return natural_error(x);
    }
  }

  // Enclosure of the error over `box` (what interval_bb prunes with; details at the code). Upper bound: the
  // natural extension's. Lower bound: the natural extension's, raised by a convexity bound. A point whose nearest
  // landmark is certain on the box contributes, per coordinate, either a term that is convex in x on the box
  // (clamp slope exactly 0 or 1 there; for the stretched error also (1 - 2 alpha) L^alpha <= (1 - alpha) T) or
  // that term's natural lower bound. The convex terms are summed into one convex function, bounded below by its
  // tangent plane at an approximate box minimiser y (coordinate descent on a quadratic model in double; for the
  // stretched error re-expanded 3 times), with its value and gradient at y evaluated in interval arithmetic, so
  // the bound is rigorous for any y; minimised over the box, the tangent plane is within the model's error of
  // the exact minimum of that sum. Points with several possible nearest landmarks are paired (pair_order) and each
  // pair adds the pair bound of formats/munkberg/shape_fit/shape_fit_pair_bound.h (at least the two points' natural
  // lower bounds; an odd one out adds its natural lower bound). The stretched kind also takes the floor of its
  // certain-landmark terms (each landmark coordinate's points pay at least their scatter; aggregated_floor in
  // shape_fit_problem.cpp). Measured (docs/solver-bench.md): 10-20x fewer interval_bb boxes than the natural extension
  // on real blocks. A centred (mean-value) form, which this function computed up to 2026-11-24, changed no box count
  // and was dropped. With a finite `prune_bound` (eval_below): once the natural lower bound (a running sum over the
  // points) reaches it, the box is discarded whatever the tangent plane would add, so [that partial lower bound, +inf]
  // is returned at once (valid: the remaining terms are >= 0); the stretched kind likewise returns [floor, natural
  // upper] once the floor reaches it, without the tangent plane. Otherwise the result is the full enclosure, bit for
  // bit.
  Interval box_enclosure(const Interval* box,
                         double prune_bound = std::numeric_limits<double>::infinity()) const;
};

inline double LatticeStretch::operator()(double c) const {
  const double position = c * scale;
  if (position >= 0.0 && position <= scale) {   // false for NaN
    const std::size_t index = static_cast<std::size_t>(position + 0.5);
    if (points[index] == c) return values[index];
  }
  return ShapeFitError::stretch(c, alpha);
}

// [0, 1]^4 and the 2^bits-point lattice on each base-point coordinate.
Bounds shape_fit_bounds();
std::vector<Lattice> shape_fit_lattices(int lattice_bits);

// The shape fit as a Problem with the landmark-fit capability. Immutable and safe to evaluate from many threads.
class ShapeFitProblem final : public Problem {
 public:
  // Validates `data` (throws Error "shape fit: ...").
  explicit ShapeFitProblem(ShapeFitData data);

  const ShapeFitData& data() const { return data_; }
  const ShapeFitError& error() const { return adapter_.error(); }
  const Problem& problem() const { return *this; }
  // Decoded landmarks (clamped to [0, 1], not stretched) for parameters x[0..4).
  std::array<Point2, kShapeLandmarkCount> decoded_landmarks(const double* x) const;

  double eval(const double* x) const override { return adapter_.eval(x); }
  double eval_below(const double* x, double bound) const override { return adapter_.eval_below(x, bound); }
  Interval eval(const Interval* box) const override { return adapter_.eval(box); }
  Interval eval_below(const Interval* box, double bound) const override { return adapter_.eval_below(box, bound); }
  double eval_with_gradient(const double* x, double* gradient) const override {
    return adapter_.eval_with_gradient(x, gradient);
  }
  bool is_smooth() const override { return false; }   // min over landmarks and the clamp have kinks
  int residual_count() const override { return 0; }
  void eval_residuals(const double* x, double* residuals, double* jacobian) const override {
    adapter_.eval_residuals(x, residuals, jacobian);   // throws: no least-squares form
  }

  const std::vector<Point2>& fit_points() const { return data_.points; }
  const std::vector<double>& fit_weights() const { return weights_; }
  // The error's per-coordinate stretch exponent alpha (section 7.2), or 1 for the linear error.
  double fit_exponent() const { return data_.error_kind == ShapeErrorKind::stretched ? data_.exponent : 1.0; }
  // The capability: points, weights, the template's coefficients, the exponent and (stretched) the targets.
  LandmarkFitView landmark_fit() const override;

 private:
  ShapeFitData data_;
  std::vector<double> weights_;   // data_.weights, or all 1 when none were given
  ErrorProblem<ShapeFitError> adapter_;
};

ShapeFitProblem make_shape_fit_problem(ShapeFitData data);

}  // namespace blocklab
