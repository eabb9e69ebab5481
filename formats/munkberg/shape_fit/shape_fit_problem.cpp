// Construction and validation of the 2D chroma shape-fit problem (formats/munkberg/shape_fit/shape_fit_problem.h;
// Munkberg et al. 2008, sections 7.1 and 7.2).
#include "formats/munkberg/shape_fit/shape_fit_problem.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>

#include "core/error.h"
#include "core/number_text.h"
#include "formats/munkberg/shape_fit/outward_bounds.h"
#include "formats/munkberg/shape_fit/shape_fit_pair_bound.h"
#include "solvers/procrustes/stretch_table.h"

namespace blocklab {

namespace {

constexpr const char* kWhere = "shape fit";


void check_lattice_bits(int bits) {
  if (bits < 1 || bits > kMaxShapeLatticeBits)
    fail(kWhere, "lattice_bits: must be in [1, " + std::to_string(kMaxShapeLatticeBits) + "], got " +
                     std::to_string(bits));
}

}  // namespace

// ---- ShapeTemplate -----------------------------------------------------------------------------------------------

// The unit square (0,0), (1,0), (1,1), (0,1): landmarks 2 and 3 sit one base length across from 1 and 0.
ShapeTemplate::ShapeTemplate() : coefficients_{{0.0, 1.0, 1.0, 0.0}, {0.0, 0.0, 1.0, 1.0}} {}

ShapeTemplate ShapeTemplate::from_landmarks(const std::array<Point2, kShapeLandmarkCount>& landmarks) {
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const Point2& p = landmarks[static_cast<std::size_t>(k)];
    if (!std::isfinite(p.u) || !std::isfinite(p.v))
      fail("shape template", "landmark " + std::to_string(k) + " is not finite");
  }
  const Point2 origin = landmarks[0];
  const double du = landmarks[1].u - origin.u, dv = landmarks[1].v - origin.v;
  const double length_squared = du * du + dv * dv;
  // Coincident base landmarks: the two stored base points would not determine scale and rotation.
  if (!(length_squared > 0.0)) fail("shape template", "landmarks 0 and 1 coincide (they must be distinct base points)");
  ShapeTemplate shape;
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    const double ru = landmarks[kk].u - origin.u, rv = landmarks[kk].v - origin.v;
    // Coordinates of landmark k in the frame (B1 - B0, perp(B1 - B0)): projection and cross product over |d|^2.
    shape.coefficients_.along_values[kk] = (ru * du + rv * dv) / length_squared;
    shape.coefficients_.across_values[kk] = (du * rv - dv * ru) / length_squared;
  }
  // Landmarks 0 and 1 are the base points by definition: store them exactly (the division above may round).
  shape.coefficients_.along_values[0] = 0.0;
  shape.coefficients_.across_values[0] = 0.0;
  shape.coefficients_.along_values[1] = 1.0;
  shape.coefficients_.across_values[1] = 0.0;
  return shape;
}

ShapeTemplate ShapeTemplate::from_coefficients(const std::array<double, kShapeLandmarkCount>& along,
                                               const std::array<double, kShapeLandmarkCount>& across) {
  for (int k = 0; k < kShapeLandmarkCount; ++k)
    if (!std::isfinite(along[static_cast<std::size_t>(k)]) || !std::isfinite(across[static_cast<std::size_t>(k)]))
      fail("shape template", "coefficient of landmark " + std::to_string(k) + " is not finite");
  if (along[0] != 0.0 || across[0] != 0.0 || along[1] != 1.0 || across[1] != 0.0)
    fail("shape template", "landmarks 0 and 1 are the base points: their coefficients must be (0, 0) and (1, 0)");
  ShapeTemplate shape;
  shape.coefficients_.along_values = along;
  shape.coefficients_.across_values = across;
  return shape;
}

std::array<Point2, kShapeLandmarkCount> ShapeTemplate::landmarks_for(Point2 b0, Point2 b1) const {
  const double du = b1.u - b0.u, dv = b1.v - b0.v;
  std::array<Point2, kShapeLandmarkCount> out;
  for (int k = 0; k < kShapeLandmarkCount; ++k)
    out[static_cast<std::size_t>(k)] = {b0.u + along(k) * du - across(k) * dv, b0.v + along(k) * dv + across(k) * du};
  return out;
}

// ---- error kind names ----------------------------------------------------------------------------------------------

std::string to_string(ShapeErrorKind kind) { return kind == ShapeErrorKind::linear ? "linear" : "stretched"; }

ShapeErrorKind shape_error_kind_from_string(const std::string& name) {
  if (name == "linear") return ShapeErrorKind::linear;
  if (name == "stretched") return ShapeErrorKind::stretched;
  throw Error("unknown shape error kind '" + name + "'; valid kinds: linear, stretched");
}

// ---- data validation -------------------------------------------------------------------------------------------

void ShapeFitData::validate() const {
  if (points.empty()) fail(kWhere, "points: no point to fit");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point2& p = points[i];
    // The comparison form rejects NaN too.
    if (!(p.u >= 0.0 && p.u <= 1.0 && p.v >= 0.0 && p.v <= 1.0))
      fail(kWhere, "points[" + std::to_string(i) + "]: (" + exact_number_text(p.u) + ", " + exact_number_text(p.v) +
                       ") is outside [0, 1]^2");
  }
  if (!weights.empty() && weights.size() != points.size())
    fail(kWhere, "weights: " + std::to_string(weights.size()) + " weights for " + std::to_string(points.size()) +
                     " points (give none or one per point)");
  for (std::size_t i = 0; i < weights.size(); ++i)
    if (!(std::isfinite(weights[i]) && weights[i] >= 0.0))
      fail(kWhere, "weights[" + std::to_string(i) + "]: must be finite and >= 0, got " + exact_number_text(weights[i]));
  if (!(exponent > 0.0 && exponent <= 1.0))
    fail(kWhere, "exponent: must be in (0, 1], got " + exact_number_text(exponent));
  check_lattice_bits(lattice_bits);
}

// ---- the functor ---------------------------------------------------------------------------------------------

