// The pair bound of the shape fit's box enclosure (formats/munkberg/shape_fit/shape_fit_pair_bound.h): its closed form
// on hand-made landmark differences, and the enclosure it joins checked against every lattice point of small boxes
// around small shapes, the boxes where it is what discards them (points with several possibly-nearest landmarks).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "formats/munkberg/shape_fit/shape_fit_pair_bound.h"
#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "tests/unit/lattice_box_points.h"

namespace blocklab {
namespace {

using shape_fit_detail::LandmarkDifferences;
using shape_fit_detail::pair_lower_bound;

ShapeFitError two_point_error(Point2 a, Point2 b, double wa, double wb) {
  ShapeFitData data;
  data.points = {a, b};
  data.weights = {wa, wb};
  return ShapeFitError::from_data(data);
}

// Every landmark difference enclosed by [lower, upper] in both coordinates (k == l stays exactly 0).
LandmarkDifferences differences_within(double lower, double upper) {
  LandmarkDifferences differences;
  for (int k = 0; k < kShapeLandmarkCount; ++k)
    for (int l = k + 1; l < kShapeLandmarkCount; ++l) {
      differences.set(k, l, true, lower, upper);
      differences.set(k, l, false, lower, upper);
    }
  return differences;
}

const double kNoNaturalBound[kShapeLandmarkCount] = {0.0, 0.0, 0.0, 0.0};

TEST(ShapeFitPairBound, TwoPointsOnOneLandmarkPayHalfTheirSquaredDistance) {
  // Landmark differences pinned at 0: whichever landmarks the two points take, they sit on one place.
  const ShapeFitError error = two_point_error({0.2, 0.3}, {0.5, 0.7}, 1.0, 1.0);
  const double bound = pair_lower_bound(error, 0, 1, kNoNaturalBound, kNoNaturalBound, differences_within(0.0, 0.0));
  const double exact = 0.5 * (0.3 * 0.3 + 0.4 * 0.4);
  EXPECT_LE(bound, exact);
  EXPECT_NEAR(bound, exact, 1e-15);
}

TEST(ShapeFitPairBound, WeightsGiveTheHarmonicFactor) {
  // w_i w_j / (w_i + w_j) = 1 * 3 / 4.
  const ShapeFitError error = two_point_error({0.1, 0.1}, {0.1, 0.6}, 1.0, 3.0);
  const double bound = pair_lower_bound(error, 0, 1, kNoNaturalBound, kNoNaturalBound, differences_within(0.0, 0.0));
  EXPECT_LE(bound, 0.75 * 0.25);
  EXPECT_NEAR(bound, 0.75 * 0.25, 1e-15);
}

TEST(ShapeFitPairBound, DifferencesThatReachTheTargetsLeaveTheNaturalBoundsOnly) {
  // Distinct landmarks may be 0.5 apart either way: t_i - t_j = (-0.3, -0.4) is reachable, so only k == l couples
  // the pair; its natural bounds make the best (k, l) choice k != l with the smallest natural sum.
  const ShapeFitError error = two_point_error({0.2, 0.3}, {0.5, 0.7}, 1.0, 1.0);
  const double i_lower[kShapeLandmarkCount] = {0.01, 0.02, 0.03, 0.04};
  const double j_lower[kShapeLandmarkCount] = {0.005, 0.03, 0.02, 0.01};
  const double bound = pair_lower_bound(error, 0, 1, i_lower, j_lower, differences_within(-0.5, 0.5));
  // k = 0 with l = 3: 0.01 + 0.01 = 0.02 (k = l = 0 would be max(0.015, 0.125)).
  EXPECT_LE(bound, 0.02);
  EXPECT_NEAR(bound, 0.02, 1e-15);
}

TEST(ShapeFitPairBound, CouplingOutweighsSmallNaturalBounds) {
  // Landmarks at most 0.1 apart in each coordinate, the points 0.3 / 0.4 apart: every (k, l) pays at least
  // 0.5 (0.2^2 + 0.3^2), far above the natural bounds.
  const ShapeFitError error = two_point_error({0.2, 0.3}, {0.5, 0.7}, 1.0, 1.0);
  const double i_lower[kShapeLandmarkCount] = {0.001, 0.001, 0.001, 0.001};
  const double bound = pair_lower_bound(error, 0, 1, i_lower, i_lower, differences_within(-0.1, 0.1));
  const double exact = 0.5 * (0.2 * 0.2 + 0.3 * 0.3);
  EXPECT_LE(bound, exact);
  EXPECT_NEAR(bound, exact, 1e-15);
}

// A block whose chroma spreads over a few lattice steps around (cu, cv): the small shapes where every point has
// several possibly-nearest landmarks on most boxes.
ShapeFitData small_shape_block(std::mt19937_64& random, ShapeErrorKind kind, bool weighted) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ShapeFitData data;
  data.error_kind = kind;
  data.shape = ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
  const double cu = 0.05 + 0.8 * unit(random), cv = 0.05 + 0.8 * unit(random), spread = 0.004 + 0.03 * unit(random);
  for (int i = 0; i < 16; ++i) {
    data.points.push_back({std::clamp(cu + spread * (unit(random) - 0.5), 0.0, 1.0),
                           std::clamp(cv + spread * (unit(random) - 0.5), 0.0, 1.0)});
    if (weighted) data.weights.push_back(unit(random) < 0.1 ? 0.0 : 0.2 + 2.0 * unit(random));
  }
  return data;
}

// Every lattice point of boxes of 1-6 lattice steps per side placed over a small shape's points lies above the
// enclosure's lower bound (interval_bb's boxes: lattice index ranges), for both error kinds, with unit and uneven
// weights, including weightless points.
TEST(ShapeFitPairBound, EnclosureStaysBelowEveryLatticePointOfSmallBoxesOverSmallShapes) {
  std::mt19937_64 random(41);
  const Lattice lattice = shape_fit_lattices(kDefaultShapeLatticeBits)[0];
  std::uniform_int_distribution<int> span(0, 5);
  int checked = 0;
  for (const ShapeErrorKind kind : {ShapeErrorKind::linear, ShapeErrorKind::stretched})
    for (int b = 0; b < 40; ++b) {
      const ShapeFitData data = small_shape_block(random, kind, b % 2 == 1);
      const ShapeFitProblem problem(data);
      for (int box_index = 0; box_index < 5; ++box_index) {
        std::int64_t lo[4], hi[4];
        for (int p = 0; p < 4; ++p) {
          const double centre = p % 2 == 0 ? data.points[0].u : data.points[0].v;
          const std::int64_t start = std::clamp<std::int64_t>(lattice.nearest_index(centre) - span(random), 0, 250);
          lo[p] = start;
          hi[p] = std::min<std::int64_t>(start + span(random), lattice.count - 1);
        }
        std::vector<Interval> box(4);
        for (int p = 0; p < 4; ++p)
          box[static_cast<std::size_t>(p)] = Interval(lattice.point(lo[p]), lattice.point(hi[p]));
        const Interval enclosure = problem.eval(box.data());
        for_each_lattice_point(lattice, lo, hi, [&](const double* x) {
          const double value = problem.eval(x);
          ++checked;
          ASSERT_GE(value, enclosure.lower()) << to_string(kind) << " block " << b << " box " << box_index;
          ASSERT_LE(value, enclosure.upper()) << to_string(kind) << " block " << b << " box " << box_index;
        });
      }
    }
  EXPECT_GT(checked, 10000);
}

}  // namespace
}  // namespace blocklab
