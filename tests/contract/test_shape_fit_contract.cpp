// The Problem contract (tests/contract/problem_contract.h) on the 2D chroma shape fit
// (formats/munkberg/shape_fit/shape_fit_problem.h), for both error kinds of Munkberg et al. 2008 (eq. 11 linear,
// section 7.2 stretched), on random and on clustered chroma point sets, with unit and non-uniform weights.
#include <gtest/gtest.h>

#include <random>

#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "tests/contract/problem_contract.h"

namespace blocklab {
namespace {

ShapeFitData block(std::uint64_t seed, ShapeErrorKind kind, bool weighted, bool clustered) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> spread(0.0, 0.02);
  ShapeFitData data;
  data.shape = ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.5, 0.7}, Point2{0.3, -0.4}});
  data.error_kind = kind;
  const Point2 centres[3] = {{0.2, 0.3}, {0.35, 0.25}, {0.25, 0.45}};
  for (int i = 0; i < 16; ++i) {
    Point2 p = clustered ? centres[i % 3] : Point2{unit(random), unit(random)};
    if (clustered) {
      p.u = std::min(1.0, std::max(0.0, p.u + spread(random)));
      p.v = std::min(1.0, std::max(0.0, p.v + spread(random)));
    }
    data.points.push_back(p);
    if (weighted) data.weights.push_back(0.1 + 2.0 * unit(random));
  }
  return data;
}

TEST(ShapeFitContract, LinearErrorOnRandomPointsHoldsTheContract) {
  contract::check_problem_contract(ShapeFitProblem(block(1, ShapeErrorKind::linear, false, false)));
}

TEST(ShapeFitContract, LinearErrorOnWeightedClusteredPointsHoldsTheContract) {
  contract::check_problem_contract(ShapeFitProblem(block(2, ShapeErrorKind::linear, true, true)));
}

TEST(ShapeFitContract, StretchedErrorOnRandomPointsHoldsTheContract) {
  contract::check_problem_contract(ShapeFitProblem(block(3, ShapeErrorKind::stretched, false, false)));
}

TEST(ShapeFitContract, StretchedErrorOnWeightedClusteredPointsHoldsTheContract) {
  contract::check_problem_contract(ShapeFitProblem(block(4, ShapeErrorKind::stretched, true, true)));
}

TEST(ShapeFitContract, PlainAdapterOfTheFunctorHoldsTheContract) {
  const ShapeFitData data = block(5, ShapeErrorKind::stretched, true, false);
  contract::check_problem_contract(make_problem(ShapeFitError::from_data(data), shape_fit_bounds(), shape_fit_lattices(8)));
}

}  // namespace
}  // namespace blocklab