ShapeFitError ShapeFitError::from_data(const ShapeFitData& data) {
  data.validate();
  ShapeFitError error;
  error.stretched = data.error_kind == ShapeErrorKind::stretched;
  error.exponent = data.exponent;
  error.lattice_bits = data.lattice_bits;
  error.lattice_stretch = error.stretched ? shared_lattice_stretch(data.exponent, data.lattice_bits) : nullptr;
  const std::size_t n = data.points.size();
  error.target_u.resize(n);
  error.target_v.resize(n);
  error.weights.assign(n, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& p = data.points[i];
    error.target_u[i] = error.stretched ? stretch(p.u, data.exponent) : p.u;
    error.target_v[i] = error.stretched ? stretch(p.v, data.exponent) : p.v;
    if (!data.weights.empty()) error.weights[i] = data.weights[i];
  }
  // (1 - alpha) T rounded down, the right-hand side of the stretched terms' convexity test (box_enclosure).
  error.convexity_floor.resize(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    error.convexity_floor[2 * i] = ((1.0 - error.exponent) * Interval(error.target_u[i])).lower();
    error.convexity_floor[2 * i + 1] = ((1.0 - error.exponent) * Interval(error.target_v[i])).lower();
  }
  error.weighted_target_lower.resize(2 * n);
  error.weighted_target_upper.resize(2 * n);
  error.weighted_square_lower.resize(2 * n);
  error.weighted_square_upper.resize(2 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 2; ++c) {
      const Interval t(c == 0 ? error.target_u[i] : error.target_v[i]);
      const Interval weighted = error.weights[i] * t, weighted_square = error.weights[i] * square(t);
      error.weighted_target_lower[2 * i + c] = weighted.lower();
      error.weighted_target_upper[2 * i + c] = weighted.upper();
      error.weighted_square_lower[2 * i + c] = weighted_square.lower();
      error.weighted_square_upper[2 * i + c] = weighted_square.upper();
    }
  // The pair bound's order (shape_fit_pair_bound.h): the weighted points sorted on the target coordinate with the
  // larger spread (ties between values by index, so the order is fixed).
  double sum_u = 0.0, sum_v = 0.0, sum_uu = 0.0, sum_vv = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(error.weights[i] > 0.0)) continue;
    error.pair_order.push_back(static_cast<int>(i));
    sum_u += error.target_u[i];
    sum_v += error.target_v[i];
    sum_uu += error.target_u[i] * error.target_u[i];
    sum_vv += error.target_v[i] * error.target_v[i];
  }
  const double count = static_cast<double>(error.pair_order.size());
  const bool along_v = count > 0.0 && sum_vv - sum_v * sum_v / count > sum_uu - sum_u * sum_u / count;
  const std::vector<double>& key = along_v ? error.target_v : error.target_u;
  std::sort(error.pair_order.begin(), error.pair_order.end(), [&key](int a, int b) {
    const double ka = key[static_cast<std::size_t>(a)], kb = key[static_cast<std::size_t>(b)];
    return ka < kb || (ka == kb && a < b);
  });
  // L.u = (1 - a) u0 + a u1 + b v0 - b v1 and L.v = -b u0 + (1 - a) v0 + b u1 + a v1 (parameters u0, v0, u1, v1).
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    const double a = data.shape.along(k), b = data.shape.across(k);
    error.u_coefficients[kk] = {1.0 - a, b, a, -b};
    error.v_coefficients[kk] = {-b, 1.0 - a, b, a};
  }
  return error;
}

// ---- the box enclosure (interval path of the functor) ---------------------------------------------------------

namespace {

// Slope of clamp(L, 0, 1) where L ranges over `l`: 1 inside (0, 1), 0 outside, either when l straddles an end.
Interval clamp_slope(const Interval& l) {
  if (l.lower() >= 0.0 && l.upper() <= 1.0) return Interval(1.0);
  if (l.upper() <= 0.0 || l.lower() >= 1.0) return Interval(0.0);
  return Interval(0.0, 1.0);
}

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The box's centre c (its midpoints) and an enclosure of x - c for each parameter, the frame both enclosures build
// their tangent plane in; true when the box is a point (every side degenerate).
bool centre_box(const Interval* box, double* centre, Interval* offset) {
  bool degenerate = true;
  for (int p = 0; p < ShapeFitError::kDim; ++p) {
    centre[p] = midpoint(box[p]);
    offset[p] = box[p] - centre[p];   // encloses x_p - c_p
    if (box[p].lower() != box[p].upper()) degenerate = false;
  }
  return degenerate;
}

// The hot loop of both enclosures: for one point t and the 4 landmark boxes, enclosures [lower[k], upper[k]] of
// the squared distance |t - L_k|^2 on plain doubles, without Boost's per-operation empty-interval checks (the
// landmark boxes are finite, non-empty and within [0, 1] here) and without branches in the rounding: each bound is
// computed in round-to-nearest and widened outward (formats/munkberg/shape_fit/outward_bounds.h).
struct LandmarkBoxes {
  double u_lower[kShapeLandmarkCount], u_upper[kShapeLandmarkCount];
  double v_lower[kShapeLandmarkCount], v_upper[kShapeLandmarkCount];
};

// sum_p coefficients[p] box[p] with the same outward bounds (terms with a zero coefficient add exactly nothing,
// a unit coefficient needs no product): the landmark coordinates over a box, as linear_form<Interval> encloses them.
// Forced inline: it runs 8-20 times per box, and GCC's heuristics stopped inlining it into the linear enclosure when
// the stretched one grew (the out-of-line calls cost +2.4 % instructions of the linear certification, callgrind).
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
inline Interval fast_linear_form(const std::array<double, ShapeFitError::kDim>& coefficients, const Interval* box) {
  double lower = 0.0, upper = 0.0;
  bool first = true;
  for (int p = 0; p < ShapeFitError::kDim; ++p) {
    const double c = coefficients[static_cast<std::size_t>(p)];
    if (c == 0.0) continue;   // exact zero term
    double term_lower, term_upper;
    if (c == 1.0) {
      term_lower = box[p].lower();
      term_upper = box[p].upper();
    } else if (c > 0.0) {
      term_lower = widen_down(c * box[p].lower());
      term_upper = widen_up(c * box[p].upper());
    } else {
      term_lower = widen_down(c * box[p].upper());
      term_upper = widen_up(c * box[p].lower());
    }
    if (first) {
      lower = term_lower;
      upper = term_upper;
      first = false;
    } else {
      lower = widen_down(lower + term_lower);
      upper = widen_up(upper + term_upper);
    }
  }
  return Interval(lower, upper, true);
}

// A sum of enclosures accumulated on plain doubles with the same outward bounds.
struct IntervalSum {
  double lower = 0.0, upper = 0.0;
  void add(double term_lower, double term_upper) {
    lower = widen_down(lower + term_lower);
    upper = widen_up(upper + term_upper);
  }
  Interval value() const { return Interval(lower, upper, true); }
  IntervalSum operator+(const IntervalSum& other) const {
    return {widen_down(lower + other.lower), widen_up(upper + other.upper)};
  }
};

// The floor of an aggregated term (the stretched box enclosure): over F in `range`,
//     sum_i w_i (T_i - F)^2 = W (F - S1/W)^2 + (S2 - S1^2/W)   (W = sum w_i, S1 = sum w_i T_i, S2 = sum w_i T_i^2)
// is at least the points' weighted scatter about their mean plus W times the squared distance from the mean to the
// range. Unlike a tangent plane it needs no convexity in x and no tangent point, but it ignores the coupling of the
// landmark coordinates through x. Rounded down; >= 0; 0 without a term of positive weight.
double aggregated_floor(const IntervalSum& weights, const IntervalSum& targets, const IntervalSum& squares,
                        const Interval& range) {
  const Interval weight = weights.value(), first = targets.value();
  if (!(weight.lower() > 0.0)) return 0.0;
  const Interval mean = first / weight;
  const double below = widen_down(range.lower() - mean.upper()), above = widen_down(mean.lower() - range.upper());
  const double distance = std::max(0.0, std::max(below, above));
  const double scatter = std::max(0.0, (squares.value() - square(first) / weight).lower());
  return std::max(0.0, (Interval(scatter) + weight * square(Interval(distance))).lower());
}

// The squared distance enclosures of point t to the 4 landmark boxes (landmarks 0 and 1, 2 and 3 side by side where
// SSE2 is available; the same bits either way).
inline void point_distances(double tu, double tv, const LandmarkBoxes& boxes, double* lower, double* upper) {
#if defined(__SSE2__)
  const __m128d u = _mm_set1_pd(tu), v = _mm_set1_pd(tv), zero = _mm_setzero_pd();
  for (int k = 0; k < kShapeLandmarkCount; k += 2) {
    __m128d ul, uh, vl, vh;
    squared_difference_bounds_pair(u, _mm_loadu_pd(&boxes.u_lower[k]), _mm_loadu_pd(&boxes.u_upper[k]), &ul, &uh);
    squared_difference_bounds_pair(v, _mm_loadu_pd(&boxes.v_lower[k]), _mm_loadu_pd(&boxes.v_upper[k]), &vl, &vh);
    _mm_storeu_pd(&lower[k], _mm_max_pd(widen_down_pair(_mm_add_pd(ul, vl)), zero));
    _mm_storeu_pd(&upper[k], widen_up_pair(_mm_add_pd(uh, vh)));
  }
#else
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    double ul, uh, vl, vh;
    squared_difference_bounds(tu, boxes.u_lower[k], boxes.u_upper[k], &ul, &uh);
    squared_difference_bounds(tv, boxes.v_lower[k], boxes.v_upper[k], &vl, &vh);
    lower[k] = std::max(0.0, widen_down(ul + vl));
    upper[k] = widen_up(uh + vh);
  }
#endif
}

