// The 2D chroma shape-fit problem (formats/munkberg/shape_fit/shape_fit_problem.h; Munkberg et al. 2008 sections 7.1
// and 7.2): template frames, the base-point parameterisation, both error kinds against independent plain-double code,
// the lattice and input validation. The Problem contract itself runs in tests/contract/test_shape_fit_contract.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include "core/error.h"
#include "formats/munkberg/shape_fit/shape_fit_problem.h"

namespace blocklab {
namespace {

// The 8-bit storage value k (origin + k * step: not always bit-equal to k / 255.0).
double q8(int k) { return Lattice::uniform(0.0, 1.0, 256).point(k); }

// A kite: base points (0,0) and (1,0), a third landmark above, a fourth below and behind.
ShapeTemplate kite() { return ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.5, 0.6}, Point2{-0.25, -0.3}}); }

// Eq. 11 with weights, written out independently: landmarks by rotating and scaling the template directly
// (complex multiplication), clamped, optional stretch, nearest landmark per point.
double independent_error(const ShapeFitData& data, const std::array<Point2, 4>& template_points, const double* x) {
  const double du = x[2] - x[0], dv = x[3] - x[1];
  // Template frame: t0 -> B0, t1 -> B1; z = (B1 - B0) / (t1 - t0) as complex numbers.
  const double tu = template_points[1].u - template_points[0].u, tv = template_points[1].v - template_points[0].v;
  const double norm = tu * tu + tv * tv;
  const double zr = (du * tu + dv * tv) / norm, zi = (dv * tu - du * tv) / norm;
  const auto f = [&](double c) {
    c = std::min(std::max(c, 0.0), 1.0);
    return data.error_kind == ShapeErrorKind::stretched ? std::pow(std::max(c, kStretchFloor), data.exponent) : c;
  };
  double total = 0.0;
  for (std::size_t i = 0; i < data.points.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (const Point2& t : template_points) {
      const double ru = t.u - template_points[0].u, rv = t.v - template_points[0].v;
      const double lu = x[0] + zr * ru - zi * rv, lv = x[1] + zi * ru + zr * rv;
      const double pu = data.error_kind == ShapeErrorKind::stretched ? std::pow(std::max(data.points[i].u, kStretchFloor), data.exponent) : data.points[i].u;
      const double pv = data.error_kind == ShapeErrorKind::stretched ? std::pow(std::max(data.points[i].v, kStretchFloor), data.exponent) : data.points[i].v;
      best = std::min(best, (pu - f(lu)) * (pu - f(lu)) + (pv - f(lv)) * (pv - f(lv)));
    }
    total += (data.weights.empty() ? 1.0 : data.weights[i]) * best;
  }
  return total;
}

ShapeFitData random_data(std::mt19937_64& random, ShapeErrorKind kind, bool weighted) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ShapeFitData data;
  data.shape = kite();
  data.error_kind = kind;
  for (int i = 0; i < 16; ++i) {
    data.points.push_back({unit(random), unit(random)});
    if (weighted) data.weights.push_back(unit(random) * 2.0);
  }
  return data;
}

TEST(ShapeTemplate, BaseLandmarksHaveCanonicalCoefficients) {
  const ShapeTemplate shape = ShapeTemplate::from_landmarks({Point2{0.2, 0.1}, Point2{0.2, 0.9}, Point2{0.6, 0.5}, Point2{0.2, 0.5}});
  EXPECT_EQ(shape.along(0), 0.0);
  EXPECT_EQ(shape.across(0), 0.0);
  EXPECT_EQ(shape.along(1), 1.0);
  EXPECT_EQ(shape.across(1), 0.0);
  // Base direction is +v (length 0.8); landmark 2 lies halfway along it and 0.4 to the clockwise side, i.e. at
  // -0.5 across (perp of +v points to -u).
  EXPECT_NEAR(shape.along(2), 0.5, 1e-15);
  EXPECT_NEAR(shape.across(2), -0.5, 1e-15);
  EXPECT_NEAR(shape.along(3), 0.5, 1e-15);
  EXPECT_NEAR(shape.across(3), 0.0, 1e-15);
}

