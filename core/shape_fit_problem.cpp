// Construction and validation of the 2D chroma shape-fit problem (core/shape_fit_problem.h; Munkberg et al. 2008,
// sections 7.1 and 7.2).
#include "core/shape_fit_problem.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"

namespace blocklab {

namespace {

constexpr const char* kWhere = "shape fit";

std::string number_text(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

void check_lattice_bits(int bits) {
  if (bits < 1 || bits > kMaxShapeLatticeBits)
    fail(kWhere, "lattice_bits: must be in [1, " + std::to_string(kMaxShapeLatticeBits) + "], got " +
                     std::to_string(bits));
}

}  // namespace

// ---- ShapeTemplate -----------------------------------------------------------------------------------------------

// The unit square (0,0), (1,0), (1,1), (0,1): landmarks 2 and 3 sit one base length across from 1 and 0.
ShapeTemplate::ShapeTemplate() : along_{0.0, 1.0, 1.0, 0.0}, across_{0.0, 0.0, 1.0, 1.0} {}

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
    shape.along_[kk] = (ru * du + rv * dv) / length_squared;
    shape.across_[kk] = (du * rv - dv * ru) / length_squared;
  }
  // Landmarks 0 and 1 are the base points by definition: store them exactly (the division above may round).
  shape.along_[0] = 0.0;
  shape.across_[0] = 0.0;
  shape.along_[1] = 1.0;
  shape.across_[1] = 0.0;
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
  shape.along_ = along;
  shape.across_ = across;
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
      fail(kWhere, "points[" + std::to_string(i) + "]: (" + number_text(p.u) + ", " + number_text(p.v) +
                       ") is outside [0, 1]^2");
  }
  if (!weights.empty() && weights.size() != points.size())
    fail(kWhere, "weights: " + std::to_string(weights.size()) + " weights for " + std::to_string(points.size()) +
                     " points (give none or one per point)");
  for (std::size_t i = 0; i < weights.size(); ++i)
    if (!(std::isfinite(weights[i]) && weights[i] >= 0.0))
      fail(kWhere, "weights[" + std::to_string(i) + "]: must be finite and >= 0, got " + number_text(weights[i]));
  if (!(exponent > 0.0 && exponent <= 1.0))
    fail(kWhere, "exponent: must be in (0, 1], got " + number_text(exponent));
  check_lattice_bits(lattice_bits);
}

// ---- the functor ---------------------------------------------------------------------------------------------

ShapeFitError ShapeFitError::from_data(const ShapeFitData& data) {
  data.validate();
  ShapeFitError error;
  error.stretched = data.error_kind == ShapeErrorKind::stretched;
  error.exponent = data.exponent;
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
  // L.u = (1 - a) u0 + a u1 + b v0 - b v1 and L.v = -b u0 + (1 - a) v0 + b u1 + a v1 (parameters u0, v0, u1, v1).
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    const double a = data.shape.along(k), b = data.shape.across(k);
    error.u_coefficients[kk] = {1.0 - a, b, a, -b};
    error.v_coefficients[kk] = {-b, 1.0 - a, b, a};
  }
  return error;
}

// ---- the centred form (interval path of the functor) --------------------------------------------------------

namespace {

// Slope of clamp(L, 0, 1) where L ranges over `l`: 1 inside (0, 1), 0 outside, either when l straddles an end.
Interval clamp_slope(const Interval& l) {
  if (l.lower() >= 0.0 && l.upper() <= 1.0) return Interval(1.0);
  if (l.upper() <= 0.0 || l.lower() >= 1.0) return Interval(0.0);
  return Interval(0.0, 1.0);
}

// Slope of the stretch max(c, floor)^alpha for c in `c` (within [0, 1]): alpha c^(alpha - 1) above the floor
// (decreasing in c, bounded by its value at the floor), 0 below it.
Interval stretch_slope(const Interval& c, double exponent) {
  // Entirely at or below the floor: the stretch is constant there.
  if (c.upper() <= kStretchFloor) return Interval(0.0);
  const Interval above(std::max(c.lower(), kStretchFloor), c.upper());
  const Interval slope = exponent * pow(above, exponent - 1.0);
  // Part of c below the floor adds slope 0.
  return c.lower() < kStretchFloor ? boost::numeric::hull(slope, Interval(0.0)) : slope;
}

}  // namespace