// natural += w * [lower, upper] for w >= 0 and 0 <= lower (a weighted nearest distance), outward rounded with the
// branch-free bounds above. Every term and partial sum is >= 0, so a widened lower bound below 0 is clamped to 0.
inline void add_weighted(double w, double lower, double upper, double& sum_lower, double& sum_upper) {
  // Unit weights (the default) need no multiplication.
  if (w != 1.0) {
    lower = std::max(0.0, widen_down(w * lower));
    upper = widen_up(w * upper);
  }
  sum_lower = std::max(0.0, widen_down(sum_lower + lower));
  sum_upper = widen_up(sum_upper + upper);
}

// sum += w * term for w >= 0 and term >= 0, a lower bound only (the separately bounded terms below).
inline void add_weighted_lower(double w, double term, double& sum) {
  if (w != 1.0) term = std::max(0.0, widen_down(w * term));
  sum = std::max(0.0, widen_down(sum + term));
}

// The stretch f(c) = max(c, kStretchFloor)^alpha over [lo, hi] (f increases) from the stretch table instead of two
// std::pow: each end widened by the table's error bound and one rounding, so the result contains std::pow's value
// at every point of [lo, hi] (StretchTable::kRelativeErrorBound). The landmark coordinates are in [0, 1] but a
// rounded linear form may pass 1 by an ulp: the table is read at 1 for the lower end (f(1) <= f(lo)) and the upper
// end is hi itself (c^alpha <= c for c >= 1). Below the floor (0 included) the table gives f(floor), as the error does.
constexpr double kTableDown = 1.0 - StretchTable::kRelativeErrorBound;
constexpr double kTableUp = 1.0 + StretchTable::kRelativeErrorBound;
// The table's values at the two ends, which the pair bound's slopes read again: `at_lower` = table(min(lo, 1)),
// `at_upper` = table(hi) (hi itself when hi > 1).
struct TableStretch {
  Interval enclosure;
  double at_lower = 0.0, at_upper = 0.0;
};
inline TableStretch table_stretch_ends(const StretchTable& table, double lo, double hi) {
  TableStretch result;
  result.at_lower = table(std::min(lo, 1.0));
  result.at_upper = hi > 1.0 ? hi : table(hi);
  const double upper = hi > 1.0 ? hi : widen_up(result.at_upper * kTableUp);
  result.enclosure = Interval(widen_down(result.at_lower * kTableDown), upper, true);
  return result;
}
inline Interval table_stretch(const StretchTable& table, double lo, double hi) {
  return table_stretch_ends(table, lo, hi).enclosure;
}

// The pair bound's ingredients (formats/munkberg/shape_fit/shape_fit_pair_bound.h). Points beyond the first
// kMaxPairedPoints keep their natural lower bound (a mask of 64 bits marks the points to pair).
constexpr std::size_t kMaxPairedPoints = 64;

// sum_p (row_k[p] - row_l[p]) x_p over the box: the difference of two landmark coordinates' linear forms, which keeps
// their correlation through x. The coefficient differences round (each by at most |d| 2^-53), so the enclosure is
// widened by twice that times the box's largest |x_p|.
Interval difference_form(const std::array<double, ShapeFitError::kDim>& row_k,
                         const std::array<double, ShapeFitError::kDim>& row_l, const Interval* box) {
  std::array<double, ShapeFitError::kDim> row;
  double slack = 0.0;
  for (std::size_t p = 0; p < row.size(); ++p) {
    row[p] = row_k[p] - row_l[p];
    const double reach = std::max(std::abs(box[p].lower()), std::abs(box[p].upper()));
    slack += (std::abs(row[p]) * 0x1p-52 + 0x1p-1074) * reach;
  }
  slack = widen_up(2.0 * slack);
  const Interval form = fast_linear_form(row, box);
  return Interval(widen_down(form.lower() - slack), widen_up(form.upper() + slack), true);
}

// The pair bound's landmark differences: per landmark pair (k < l) and coordinate, the difference of the two
// coordinate enclosures, intersected with coupled(jk, jl) (an enclosure of M_k - M_l that keeps their correlation
// through x, or the whole line where there is none). Both enclose the same values, so the intersection is not empty.
template <typename Coupled>
void fill_landmark_differences(const Interval* coordinate, Coupled coupled,
                               shape_fit_detail::LandmarkDifferences& differences) {
  for (int k = 0; k < kShapeLandmarkCount; ++k)
    for (int l = k + 1; l < kShapeLandmarkCount; ++l)
      for (int c = 0; c < 2; ++c) {
        const int jk = 2 * k + c, jl = 2 * l + c;
        const Interval tight = coupled(jk, jl);
        const double lower = widen_down(coordinate[jk].lower() - coordinate[jl].upper());
        const double upper = widen_up(coordinate[jk].upper() - coordinate[jl].lower());
        differences.set(k, l, c == 0, std::max(lower, tight.lower()), std::min(upper, tight.upper()));
      }
}

// The multi-candidate points' share of the lower bound: the points marked in `several`, in pair_order, the r-th
// paired with the (r + m/2)-th, each pair adding its pair bound; an odd one out adds its natural lower bound.
// `fill_differences` fills the landmark differences, only when there is a pair. Rounded down; >= 0.
template <typename FillDifferences>
double paired_points_lower(const ShapeFitError& error, std::uint64_t several,
                           const double (*candidate_lower)[kShapeLandmarkCount], FillDifferences fill_differences) {
  int members[kMaxPairedPoints];
  int count = 0;
  for (const int i : error.pair_order)
    if (static_cast<std::size_t>(i) < kMaxPairedPoints && ((several >> i) & 1u) != 0) members[count++] = i;
  double sum = 0.0;
  const int half = count / 2;
  if (half > 0) {
    shape_fit_detail::LandmarkDifferences differences;
    fill_differences(differences);
    for (int r = 0; r < half; ++r) {
      const int i = members[r], j = members[r + half];
      const double pair = shape_fit_detail::pair_lower_bound(error, i, j, candidate_lower[i], candidate_lower[j],
                                                             differences);
      sum = std::max(0.0, widen_down(sum + pair));
    }
  }
  if (count % 2 == 1) {
    const int last = members[count - 1];
    double nearest = candidate_lower[last][0];
    for (int k = 1; k < kShapeLandmarkCount; ++k) nearest = std::min(nearest, candidate_lower[last][k]);
    add_weighted_lower(error.weights[static_cast<std::size_t>(last)], nearest, sum);
  }
  return sum;
}