TEST(ShapeTemplate, LandmarksForReproducesASimilarityOfTheTemplate) {
  const ShapeTemplate shape = kite();
  // Rotate by 90 degrees and scale by 0.5 around B0 = (0.3, 0.2): B1 = (0.3, 0.7).
  const auto landmarks = shape.landmarks_for({0.3, 0.2}, {0.3, 0.7});
  EXPECT_NEAR(landmarks[2].u, 0.3 - 0.3, 1e-15);   // (0.5, 0.6) -> 0.5 * (-0.6, 0.5) + B0
  EXPECT_NEAR(landmarks[2].v, 0.2 + 0.25, 1e-15);
  EXPECT_NEAR(landmarks[3].u, 0.3 + 0.15, 1e-15);  // (-0.25, -0.3) -> 0.5 * (0.3, -0.25) + B0
  EXPECT_NEAR(landmarks[3].v, 0.2 - 0.125, 1e-15);
}

TEST(ShapeTemplate, RejectsCoincidentBaseLandmarksAndBadCoefficients) {
  EXPECT_THROW(ShapeTemplate::from_landmarks({Point2{0.5, 0.5}, Point2{0.5, 0.5}, Point2{0, 0}, Point2{1, 1}}), Error);
  EXPECT_THROW(ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{NAN, 0}, Point2{1, 1}}), Error);
  EXPECT_THROW(ShapeTemplate::from_coefficients({0, 0.5, 1, 1}, {0, 0, 1, -1}), Error);
  EXPECT_NO_THROW(ShapeTemplate::from_coefficients({0, 1, 1, 0}, {0, 0, 1, 1}));
}

TEST(ShapeErrorKind, RoundTripsThroughStringsAndRejectsUnknownNames) {
  EXPECT_EQ(shape_error_kind_from_string(to_string(ShapeErrorKind::linear)), ShapeErrorKind::linear);
  EXPECT_EQ(shape_error_kind_from_string(to_string(ShapeErrorKind::stretched)), ShapeErrorKind::stretched);
  try {
    shape_error_kind_from_string("gamma");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("linear, stretched"), std::string::npos) << e.what();
  }
}

TEST(ShapeFitProblem, LinearErrorMatchesIndependentComputationAtRandomPoints) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const ShapeFitData data = random_data(random, ShapeErrorKind::linear, trial % 2 == 1);
    const ShapeFitProblem problem(data);
    const std::array<Point2, 4> template_points = {Point2{0, 0}, Point2{1, 0}, Point2{0.5, 0.6}, Point2{-0.25, -0.3}};
    for (int k = 0; k < 20; ++k) {
      const double x[4] = {unit(random), unit(random), unit(random), unit(random)};
      const double expected = independent_error(data, template_points, x);
      EXPECT_NEAR(problem.eval(x), expected, 1e-12 * (1.0 + expected));
    }
  }
}

TEST(ShapeFitProblem, StretchedErrorMatchesIndependentComputationAtRandomPoints) {
  std::mt19937_64 random(12);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    ShapeFitData data = random_data(random, ShapeErrorKind::stretched, trial % 2 == 1);
    data.exponent = trial % 3 == 0 ? 0.455 : 0.3 + 0.6 * unit(random);
    const ShapeFitProblem problem(data);
    const std::array<Point2, 4> template_points = {Point2{0, 0}, Point2{1, 0}, Point2{0.5, 0.6}, Point2{-0.25, -0.3}};
    for (int k = 0; k < 20; ++k) {
      const double x[4] = {unit(random), unit(random), unit(random), unit(random)};
      const double expected = independent_error(data, template_points, x);
      EXPECT_NEAR(problem.eval(x), expected, 1e-12 * (1.0 + expected));
    }
  }
}