Interval ShapeFitError::centred_enclosure(const Interval* box) const {
  double centre[kDim];
  Interval at_centre_box[kDim], offset[kDim];
  bool degenerate = true;
  for (int p = 0; p < kDim; ++p) {
    centre[p] = midpoint(box[p]);
    at_centre_box[p] = Interval(centre[p]);
    offset[p] = box[p] - centre[p];   // encloses x_p - c_p
    if (box[p].lower() != box[p].upper()) degenerate = false;
  }
  // A point box: the centred form would only add rounding.
  if (degenerate) return natural_error(box);
  const Interval at_centre = natural_error(at_centre_box);

  // Landmarks over the box (clamped, stretched) and the chain factor d(stretched landmark) / d(linear landmark).
  Interval landmark_u[kShapeLandmarkCount], landmark_v[kShapeLandmarkCount];
  Interval chain_u[kShapeLandmarkCount], chain_v[kShapeLandmarkCount];
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    const Interval linear_u = linear_form(u_coefficients[kk], box), linear_v = linear_form(v_coefficients[kk], box);
    landmark_u[k] = clamp(linear_u, Interval(0.0), Interval(1.0));
    landmark_v[k] = clamp(linear_v, Interval(0.0), Interval(1.0));
    chain_u[k] = clamp_slope(linear_u);
    chain_v[k] = clamp_slope(linear_v);
    if (stretched) {
      chain_u[k] = chain_u[k] * stretch_slope(landmark_u[k], exponent);
      chain_v[k] = chain_v[k] * stretch_slope(landmark_v[k], exponent);
      landmark_u[k] = stretch(landmark_u[k], exponent);
      landmark_v[k] = stretch(landmark_v[k], exponent);
    }
  }

  // Supporting-hyperplane bound (linear kind only). Where landmark k's clamps are inactive or saturated over the
  // whole box (clamp slope exactly 1 or 0 per coordinate), its distance d_k(x) = |t - clamp(L_k(x))|^2 is a convex
  // quadratic on the box, so d_k(x) >= d_k(c) + grad d_k(c) . (x - c) everywhere in it. A point with a single
  // possibly-nearest landmark contributes that hyperplane to ONE global hyperplane (minimised over the box once);
  // a point with several contributes min over them of each one's own lower bound (its hyperplane minimised over
  // the box, or the natural lower bound of a non-convex one). The bound's slack is the dropped quadratic term
  // only, about half the centred form's (whose gradient enclosure adds |H| r on top of |grad(c)|), and near a
  // minimum grad(c) ~ 0, so it prunes boxes the centred form keeps. d_k(c) and grad d_k(c) are evaluated in
  // interval arithmetic at the point c, so the bound is rigorous.
  Interval centre_u[kShapeLandmarkCount], centre_v[kShapeLandmarkCount];
  bool convex[kShapeLandmarkCount];
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    centre_u[k] = clamp(linear_form(u_coefficients[kk], at_centre_box), Interval(0.0), Interval(1.0));
    centre_v[k] = clamp(linear_form(v_coefficients[kk], at_centre_box), Interval(0.0), Interval(1.0));
    // Slope exactly 0 or 1 on the whole box (a straddled clamp, slope [0, 1], has a concave kink).
    convex[k] = !stretched && chain_u[k].lower() == chain_u[k].upper() && chain_v[k].lower() == chain_v[k].upper();
  }
  // Value and gradient at c of landmark k's distance to point i (chain slopes are exactly 0 or 1 when used).
  const auto centre_term = [&](std::size_t i, int k, Interval* term_gradient) {
    const std::size_t kk = static_cast<std::size_t>(k);
    const Interval du = centre_u[k] - target_u[i], dv = centre_v[k] - target_v[i];
    const Interval along_u = chain_u[k].lower() == 1.0 ? 2.0 * du : Interval(0.0);
    const Interval along_v = chain_v[k].lower() == 1.0 ? 2.0 * dv : Interval(0.0);
    for (int p = 0; p < kDim; ++p) {
      const std::size_t pp = static_cast<std::size_t>(p);
      term_gradient[p] = u_coefficients[kk][pp] * along_u + v_coefficients[kk][pp] * along_v;
    }
    return square(du) + square(dv);
  };
  Interval hyperplane_value(0.0);
  Interval hyperplane_gradient[kDim] = {Interval(0.0), Interval(0.0), Interval(0.0), Interval(0.0)};
  Interval separate_lower(0.0);   // sum of the per-point lower bounds of points with several candidates
  bool hyperplane_usable = !stretched;

  // The natural extension is summed in the same loop (the same expression as natural_error, sharing its
  // landmark distances).
  Interval natural(0.0);
  Interval gradient[kDim] = {Interval(0.0), Interval(0.0), Interval(0.0), Interval(0.0)};
  const std::size_t n = target_u.size();
  for (std::size_t i = 0; i < n; ++i) {
    Interval distance[kShapeLandmarkCount];
    double smallest_upper = std::numeric_limits<double>::infinity();
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      distance[k] = square(target_u[i] - landmark_u[k]) + square(target_v[i] - landmark_v[k]);
      smallest_upper = std::min(smallest_upper, distance[k].upper());
    }
    Interval nearest = distance[0];
    for (int k = 1; k < kShapeLandmarkCount; ++k) nearest = min(nearest, distance[k]);
    natural += weights[i] == 1.0 ? nearest : weights[i] * nearest;
    if (weights[i] == 0.0) continue;   // a weightless point contributes no slope
    Interval point_gradient[kDim];
    bool any_active = false;
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      // Certainly farther than another landmark everywhere in the box: never the nearest, never differentiated.
      if (distance[k].lower() > smallest_upper) continue;
      const std::size_t kk = static_cast<std::size_t>(k);
      // d/dL of (L - target)^2 times the chain factor; a unit chain (linear kind, clamp inactive) needs no product.
      Interval along_u = 2.0 * (landmark_u[k] - target_u[i]);
      Interval along_v = 2.0 * (landmark_v[k] - target_v[i]);
      if (!(chain_u[k].lower() == 1.0 && chain_u[k].upper() == 1.0)) along_u = along_u * chain_u[k];
      if (!(chain_v[k].lower() == 1.0 && chain_v[k].upper() == 1.0)) along_v = along_v * chain_v[k];
      for (int p = 0; p < kDim; ++p) {
        const std::size_t pp = static_cast<std::size_t>(p);
        const double cu = u_coefficients[kk][pp], cv = v_coefficients[kk][pp];
        // Zero coefficients (the base landmarks' unused parameters) contribute exactly nothing.
        const Interval slope = cu == 0.0 ? (cv == 0.0 ? Interval(0.0) : cv * along_v)
                                         : (cv == 0.0 ? cu * along_u : cu * along_u + cv * along_v);
        point_gradient[p] = any_active ? boost::numeric::hull(point_gradient[p], slope) : slope;
      }
      any_active = true;
    }
    for (int p = 0; p < kDim; ++p) gradient[p] += weights[i] * point_gradient[p];
    if (!hyperplane_usable) continue;
    int active_count = 0, single = 0;
    for (int k = 0; k < kShapeLandmarkCount; ++k)
      if (distance[k].lower() <= smallest_upper) {
        ++active_count;
        single = k;
      }
    Interval term_gradient[kDim];
    if (active_count == 1 && convex[single]) {
      hyperplane_value += weights[i] * centre_term(i, single, term_gradient);
      for (int p = 0; p < kDim; ++p) hyperplane_gradient[p] += weights[i] * term_gradient[p];
      continue;
    }
    double point_lower = std::numeric_limits<double>::infinity();
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      if (distance[k].lower() > smallest_upper) continue;   // never the nearest in this box
      double bound = distance[k].lower();
      if (convex[k]) {
        Interval plane = centre_term(i, k, term_gradient);
        for (int p = 0; p < kDim; ++p) plane += term_gradient[p] * offset[p];
        bound = std::max(bound, plane.lower());
      }
      point_lower = std::min(point_lower, bound);
    }
    // No candidate at all would mean NaN distances: give up the hyperplane bound rather than add +inf.
    if (!(point_lower < std::numeric_limits<double>::infinity())) {
      hyperplane_usable = false;
      continue;
    }
    separate_lower += weights[i] * Interval(point_lower);
  }
  Interval centred = at_centre;
  for (int p = 0; p < kDim; ++p) centred += gradient[p] * offset[p];
  double lower = std::max(natural.lower(), centred.lower());
  if (hyperplane_usable) {
    Interval plane = hyperplane_value;
    for (int p = 0; p < kDim; ++p) plane += hyperplane_gradient[p] * offset[p];
    plane += separate_lower;
    // NaN (an empty term) fails the comparison and keeps the other bounds.
    if (plane.lower() > lower) lower = plane.lower();
  }
  const double upper = std::min(natural.upper(), centred.upper());
  // Both enclose the error, so they overlap; keep the natural extension should rounding ever say otherwise (or
  // either is empty: NaN bounds fail the comparison).
  if (!(lower <= upper)) return natural;
  return Interval(lower, upper);
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

ShapeFitProblem make_shape_fit_problem(ShapeFitData data) { return ShapeFitProblem(std::move(data)); }

}  // namespace blocklab