// The point scan of the box enclosure: ONE loop skeleton for both error kinds, each kind a policy for the terms of
// single-candidate points. Per point: the landmark distances over the box, the natural extension's sums, the prune
// test, and the point's class: one possibly-nearest landmark (`single_landmark(i, w, k, separate)` takes its
// coordinate terms: the linear policy aggregates the convex ones and adds the others to `separate`, the stretched
// one keeps its non-convex sums apart), several (marked for the pair bound, or beyond kMaxPairedPoints their
// natural lower bound added to `separate`), or none (NaN distances: the tangent bound is given up).
struct PointScan {
  double natural_lower = 0.0, natural_upper = 0.0;
  double separate = 0.0;          // rounded-down sum of lower bounds outside the tangent plane and the pairs
  std::uint64_t several = 0;      // points with several possibly-nearest landmarks (bit i), paired afterwards
  double candidate_lower[kMaxPairedPoints][kShapeLandmarkCount];   // their per-landmark natural lower bounds
  bool tangent_usable = true;
  bool pruned = false;            // the natural lower bound reached the prune bound: stopped there
};

template <typename SingleLandmark>
void scan_points(const ShapeFitError& error, const LandmarkBoxes& boxes, double prune_bound, PointScan& scan,
                 SingleLandmark single_landmark) {
  const std::size_t n = error.target_u.size();
  for (std::size_t i = 0; i < n; ++i) {
    double distance_lower[kShapeLandmarkCount], distance_upper[kShapeLandmarkCount];
    point_distances(error.target_u[i], error.target_v[i], boxes, distance_lower, distance_upper);
    // The interval min extension: [min of lowers, min of uppers].
    double nearest_lower = distance_lower[0], smallest_upper = distance_upper[0];
    for (int k = 1; k < kShapeLandmarkCount; ++k) {
      nearest_lower = std::min(nearest_lower, distance_lower[k]);
      smallest_upper = std::min(smallest_upper, distance_upper[k]);
    }
    const double w = error.weights[i];
    add_weighted(w, nearest_lower, smallest_upper, scan.natural_lower, scan.natural_upper);
    // Discarded by its natural bound alone: the rest of the points and the tangent plane cannot lower it.
    if (scan.natural_lower >= prune_bound) {
      scan.pruned = true;
      return;
    }
    // A weightless point adds exactly 0 to the bound; once the tangent bound is given up nothing more is needed.
    if (w == 0.0 || !scan.tangent_usable) continue;
    // Landmarks certainly farther than another one everywhere in the box are never the nearest. The smallest lower
    // bound among the candidates is the point's natural lower bound (the landmark of the smallest lower bound is
    // always a candidate).
    int active_count = 0, single = 0;
    double point_lower = kInfinity;
    for (int k = 0; k < kShapeLandmarkCount; ++k)
      if (distance_lower[k] <= smallest_upper) {
        ++active_count;
        single = k;
        point_lower = std::min(point_lower, distance_lower[k]);
      }
    if (active_count == 1) {
      single_landmark(i, w, single, scan.separate);
      continue;
    }
    // No candidate at all would mean NaN distances: give up the tangent bound rather than add +inf.
    if (!(point_lower < kInfinity)) {
      scan.tangent_usable = false;
      continue;
    }
    if (i < kMaxPairedPoints) {   // paired after the loop (formats/munkberg/shape_fit/shape_fit_pair_bound.h)
      std::copy(distance_lower, distance_lower + kShapeLandmarkCount, scan.candidate_lower[i]);
      scan.several |= std::uint64_t{1} << i;
      continue;
    }
    add_weighted_lower(w, point_lower, scan.separate);
  }
}

// Coordinate descent (up to 6 sweeps, on doubles) for the minimiser over the box of the quadratic model
// m(c + s) = gradient . s + 1/2 s^T hessian s with s_p in [offset_p.lower, offset_p.upper]. Only a good tangent
// point is wanted: any result is valid for the bounds built on it. A sweep that changes no step is a fixed point
// (every later sweep would repeat it bit for bit), so the descent stops there with the same steps.
template <int kDim>
void minimise_model(const double (&gradient)[kDim], const double (&hessian)[kDim][kDim], const Interval* offset,
                    double (&step)[kDim]) {
  for (int p = 0; p < kDim; ++p) step[p] = 0.0;
  for (int sweep = 0; sweep < 6; ++sweep) {
    bool changed = false;
    for (int p = 0; p < kDim; ++p) {
      double slope = gradient[p];
      for (int q = 0; q < kDim; ++q)
        if (q != p) slope += hessian[p][q] * step[q];
      const double curvature = hessian[p][p];
      // Flat (or non-convex) direction: the linear term alone decides the end of the box.
      const double target = curvature > 0.0 ? -slope / curvature : (slope > 0.0 ? -kInfinity : kInfinity);
      // NaN (from a NaN model) fails both comparisons in min/max below and is replaced by 0, the centre.
      const double next =
          std::isnan(target) ? 0.0 : std::min(std::max(target, offset[p].lower()), offset[p].upper());
      // Compared as bits: -0.0 and 0.0 must count as a change (they can give different products later).
      changed = changed || std::memcmp(&next, &step[p], sizeof next) != 0;
      step[p] = next;
    }
    if (!changed) return;
  }
}