// The stretched point error reads the stretch of lattice coordinates from LatticeStretch: the table must be std::pow's
// value bit for bit on every lattice point of every supported lattice, and off the lattice it computes the same.
TEST(LatticeStretch, IsTheStretchBitForBitOnAndOffTheLattice) {
  for (const double alpha : {0.455, 0.1, 1.0})
    for (int bits = 1; bits <= LatticeStretch::kMaxBits; ++bits) {
      const LatticeStretch* table = shared_lattice_stretch(alpha, bits);
      ASSERT_NE(table, nullptr);
      EXPECT_EQ(shared_lattice_stretch(alpha, bits), table) << "built once";
      const Lattice lattice = shape_fit_lattices(bits)[0];
      for (std::int64_t i = 0; i < lattice.count; ++i) {
        const double c = lattice.point(i);
        ASSERT_EQ((*table)(c), ShapeFitError::stretch(c, alpha)) << "alpha " << alpha << " bits " << bits << " i " << i;
        // Off the lattice: just above each point, and values outside [0, 1].
        const double off = std::nextafter(c, 2.0);
        EXPECT_EQ((*table)(off), ShapeFitError::stretch(off, alpha));
      }
      for (const double c : {-0.0, -1e-9, 1.5, 0.5 / static_cast<double>(lattice.count)})
        EXPECT_EQ((*table)(c), ShapeFitError::stretch(c, alpha)) << c;
      EXPECT_TRUE(std::isnan((*table)(std::nan(""))));
    }
  EXPECT_EQ(shared_lattice_stretch(0.455, LatticeStretch::kMaxBits + 1), nullptr);   // larger lattices: std::pow
}

// Problem::eval_below, what interval_bb's leaves, lattice_polish and procrustes ask with their incumbent's error.
TEST(ShapeFitProblem, EvalBelowIsTheErrorBitForBitBelowTheBoundAndAtLeastTheBoundOtherwise) {
  std::mt19937_64 random(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int stopped_early = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const ShapeFitData data =
        random_data(random, trial % 2 == 0 ? ShapeErrorKind::linear : ShapeErrorKind::stretched, trial % 4 >= 2);
    const ShapeFitProblem problem(data);
    for (int k = 0; k < 20; ++k) {
      const double x[4] = {unit(random), unit(random), unit(random), unit(random)};
      const double exact = problem.eval(x);
      EXPECT_EQ(problem.eval_below(x, std::numeric_limits<double>::infinity()), exact);
      EXPECT_EQ(problem.eval_below(x, std::nextafter(exact, 1e300)), exact);   // just above: the full sum
      for (const double fraction : {1.0, 0.5, 0.05}) {
        const double bound = exact * fraction;
        const double partial = problem.eval_below(x, bound);
        EXPECT_GE(partial, bound);
        EXPECT_LE(partial, exact);   // a partial sum of the same non-negative terms
        if (partial < exact) ++stopped_early;
      }
    }
  }
  EXPECT_GT(stopped_early, 100);   // the early exit is really taken, not just allowed
}

// A functor without an eval_below method.
struct Quadratic {
  static constexpr int kDim = 2;
  template <typename T>
  T operator()(const T* x) const { return x[0] * x[0] + 3.0 * x[1] * x[1]; }
};

// An error functor without its own eval_below gets the full error from the adapter, whatever the bound.
TEST(ErrorProblem, EvalBelowWithoutAFunctorEarlyExitIsTheFullError) {
  const auto problem = make_problem(Quadratic{}, Bounds{{-1.0, -1.0}, {1.0, 1.0}});
  const double x[2] = {0.5, -0.25};
  EXPECT_EQ(problem.eval_below(x, 0.0), problem.eval(x));
  EXPECT_EQ(problem.eval_below(x, 1e-9), 0.4375);
}

TEST(ShapeFitProblem, PointsOnTheDecodedTemplateHaveZeroErrorInBothKinds) {
  const double x[4] = {q8(40), q8(60), q8(170), q8(90)};
  for (const ShapeErrorKind kind : {ShapeErrorKind::linear, ShapeErrorKind::stretched}) {
    ShapeFitData data;
    data.shape = kite();
    data.error_kind = kind;
    data.points = {Point2{0.5, 0.5}};   // placeholder to build the decoder
    const auto landmarks = ShapeFitProblem(data).decoded_landmarks(x);
    data.points.clear();
    for (int i = 0; i < 16; ++i) data.points.push_back(landmarks[static_cast<std::size_t>(i % 4)]);
    const ShapeFitProblem problem(data);
    EXPECT_EQ(problem.eval(x), 0.0) << to_string(kind);
  }
}

