// The floor of the stretched shape fit's box enclosure (formats/munkberg/shape_fit/shape_fit_problem.cpp,
// aggregated_floor): the points whose nearest landmark is certain on a box pay at least their scatter about their mean,
// whatever x in the box, convex terms or not. Checked on the box that showed the gap: a near-grey chroma cloud next to
// u = 0 and a large shape whose third landmark crosses u = 0 over the box (a clamped, non-convex coordinate), where the
// enclosure's lower bound was 0.73x the block's optimum while every lattice point of the box is 1.9x or more.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "tests/unit/lattice_box_points.h"

namespace blocklab {
namespace {

// The 16 logYuv chroma points of block 1730 of 2000 spread over memorial.hdr (../shared/data/hdr, the bench's
// block sampling), rounded to 4 decimals: a grey block, u near 0.016.
ShapeFitData near_grey_block() {
  ShapeFitData data;
  data.error_kind = ShapeErrorKind::stretched;
  data.shape = ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
  data.points = {{0.0155, 0.5571}, {0.0154, 0.5588}, {0.0149, 0.5604}, {0.0160, 0.5573},
                 {0.0153, 0.5548}, {0.0163, 0.5565}, {0.0157, 0.5611}, {0.0158, 0.5566},
                 {0.0171, 0.5559}, {0.0148, 0.5619}, {0.0159, 0.5619}, {0.0161, 0.5627},
                 {0.0157, 0.5544}, {0.0163, 0.5510}, {0.0163, 0.5565}, {0.0159, 0.5604}};
  data.weights.assign(data.points.size(), 1.0);
  return data;
}

// sum_i (f(t_i) - mean)^2 over both coordinates, f the stretch: the least error of any one place for all points.
double stretched_scatter(const ShapeFitData& data) {
  double total = 0.0;
  for (int c = 0; c < 2; ++c) {
    std::vector<double> stretched;
    for (const Point2& p : data.points) stretched.push_back(std::pow(c == 0 ? p.u : p.v, data.exponent));
    double mean = 0.0;
    for (double s : stretched) mean += s / static_cast<double>(stretched.size());
    for (double s : stretched) total += (s - mean) * (s - mean);
  }
  return total;
}

TEST(ShapeFitFloorBound, PointsOfOneCertainLandmarkPayAtLeastTheirScatterEvenWhereItsCoordinateIsClamped) {
  const ShapeFitData data = near_grey_block();
  const ShapeFitProblem problem(data);
  const Lattice lattice = shape_fit_lattices(kDefaultShapeLatticeBits)[0];
  // Base points (0.47, 0.41) and (0.13, 0.93), lattice indices: landmark 2 lands on the cloud, its u range over the
  // box crosses 0 (clamped); the other landmarks are far away.
  const std::int64_t lo[4] = {120, 104, 32, 236}, hi[4] = {121, 107, 35, 239};
  std::vector<Interval> box;
  for (int p = 0; p < 4; ++p) box.push_back(Interval(lattice.point(lo[p]), lattice.point(hi[p])));
  const Interval enclosure = problem.eval(box.data());

  const double scatter = stretched_scatter(data);
  EXPECT_GE(enclosure.lower(), scatter * (1.0 - 1e-9));
  // Still an enclosure: every lattice point of the box lies inside it.
  for_each_lattice_point(lattice, lo, hi, [&](const double* x) {
    const double value = problem.eval(x);
    EXPECT_GE(value, enclosure.lower());
    EXPECT_LE(value, enclosure.upper());
  });
}

}  // namespace
}  // namespace blocklab