// The stretched error's enclosure (ShapeFitError::box_enclosure): the natural extension, with a tangent-plane lower
// bound over the coordinate terms of points whose nearest landmark is certain, where those terms are convex.
//   Per coordinate, g(L) = (T - f(L))^2 with f(L) = L^alpha (L above the stretch floor, unclamped on the box),
//   g'' = 2 f'^2 - 2 (T - f) f''. With f'' < 0 it is >= 0 where f(L) <= T, and where f(L) > T it is >= 0 iff
//   (L^alpha - T)(1 - alpha) <= alpha L^alpha, i.e. (1 - 2 alpha) L^alpha <= (1 - alpha) T: always for
//   alpha >= 1/2, and for alpha < 1/2 checked at the box's largest L (L^alpha increases). A coordinate clamped
//   over the whole box (slope 0) is constant. The sum H of such terms is convex on the box, so for any y in the
//   box H(x) >= H(y) + grad H(y) . (x - y); y is the box minimiser of a quadratic model of H (curvature g'' per
//   term), re-expanded around the previous y 3 times (the stretch makes H far from quadratic over large boxes:
//   measured 2x fewer boxes than a single expansion at the centre); H(y) and grad H(y) are evaluated in interval
//   arithmetic, so the bound is rigorous. Terms are aggregated per landmark coordinate:
//   sum_i w_i (T_i - F)^2 = S2 - 2 F S1 + F^2 W with W = sum w_i, S1 = sum w_i T_i, S2 = sum w_i T_i^2, and its
//   derivative in L is -2 f'(L) (S1 - F W). A non-convex coordinate term adds its natural lower bound; points with
//   several possibly-nearest landmarks are paired and add the pair bound
// (formats/munkberg/shape_fit/shape_fit_pair_bound.h). The lower
//   bound is the largest of the natural one, the tangent plane's and the floor (aggregated_floor: all terms of the
//   certain-landmark points, convex or not, at least their scatter), which is computed first.
Interval stretched_box_enclosure(const ShapeFitError& error, const Interval* box, double prune_bound) {
  constexpr int kDim = ShapeFitError::kDim;
  const double alpha = error.exponent;
  const StretchTable& table = shared_stretch_table(alpha);
  double centre[kDim];
  Interval offset[kDim];
  const bool degenerate = centre_box(box, centre, offset);
  // A point box: the tangent plane would only add rounding.
  if (degenerate) return error.natural_error(box);

  // Per landmark coordinate (index 2 k for u, 2 k + 1 for v): its coefficient row, linear value over the box,
  // clamp slope, stretched value over the box, and whether its terms can be convex (smooth on the box).
  constexpr int kCoordinates = 2 * kShapeLandmarkCount;
  const std::array<double, kDim>* rows[kCoordinates];
  Interval stretched_value[kCoordinates];
  bool smooth[kCoordinates], constant[kCoordinates];
  double convex_limit[kCoordinates];   // terms are convex when (1 - alpha) T >= this
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    rows[2 * k] = &error.u_coefficients[kk];
    rows[2 * k + 1] = &error.v_coefficients[kk];
  }
  Interval linear_value[kCoordinates];
  double table_at_lower[kCoordinates], table_at_upper[kCoordinates];   // f at the clamped ends, from the table
  for (int j = 0; j < kCoordinates; ++j) {
    const Interval linear = fast_linear_form(*rows[j], box);
    linear_value[j] = linear;
    const Interval clamped = clamp(linear, Interval(0.0), Interval(1.0));
    const TableStretch ends = table_stretch_ends(table, clamped.lower(), clamped.upper());
    stretched_value[j] = ends.enclosure;
    table_at_lower[j] = ends.at_lower;
    table_at_upper[j] = ends.at_upper;
    const Interval slope = clamp_slope(linear);
    constant[j] = slope.lower() == 0.0 && slope.upper() == 0.0;
    // Slope exactly 1 and above the floor: the stretch is the smooth L^alpha on the whole box.
    smooth[j] = constant[j] || (slope.lower() == 1.0 && linear.lower() >= kStretchFloor);
    convex_limit[j] = -kInfinity;
    // (1 - 2 alpha) L^alpha at the largest L of the box; the stretched value's upper bound encloses L^alpha there
    // (L <= 1 when smooth, so the clamp changes nothing).
    if (smooth[j] && !constant[j] && alpha < 0.5)
      convex_limit[j] = ((1.0 - 2.0 * alpha) * Interval(stretched_value[j].upper())).upper();
  }

  LandmarkBoxes boxes;
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    boxes.u_lower[k] = stretched_value[2 * k].lower();
    boxes.u_upper[k] = stretched_value[2 * k].upper();
    boxes.v_lower[k] = stretched_value[2 * k + 1].lower();
    boxes.v_upper[k] = stretched_value[2 * k + 1].upper();
  }
  // Sums of lower bounds (rounded down): the non-convex coordinate terms of single-candidate points, and (the
  // scan's `separate`) the other terms not aggregated (points beyond kMaxPairedPoints, then the pair bound).
  double nonconvex_lower = 0.0;
  // Aggregated sums per landmark coordinate: W, S1, S2 of the convex terms of single-candidate points (the tangent
  // plane), and of their other terms (with the convex ones, the floor).
  IntervalSum weight_sums[kCoordinates], target_sums[kCoordinates], square_sums[kCoordinates];
  IntervalSum nonconvex_weight_sums[kCoordinates], nonconvex_target_sums[kCoordinates],
      nonconvex_square_sums[kCoordinates];
  PointScan scan;
  scan_points(error, boxes, prune_bound, scan, [&](std::size_t i, double w, int single, double&) {
    // Separable by coordinate: a convex coordinate term is aggregated, any other adds its natural lower bound.
    const double targets[2] = {error.target_u[i], error.target_v[i]};
    for (int c = 0; c < 2; ++c) {
      const int j = 2 * single + c;
      const double floor_value = error.convexity_floor[2 * i + static_cast<std::size_t>(c)];
      const bool convex = smooth[j] && (convex_limit[j] == -kInfinity || convex_limit[j] <= floor_value);
      const std::size_t ic = 2 * i + static_cast<std::size_t>(c);
      if (!convex) {
        double term_lower, term_upper;
        squared_difference_bounds(targets[c], stretched_value[j].lower(), stretched_value[j].upper(), &term_lower,
                                  &term_upper);
        add_weighted_lower(w, term_lower, nonconvex_lower);
        nonconvex_target_sums[j].add(error.weighted_target_lower[ic], error.weighted_target_upper[ic]);
        nonconvex_square_sums[j].add(error.weighted_square_lower[ic], error.weighted_square_upper[ic]);
        nonconvex_weight_sums[j].add(w, w);
        continue;
      }
      target_sums[j].add(error.weighted_target_lower[ic], error.weighted_target_upper[ic]);
      square_sums[j].add(error.weighted_square_lower[ic], error.weighted_square_upper[ic]);
      weight_sums[j].add(w, w);
    }
  });
  if (scan.pruned) return Interval(scan.natural_lower, kInfinity);
  double separate_lower = scan.separate;
  const std::uint64_t several = scan.several;
  const auto& candidate_lower = scan.candidate_lower;
  const Interval natural(scan.natural_lower, scan.natural_upper);
  if (!scan.tangent_usable) return natural;
  // The landmark differences of the pair bound: the difference of the stretched ranges, and where both coordinates
  // are smooth and sloped on the box, f(a) - f(b) = f'(xi) (a - b) with xi between them (mean value theorem), f'
  // decreasing: f' between its value at the larger upper end and at the smaller lower end (f' = alpha f / L, from
  // the table widened by its error bound), times the linear form of a - b. The intersection of both.
  const auto fill_differences = [&](shape_fit_detail::LandmarkDifferences& differences) {
    double slope_lower[kCoordinates], slope_upper[kCoordinates];
    bool sloped[kCoordinates];
    for (int j = 0; j < kCoordinates; ++j) {
      sloped[j] = smooth[j] && !constant[j];
      if (!sloped[j]) continue;
      // Smooth: kStretchFloor <= L <= 1 on the box, so both divisions are by positive values, and the clamp changed
      // nothing: the table's values at the ends are f(lo) and f(hi).
      const double lo = linear_value[j].lower(), hi = linear_value[j].upper();
      slope_upper[j] = widen_up(widen_up(alpha * widen_up(table_at_lower[j] * kTableUp)) / lo);
      slope_lower[j] =
          std::max(0.0, widen_down(widen_down(alpha * widen_down(table_at_upper[j] * kTableDown)) / hi));
    }
    const auto mean_value_form = [&](int jk, int jl) {
      if (!sloped[jk] || !sloped[jl]) return Interval::whole();
      const Interval d = difference_form(*rows[jk], *rows[jl], box);
      const double s_lo = std::min(slope_lower[jk], slope_lower[jl]);
      const double s_hi = std::max(slope_upper[jk], slope_upper[jl]);
      // [s_lo, s_hi] * d with s_lo >= 0: each end takes the slope that moves it outward.
      return Interval(widen_down((d.lower() >= 0.0 ? s_lo : s_hi) * d.lower()),
                      widen_up((d.upper() >= 0.0 ? s_hi : s_lo) * d.upper()), true);
    };
    fill_landmark_differences(stretched_value, mean_value_form, differences);
  };
  const double paired = paired_points_lower(error, several, candidate_lower, fill_differences);
  separate_lower = std::max(0.0, widen_down(separate_lower + paired));
  // The floor (aggregated_floor) of every coordinate term of the single-candidate points, convex or not, over the
  // box's stretched range. Stronger than the tangent plane where the model's minimiser is poor (a steep stretch near
  // L = 0 over a large box: measured on memorial.hdr's near-grey blocks, 142,069 -> 19,031 boxes for one) or a term
  // is not convex; a box it discards needs no tangent plane.
  double floor_bound = separate_lower;
  for (int j = 0; j < kCoordinates; ++j)
    floor_bound = widen_down(floor_bound + aggregated_floor(weight_sums[j] + nonconvex_weight_sums[j],
                                                            target_sums[j] + nonconvex_target_sums[j],
                                                            square_sums[j] + nonconvex_square_sums[j],
                                                            stretched_value[j]));
  if (floor_bound >= prune_bound && floor_bound <= natural.upper()) return Interval(floor_bound, natural.upper());
  Interval sum_w[kCoordinates], sum_t[kCoordinates], sum_tt[kCoordinates];
  for (int j = 0; j < kCoordinates; ++j) {
    sum_w[j] = weight_sums[j].value();
    sum_t[j] = target_sums[j].value();
    sum_tt[j] = square_sums[j].value();
  }

  // Quadratic model of H (doubles) around a point, and its box minimiser y = c + step: first around the centre,
  // then once more around that y (the stretch makes H far from quadratic over large boxes).
  // Without a sloped aggregated term (every point with several possibly-nearest landmarks, as on most boxes of a
  // small shape) every gradient below is exactly [0, 0], so the tangent point changes nothing: no model (y = c).
  bool sloped = false;
  for (int j = 0; j < kCoordinates; ++j) sloped = sloped || (!constant[j] && sum_w[j].upper() != 0.0);
  double step[kDim] = {0.0, 0.0, 0.0, 0.0};
  for (int pass = 0; sloped && pass < 3; ++pass) {
    // Model around c + step: gradient g and Hessian B there; minimise g . (s - step) + 1/2 (s - step)^T B (s - step)
    // over the box, written in the offsets from c as (g - B step) . s + 1/2 s^T B s.
    double model_gradient[kDim] = {0.0, 0.0, 0.0, 0.0};
    double model_hessian[kDim][kDim] = {};
    for (int j = 0; j < kCoordinates; ++j) {
      if (constant[j] || sum_w[j].upper() == 0.0) continue;   // no slope, or no aggregated term
      double at_point = 0.0;
      for (int p = 0; p < kDim; ++p) at_point += (*rows[j])[static_cast<std::size_t>(p)] * (centre[p] + step[p]);
      // The model only places the tangent point: the table's value is plenty (and l stays in [floor, 1]).
      const double l = std::min(std::max(at_point, kStretchFloor), 1.0);
      const double f = table(l), f1 = alpha * f / l, f2 = (alpha - 1.0) * f1 / l;
      const double weight = midpoint(sum_w[j]), first = midpoint(sum_t[j]);
      const double d1 = -2.0 * f1 * (first - f * weight);
      const double d2 = 2.0 * f1 * f1 * weight - 2.0 * f2 * (first - f * weight);
      for (int p = 0; p < kDim; ++p) {
        const double rp = (*rows[j])[static_cast<std::size_t>(p)];
        model_gradient[p] += d1 * rp;
        for (int q = 0; q < kDim; ++q) model_hessian[p][q] += d2 * rp * (*rows[j])[static_cast<std::size_t>(q)];
      }
    }
    for (int p = 0; p < kDim; ++p)
      for (int q = 0; q < kDim; ++q) model_gradient[p] -= model_hessian[p][q] * step[q];
    minimise_model<kDim>(model_gradient, model_hessian, offset, step);
  }
  double y[kDim];
  Interval y_box[kDim];
  for (int p = 0; p < kDim; ++p) {
    y[p] = centre[p] + step[p];
    y[p] = std::min(std::max(y[p], box[p].lower()), box[p].upper());   // rounding must not leave the box
    y_box[p] = Interval(y[p]);
  }

  // H(y) and grad H(y), rigorously.
  Interval value(0.0);
  Interval gradient[kDim] = {Interval(0.0), Interval(0.0), Interval(0.0), Interval(0.0)};
  for (int j = 0; j < kCoordinates; ++j) {
    if (sum_w[j].upper() == 0.0) continue;   // no aggregated term
    // Constant coordinates: the clamped (and stretched) value of the box, no slope.
    const Interval l = constant[j] ? Interval(0.0) : fast_linear_form(*rows[j], y_box);
    const Interval f = constant[j] ? stretched_value[j] : table_stretch(table, l.lower(), l.upper());
    value += sum_tt[j] - 2.0 * f * sum_t[j] + square(f) * sum_w[j];
    if (constant[j]) continue;
    // l >= the floor: inside the smooth box.
    // f'(l) = alpha l^(alpha - 1) = alpha f(l) / l (l > 0 here), without another power.
    const Interval slope = -2.0 * (alpha * (f / l)) * (sum_t[j] - f * sum_w[j]);
    for (int p = 0; p < kDim; ++p) {
      const double rp = (*rows[j])[static_cast<std::size_t>(p)];
      if (rp != 0.0) gradient[p] += rp * slope;   // zero coefficients add exactly nothing
    }
  }
  Interval tangent = value + Interval(widen_down(separate_lower + nonconvex_lower));
  for (int p = 0; p < kDim; ++p) tangent += gradient[p] * (box[p] - y[p]);
  double lower = natural.lower();
  // NaN (an empty term) fails the comparison and keeps the natural bound.
  if (tangent.lower() > lower) lower = tangent.lower();
  if (floor_bound > lower) lower = floor_bound;
  // The tangent bound is a lower bound of the error, so it stays <= natural.upper(); keep the natural extension
  // should rounding ever say otherwise.
  if (!(lower <= natural.upper())) return natural;
  return Interval(lower, natural.upper());
}

}  // namespace

