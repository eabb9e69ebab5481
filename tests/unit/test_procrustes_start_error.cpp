// The start-error screening of the `procrustes` solver's search=start_error (solvers/procrustes/
// start_error_screening.h): the single-precision SIMD start error against a double-precision evaluation of its
// definition (the refinement measure at the base points clamped to [0, 1]^4) and its portable path bit for bit, and
// the refinement order of its keys.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "solvers/procrustes/start_error_screening.h"

namespace blocklab {
namespace {

ShapeTemplate kite() {
  return ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
}

// The definition, in double, written independently of the kernel: landmarks of the clamped base points (the
// template's own decoding, formats/munkberg/shape_fit/shape_fit_problem.h), clamped, mapped; nearest mapped landmark
// per mapped point. `spread` receives sum_i w_i (|du| + |dv|) at the nearest landmarks, the scale of the
// single-precision cancellation in du and dv.
double reference_start_error(const std::vector<Point2>& points, const std::vector<double>& weights, double alpha,
                             const ShapeTemplate& shape, const ProcrustesCandidate& candidate, double* spread) {
  const auto clamp = [](double c) { return std::min(std::max(c, 0.0), 1.0); };
  const auto f = [&](double c) { return alpha == 1.0 ? c : std::pow(std::max(c, kStretchFloor), alpha); };
  const Point2 b0{clamp(candidate.base0.u), clamp(candidate.base0.v)};
  const Point2 b1{clamp(candidate.base1.u), clamp(candidate.base1.v)};
  const Point2 d{b1.u - b0.u, b1.v - b0.v};
  double total = 0.0;
  *spread = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    double nearest = std::numeric_limits<double>::infinity(), nearest_spread = 0.0;
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      const double a = shape.along(k), b = shape.across(k);
      // The rows of formats/munkberg/shape_fit/shape_fit_problem.h, u = (1 - a) u0 + b v0 + a u1 - b v1 and
      // v = -b u0 + (1 - a) v0 + b u1 + a v1, written as u0 + a du - b dv and v0 + a dv + b du.
      const double u = clamp(b0.u + a * d.u - b * d.v), v = clamp(b0.v + a * d.v + b * d.u);
      const double du = f(points[i].u) - f(u), dv = f(points[i].v) - f(v);
      if (du * du + dv * dv < nearest) {
        nearest = du * du + dv * dv;
        nearest_spread = std::abs(du) + std::abs(dv);
      }
    }
    total += weights[i] * nearest;
    *spread += weights[i] * nearest_spread;
  }
  return total;
}

float kernel_start_error(const std::vector<Point2>& points, const std::vector<double>& weights, double alpha,
                         const ShapeTemplate& shape, const ProcrustesCandidate& candidate, bool portable = false) {
  const RefineMeasure measure(alpha);
  std::vector<double> targets(2 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    targets[i] = measure.map(points[i].u);
    targets[points.size() + i] = measure.map(points[i].v);
  }
  StartErrorPoints packed;
  packed.assign(targets, weights);
  return portable ? candidate_start_error_portable(packed, measure, landmark_rows(shape), candidate)
                  : candidate_start_error(packed, measure, landmark_rows(shape), candidate);
}

TEST(ProcrustesStartError, MatchesItsDefinitionInDoubleToSinglePrecision) {
  std::mt19937_64 random(21);
  std::uniform_real_distribution<double> unit(0.0, 1.0), wide(-0.5, 1.5);
  const ShapeTemplate shape = kite();
  int checked = 0;
  for (const double alpha : {1.0, 0.455}) {
    // 1, 5 and 17 points leave partial groups of four (the padding must add nothing); 16 is the block.
    for (const std::size_t count : {1u, 5u, 16u, 17u}) {
      for (int trial = 0; trial < 200; ++trial) {
        std::vector<Point2> points(count);
        std::vector<double> weights(count);
        for (std::size_t i = 0; i < count; ++i) {
          points[i] = {unit(random), unit(random)};
          weights[i] = trial % 5 == 0 && i % 3 == 0 ? 0.0 : 0.25 + 3.0 * unit(random);
        }
        // Base points outside [0, 1] too: the kernel must clamp them (and then the landmarks) first.
        ProcrustesCandidate candidate;
        candidate.base0 = {wide(random), wide(random)};
        candidate.base1 = {wide(random), wide(random)};
        double spread = 0.0;
        const double expected = reference_start_error(points, weights, alpha, shape, candidate, &spread);
        const float actual_float = kernel_start_error(points, weights, alpha, shape, candidate);
        const double actual = actual_float;
        // Single precision: coordinates rounded to 2^-24 (< 1 each) put an error of ~2^-23 on du and dv, so
        // ~2^-22 |du| on du^2 (cancellation: not relative to the term); the products and sums add ~2^-22
        // relative. 2^-20 of both leaves a margin of 4 and still fails a kernel that mixes up a landmark.
        EXPECT_NEAR(actual, expected, 0x1p-20 * (spread + expected))
            << "alpha " << alpha << ", " << count << " points, trial " << trial;
        // The portable path (where SSE2 is missing) does the same operations: the same float.
        const float portable = kernel_start_error(points, weights, alpha, shape, candidate, true);
        EXPECT_EQ(std::memcmp(&portable, &actual_float, sizeof portable), 0)
            << portable << " vs " << actual_float << ", trial " << trial;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 1600);
}

TEST(ProcrustesStartError, ANaNBasePointGivesNaN) {
  const std::vector<Point2> points = {{0.2, 0.3}, {0.6, 0.1}};
  const std::vector<double> weights = {1.0, 1.0};
  ProcrustesCandidate candidate;
  candidate.base0 = {std::nan(""), 0.5};
  candidate.base1 = {0.4, 0.5};
  EXPECT_TRUE(std::isnan(kernel_start_error(points, weights, 1.0, kite(), candidate)));
  EXPECT_TRUE(std::isnan(kernel_start_error(points, weights, 0.455, kite(), candidate)));
  EXPECT_TRUE(std::isnan(kernel_start_error(points, weights, 1.0, kite(), candidate, true)));
}

TEST(ProcrustesStartError, KeysTakeCandidatesByErrorThenIndexWithNaNLast) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::nanf("");
  const std::vector<float> errors = {0.5f, nan, 0.25f, 0.5f, inf, 0.0f, -nan, 1e-30f};
  std::vector<std::uint64_t> keys;
  for (std::size_t i = 0; i < errors.size(); ++i) keys.push_back(start_error_key(errors[i], i));
  std::vector<std::size_t> taken;
  for (std::size_t next = take_lowest_start_error(keys); next != keys.size(); next = take_lowest_start_error(keys))
    taken.push_back(next);
  // 0 < 1e-30 < 0.25 < 0.5 (index 0, then 3) < inf < NaN (either sign, by index).
  const std::vector<std::size_t> expected = {5, 7, 2, 0, 3, 4, 1, 6};
  EXPECT_EQ(taken, expected);
  EXPECT_EQ(take_lowest_start_error(keys), keys.size());   // all taken
}

}  // namespace
}  // namespace blocklab