TEST(ShapeFitProblem, LandmarksOutsideTheUnitSquareAreClamped) {
  ShapeFitData data;
  data.shape = ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{2, 0}, Point2{-1, 0}});
  data.points = {Point2{1.0, 0.5}, Point2{0.0, 0.5}};
  const ShapeFitProblem problem(data);
  // Base points (0.25, 0.5), (0.75, 0.5): landmarks 2 and 3 at u = 1.25 and -0.25, clamped to 1 and 0.
  const double x[4] = {0.25, 0.5, 0.75, 0.5};
  const auto landmarks = problem.decoded_landmarks(x);
  EXPECT_EQ(landmarks[2].u, 1.0);
  EXPECT_EQ(landmarks[3].u, 0.0);
  EXPECT_EQ(problem.eval(x), 0.0);
}

TEST(ShapeFitProblem, WeightsScaleEachPointsContribution) {
  ShapeFitData data;
  data.points = {Point2{0.1, 0.1}, Point2{0.9, 0.9}};
  data.weights = {3.0, 0.0};
  const ShapeFitProblem problem(data);
  // Unit square template, B0 = B1 = (0.2, 0.1): every landmark at (0.2, 0.1); point 0 is 0.1 away, weight 3.
  const double x[4] = {0.2, 0.1, 0.2, 0.1};
  EXPECT_NEAR(problem.eval(x), 3.0 * 0.01, 1e-16);
  EXPECT_EQ(problem.fit_weights(), (std::vector<double>{3.0, 0.0}));
}

TEST(ShapeFitProblem, ExposesThePointSetAndTheStorageLattice) {
  ShapeFitData data;
  data.points = {Point2{0.25, 0.75}};
  data.lattice_bits = 5;
  const ShapeFitProblem problem(data);
  const Problem& as_problem = problem;
  const LandmarkFitView fit = as_problem.landmark_fit();
  ASSERT_TRUE(fit.available());
  EXPECT_EQ(fit.points, &problem.fit_points());
  EXPECT_EQ(*fit.weights, std::vector<double>{1.0});
  EXPECT_EQ(fit.exponent, 1.0);                     // the linear error: no stretch
  EXPECT_EQ(fit.stretched_u, nullptr);
  EXPECT_EQ(fit.landmarks.along(2), data.shape.along(2));
  EXPECT_EQ(fit.landmarks.across(3), data.shape.across(3));
  EXPECT_EQ(problem.dim(), 4);
  EXPECT_EQ(problem.fit_weights(), std::vector<double>{1.0});
  EXPECT_EQ(problem.fit_points().size(), 1u);
  for (int p = 0; p < 4; ++p) {
    EXPECT_EQ(problem.lattice(p).count, 32);
    EXPECT_EQ(problem.lattice(p).point(31), 1.0);
    EXPECT_EQ(problem.lower(p), 0.0);
    EXPECT_EQ(problem.upper(p), 1.0);
  }
  EXPECT_FALSE(problem.is_smooth());
  EXPECT_EQ(problem.residual_count(), 0);
  // The plain adapter built from the same data evaluates identically.
  const auto adapter = make_problem(ShapeFitError::from_data(data), shape_fit_bounds(), shape_fit_lattices(5));
  const double x[4] = {0.1, 0.2, 0.7, 0.4};
  EXPECT_EQ(adapter.eval(x), problem.eval(x));
}

void expect_error_mentions(const ShapeFitData& data, const std::string& text) {
  try {
    const ShapeFitProblem problem(data);
    ADD_FAILURE() << "no error for " << text;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(ShapeFitProblem, InvalidDataIsAnErrorNamingTheField) {
  ShapeFitData good;
  good.points = {Point2{0.5, 0.5}, Point2{0.2, 0.3}};
  ShapeFitData data = good;
  data.points.clear();
  expect_error_mentions(data, "points: no point");
  data = good;
  data.points[1].u = 1.5;
  expect_error_mentions(data, "points[1]");
  data = good;
  data.points[0].v = std::nan("");
  expect_error_mentions(data, "points[0]");
  data = good;
  data.weights = {1.0};
  expect_error_mentions(data, "weights: 1 weights for 2 points");
  data = good;
  data.weights = {1.0, -1.0};
  expect_error_mentions(data, "weights[1]");
  data = good;
  data.exponent = 0.0;
  expect_error_mentions(data, "exponent");
  data = good;
  data.lattice_bits = 0;
  expect_error_mentions(data, "lattice_bits");
  data = good;
  data.lattice_bits = 25;
  expect_error_mentions(data, "lattice_bits");
}

}  // namespace
}  // namespace blocklab