Interval ShapeFitError::box_enclosure(const Interval* box, double prune_bound) const {
  if (stretched) return stretched_box_enclosure(*this, box, prune_bound);
  double centre[kDim];
  Interval offset[kDim];
  const bool degenerate = centre_box(box, centre, offset);
  // A point box: the hyperplane would only add rounding.
  if (degenerate) return natural_error(box);

  // Landmarks over the box (clamped) and the slope of each clamp.
  Interval landmark_u[kShapeLandmarkCount], landmark_v[kShapeLandmarkCount];
  Interval chain_u[kShapeLandmarkCount], chain_v[kShapeLandmarkCount];
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    const Interval linear_u = fast_linear_form(u_coefficients[kk], box);
    const Interval linear_v = fast_linear_form(v_coefficients[kk], box);
    landmark_u[k] = clamp(linear_u, Interval(0.0), Interval(1.0));
    landmark_v[k] = clamp(linear_v, Interval(0.0), Interval(1.0));
    chain_u[k] = clamp_slope(linear_u);
    chain_v[k] = clamp_slope(linear_v);
  }

  // Convexity bound. Where landmark k's clamps are inactive or saturated over the whole box (clamp slope exactly
  // 1 or 0 per coordinate), its distance d_k(x) = |t - clamp(L_k(x))|^2 is a convex quadratic on the box. Points
  // with a single possibly-nearest landmark contribute their convex coordinate terms to ONE convex quadratic,
  // bounded below by its tangent plane at (approximately) its box minimiser (after the loop), and the natural lower
  // bound of any coordinate term whose clamp straddles 0 or 1. A point with several candidates contributes its
  // natural lower bound (min over the candidates). (Measured: also bounding those points' convex candidates by
  // their tangent planes at the box centre saved 2-4% of the boxes at 2.5x the time per box; dropped.) Values and
  // gradients are evaluated in interval arithmetic at points, so the bound is rigorous.
  // The clamped landmark coordinates at the centre, for the double model only.
  double centre_u[kShapeLandmarkCount], centre_v[kShapeLandmarkCount];
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    centre_u[k] = clamp(linear_form(u_coefficients[kk], centre), 0.0, 1.0);
    centre_v[k] = clamp(linear_form(v_coefficients[kk], centre), 0.0, 1.0);
  }
  // Per landmark coordinate j = 2 k (u) or 2 k + 1 (v): coefficient row, clamped box value, clamp slope.
  constexpr int kCoordinates = 2 * kShapeLandmarkCount;
  const std::array<double, kDim>* rows[kCoordinates];
  Interval coordinate_box[kCoordinates];
  double coordinate_centre[kCoordinates];
  bool fixed_slope[kCoordinates], free_slope[kCoordinates];   // slope exactly 0 or 1 / exactly 1
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    rows[2 * k] = &u_coefficients[kk];
    rows[2 * k + 1] = &v_coefficients[kk];
    coordinate_box[2 * k] = landmark_u[k];
    coordinate_box[2 * k + 1] = landmark_v[k];
    coordinate_centre[2 * k] = centre_u[k];
    coordinate_centre[2 * k + 1] = centre_v[k];
    fixed_slope[2 * k] = chain_u[k].lower() == chain_u[k].upper();
    fixed_slope[2 * k + 1] = chain_v[k].lower() == chain_v[k].upper();
    free_slope[2 * k] = chain_u[k].lower() == 1.0;
    free_slope[2 * k + 1] = chain_v[k].lower() == 1.0;
  }
  // Points with a single possibly-nearest landmark k: the error term is w (t_u - clamp(L_u))^2 + w (t_v -
  // clamp(L_v))^2, separable by coordinate. A coordinate whose clamp slope is exactly 0 or 1 on the box gives a
  // convex quadratic in x and is aggregated per coordinate: weight W_j = sum w, S_j = sum w t, T_j = sum w t^2, from
  // which the aggregated terms' total and gradient follow without per-point work. A coordinate whose clamp
  // straddles 0 or 1 (a concave kink) adds its natural lower bound instead. W_j is summed as an interval (a double
  // sum of non-unit weights rounds); `aggregated` says whether any term was.
  bool aggregated[kCoordinates] = {};
  IntervalSum weight_sums[kCoordinates], target_sums[kCoordinates], square_sums[kCoordinates];
  // The natural lower bounds of the terms not aggregated: straddled coordinates and points with several candidates
  // beyond the paired ones (the scan's `separate`, summed rounding down), then the pair bound.
  // The natural extension is summed in the same scan (the same bounds as natural_error, sharing its landmark
  // distances).
  LandmarkBoxes boxes;
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    boxes.u_lower[k] = landmark_u[k].lower();
    boxes.u_upper[k] = landmark_u[k].upper();
    boxes.v_lower[k] = landmark_v[k].lower();
    boxes.v_upper[k] = landmark_v[k].upper();
  }
  PointScan scan;
  scan_points(*this, boxes, prune_bound, scan, [&](std::size_t i, double w, int single, double& separate) {
    const double targets[2] = {target_u[i], target_v[i]};
    for (int c = 0; c < 2; ++c) {
      const int j = 2 * single + c;
      if (!fixed_slope[j]) {
        // Straddled clamp: the natural lower bound of this coordinate's term.
        double term_lower, term_upper;
        squared_difference_bounds(targets[c], coordinate_box[j].lower(), coordinate_box[j].upper(), &term_lower,
                                  &term_upper);
        add_weighted_lower(w, term_lower, separate);
        continue;
      }
      const std::size_t ic = 2 * i + static_cast<std::size_t>(c);
      target_sums[j].add(weighted_target_lower[ic], weighted_target_upper[ic]);
      square_sums[j].add(weighted_square_lower[ic], weighted_square_upper[ic]);
      weight_sums[j].add(w, w);
      aggregated[j] = true;
    }
  });
  if (scan.pruned) return Interval(scan.natural_lower, kInfinity);
  const bool hyperplane_usable = scan.tangent_usable;
  double separate_sum = scan.separate;
  if (hyperplane_usable) {
    // The landmark differences of the pair bound: the difference of the clamped ranges and, where neither clamp
    // acts on the box (slope exactly 1), the linear form of the difference; the intersection of both.
    const auto fill_differences = [&](shape_fit_detail::LandmarkDifferences& differences) {
      const auto linear_form = [&](int jk, int jl) {
        return free_slope[jk] && free_slope[jl] ? difference_form(*rows[jk], *rows[jl], box) : Interval::whole();
      };
      fill_landmark_differences(coordinate_box, linear_form, differences);
    };
    const double paired = paired_points_lower(*this, scan.several, scan.candidate_lower, fill_differences);
    separate_sum = std::max(0.0, widen_down(separate_sum + paired));
  }
  const Interval separate_lower(separate_sum);
  const Interval natural(scan.natural_lower, scan.natural_upper);
  Interval sum_w[kCoordinates], sum_t[kCoordinates], sum_squares[kCoordinates];
  for (int j = 0; j < kCoordinates; ++j) {
    sum_w[j] = weight_sums[j].value();
    sum_t[j] = target_sums[j].value();
    sum_squares[j] = square_sums[j].value();
  }
  double lower = natural.lower();
  if (hyperplane_usable) {
    // The aggregated terms form ONE convex quadratic on the box (each is w (t - r_j . x)^2 for a free coordinate,
    // slope 1, or the constant w (t - m_j)^2 for a saturated one, m_j = 0 or 1):
    //     Q(x) = sum_j [T_j - 2 L_j(x) S_j + W_j L_j(x)^2],   grad Q = sum_{j free} 2 (W_j L_j(x) - S_j) r_j,
    // with L_j(x) the landmark coordinate at x. Its tangent plane at any y, Q(y) + grad Q(y) . (x - y), lies below
    // Q everywhere (convexity), and minimised over the box it is the exact minimum of Q when y is Q's box
    // minimiser. y is found approximately on a double model (gradient at the centre c and the Hessian
    // 2 sum_{j free} W_j r_j r_j^T, coordinate descent: any y gives a valid bound); Q(y) and grad Q(y) are then
    // evaluated from the aggregated sums in interval arithmetic, so the bound is rigorous. (The tangent plane at c
    // itself, which drops the whole quadratic term, pruned 5x fewer boxes.)
    double model_gradient[kDim] = {0.0, 0.0, 0.0, 0.0}, model_hessian[kDim][kDim] = {};
    double step[kDim] = {0.0, 0.0, 0.0, 0.0};
    bool sloped = false;
    for (int j = 0; j < kCoordinates; ++j) {
      if (!aggregated[j] || !free_slope[j]) continue;   // no aggregated term, or a constant one
      sloped = true;
      const double w = midpoint(sum_w[j]);
      const double along = 2.0 * (w * coordinate_centre[j] - midpoint(sum_t[j]));
      for (int p = 0; p < kDim; ++p) {
        const double rp = (*rows[j])[static_cast<std::size_t>(p)];
        model_gradient[p] += rp * along;
        for (int q = 0; q < kDim; ++q) model_hessian[p][q] += 2.0 * w * rp * (*rows[j])[static_cast<std::size_t>(q)];
      }
    }
    // Without a sloped aggregated term every gradient below is exactly [0, 0]: the tangent point changes nothing.
    if (sloped) minimise_model<kDim>(model_gradient, model_hessian, offset, step);
    Interval y_box[kDim];
    double y[kDim];
    for (int p = 0; p < kDim; ++p) {
      y[p] = centre[p] + step[p];
      y_box[p] = Interval(y[p]);
    }
    Interval value = separate_lower;
    Interval gradient[kDim] = {Interval(0.0), Interval(0.0), Interval(0.0), Interval(0.0)};
    for (int j = 0; j < kCoordinates; ++j) {
      if (!aggregated[j]) continue;   // no aggregated term on this coordinate
      // Slope 1: the affine coordinate at y (the quadratic's own formula, unclamped); slope 0: the clamp constant
      // of the box (coordinate_box[j] is then exactly 0 or 1).
      const Interval l = free_slope[j] ? fast_linear_form(*rows[j], y_box) : coordinate_box[j];
      value += sum_squares[j] - 2.0 * (l * sum_t[j]) + sum_w[j] * square(l);
      if (!free_slope[j]) continue;
      const Interval along = 2.0 * (sum_w[j] * l - sum_t[j]);
      for (int p = 0; p < kDim; ++p) {
        const double rp = (*rows[j])[static_cast<std::size_t>(p)];
        if (rp != 0.0) gradient[p] += rp * along;   // zero coefficients add exactly nothing
      }
    }
    Interval tangent = value;
    for (int p = 0; p < kDim; ++p) tangent += gradient[p] * (box[p] - y[p]);
    // NaN (an empty term) fails the comparison and keeps the natural bound.
    if (tangent.lower() > lower) lower = tangent.lower();
  }
  // The plane bound is a lower bound of the error, so it stays <= natural.upper(); keep the natural extension
  // should rounding ever say otherwise (or it is empty: NaN bounds fail the comparison).
  if (!(lower <= natural.upper())) return natural;
  return Interval(lower, natural.upper());
}

// ---- the stretch at lattice points ----------------------------------------------------------------------------

const LatticeStretch* shared_lattice_stretch(double alpha, int bits) {
  if (bits < 1 || bits > LatticeStretch::kMaxBits) return nullptr;
  static std::mutex mutex;
  static std::vector<std::unique_ptr<const LatticeStretch>> tables;
  const std::lock_guard<std::mutex> lock(mutex);
  for (const auto& table : tables)
    if (table->alpha == alpha && table->bits == bits) return table.get();
  auto table = std::make_unique<LatticeStretch>();
  table->alpha = alpha;
  table->bits = bits;
  const Lattice lattice = shape_fit_lattices(bits)[0];
  table->scale = static_cast<double>(lattice.count - 1);
  for (std::int64_t i = 0; i < lattice.count; ++i) {
    const double point = lattice.point(i);
    table->points.push_back(point);
    table->values.push_back(ShapeFitError::stretch(point, alpha));   // the point error's own operations
  }
  tables.push_back(std::move(table));
  return tables.back().get();
}

// ---- bounds, lattices, the Problem -----------------------------------------------------------------------------

Bounds shape_fit_bounds() { return Bounds{{0.0, 0.0, 0.0, 0.0}, {1.0, 1.0, 1.0, 1.0}}; }

std::vector<Lattice> shape_fit_lattices(int lattice_bits) {
  check_lattice_bits(lattice_bits);
  const Lattice lattice = Lattice::uniform(0.0, 1.0, std::int64_t{1} << lattice_bits);
  return std::vector<Lattice>(kShapeFitParameterCount, lattice);
}

namespace {

std::vector<double> unit_weights_if_empty(const ShapeFitData& data) {
  return data.weights.empty() ? std::vector<double>(data.points.size(), 1.0) : data.weights;
}

}  // namespace

ShapeFitProblem::ShapeFitProblem(ShapeFitData data)
    : Problem(kShapeFitParameterCount, shape_fit_bounds(), shape_fit_lattices(data.lattice_bits)),
      data_(std::move(data)),
      weights_(unit_weights_if_empty(data_)),
      adapter_(ShapeFitError::from_data(data_), shape_fit_bounds(), shape_fit_lattices(data_.lattice_bits)) {}

std::array<Point2, kShapeLandmarkCount> ShapeFitProblem::decoded_landmarks(const double* x) const {
  // The same linear forms and clamp the error evaluates (bit-identical landmarks), without the stretch.
  std::array<Point2, kShapeLandmarkCount> out;
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    out[kk].u = clamp(ShapeFitError::linear_form(error().u_coefficients[kk], x), 0.0, 1.0);
    out[kk].v = clamp(ShapeFitError::linear_form(error().v_coefficients[kk], x), 0.0, 1.0);
  }
  return out;
}

LandmarkFitView ShapeFitProblem::landmark_fit() const {
  LandmarkFitView view;
  view.points = &data_.points;
  view.weights = &weights_;
  view.landmarks = data_.shape.coefficients();
  view.exponent = fit_exponent();
  // The stretched error's targets are f(p_i) with the same std::pow the solver's measure would call, bit for bit.
  if (error().stretched) {
    view.stretched_u = &error().target_u;
    view.stretched_v = &error().target_v;
  }
  return view;
}

ShapeFitProblem make_shape_fit_problem(ShapeFitData data) { return ShapeFitProblem(std::move(data)); }

}  // namespace blocklab
