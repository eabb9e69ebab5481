// The tabulated closed-form fits of every landmark correspondence of a cluster level (solvers/procrustes/
// correspondence_fits.h, option svd=tables) against fit_weighted_similarity's closed form, fit by fit, and on the
// degenerate inputs the closed form documents (all weights 0, one weighted cluster, one cluster).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "solvers/procrustes/correspondence_fits.h"
#include "solvers/procrustes/weighted_procrustes.h"

namespace blocklab {
namespace {

ShapeTemplate kite() {
  return ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
}

SimilarityFit reference_fit(const std::vector<Point2>& centres, const std::vector<double>& weights,
                            const ShapeTemplate& shape, const std::vector<int>& choice) {
  std::vector<Point2> sources;
  for (const int l : choice) sources.push_back(shape.normalised_landmark(l));
  return fit_weighted_similarity(sources.data(), centres.data(), weights.data(), static_cast<int>(centres.size()),
                                 ProcrustesMethod::closed_form);
}

// Same transform up to rounding. Centres are in [0, 1]; when two matched landmarks are close (random templates) the
// scale |z| grows and the sums lose digits in proportion, hence 1e-12 x (1 + |z|)^2: ~4,500 ulps of 1 for the
// kite's O(1) scales, and still far below any wrong term.
void expect_same_fit(const SimilarityFit& actual, const SimilarityFit& expected, const std::string& where) {
  const double scale = std::hypot(expected.scale_cos, expected.scale_sin);
  const double tolerance = 1e-12 * (1.0 + scale) * (1.0 + scale);
  EXPECT_NEAR(actual.scale_cos, expected.scale_cos, tolerance) << where;
  EXPECT_NEAR(actual.scale_sin, expected.scale_sin, tolerance) << where;
  EXPECT_NEAR(actual.translation.u, expected.translation.u, tolerance) << where;
  EXPECT_NEAR(actual.translation.v, expected.translation.v, tolerance) << where;
  EXPECT_NEAR(actual.residual, expected.residual, tolerance) << where;
}

TEST(CorrespondenceFits, EveryCorrespondenceMatchesTheClosedForm) {
  std::mt19937_64 random(31);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int fits = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // The kite, and random templates (landmarks 0 and 1 fixed by the base-point convention).
    const ShapeTemplate shape =
        trial % 3 == 0 ? kite()
                       : ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0},
                                                        Point2{2 * unit(random) - 0.5, 2 * unit(random) - 1.0},
                                                        Point2{2 * unit(random) - 0.5, 2 * unit(random) - 1.0}});
    for (int count = 1; count <= kShapeLandmarkCount; ++count) {
      std::vector<Point2> centres(static_cast<std::size_t>(count));
      std::vector<double> weights(static_cast<std::size_t>(count));
      for (int j = 0; j < count; ++j) {
        centres[static_cast<std::size_t>(j)] = {unit(random), unit(random)};
        // Cluster weights are point counts (or sums of texel weights); a zero-weight cluster now and then.
        weights[static_cast<std::size_t>(j)] = trial % 7 == 0 && j == 1 ? 0.0 : 1.0 + std::floor(8 * unit(random));
      }
      const CorrespondenceFits tables(centres.data(), weights.data(), count, shape);
      // Every ordered choice of `count` distinct landmarks: prefixes of the permutations.
      std::vector<int> permutation = {0, 1, 2, 3};
      do {
        const std::vector<int> choice(permutation.begin(), permutation.begin() + count);
        expect_same_fit(tables.fit(choice.data()), reference_fit(centres, weights, shape, choice),
                        "trial " + std::to_string(trial) + ", " + std::to_string(count) + " clusters");
        ++fits;
        // Skip the permutations that repeat this prefix.
        std::sort(permutation.begin() + count, permutation.end(), std::greater<int>());
      } while (std::next_permutation(permutation.begin(), permutation.end()));
    }
  }
  EXPECT_EQ(fits, 300 * (4 + 12 + 24 + 24));
}

TEST(CorrespondenceFits, AllWeightsZeroGiveScaleZeroAtThePlainMean) {
  const std::vector<Point2> centres = {{0.2, 0.4}, {0.6, 0.8}, {0.1, 0.3}};
  const std::vector<double> weights = {0.0, 0.0, 0.0};
  const CorrespondenceFits tables(centres.data(), weights.data(), 3, kite());
  const int choice[3] = {2, 0, 3};
  const SimilarityFit fit = tables.fit(choice);
  EXPECT_EQ(fit.scale_cos, 0.0);
  EXPECT_EQ(fit.scale_sin, 0.0);
  EXPECT_NEAR(fit.translation.u, 0.3, 1e-15);
  EXPECT_NEAR(fit.translation.v, 0.5, 1e-15);
  expect_same_fit(fit, reference_fit(centres, weights, kite(), {2, 0, 3}), "all weights 0");
}

// One cluster, or one cluster carrying all the weight: the weighted sources coincide, scale and rotation are
// undetermined, and the minimum-norm answer is scale 0 at that centre (the closed form's rule).
TEST(CorrespondenceFits, CoincidentWeightedSourcesGiveScaleZeroAtTheWeightedMean) {
  const std::vector<Point2> one = {{0.7, 0.2}};
  const std::vector<double> one_weight = {5.0};
  const int first[1] = {3};
  const SimilarityFit single = CorrespondenceFits(one.data(), one_weight.data(), 1, kite()).fit(first);
  EXPECT_EQ(single.scale_cos, 0.0);
  EXPECT_EQ(single.scale_sin, 0.0);
  EXPECT_EQ(single.translation.u, 0.7);
  EXPECT_EQ(single.translation.v, 0.2);
  EXPECT_EQ(single.residual, 0.0);

  const std::vector<Point2> centres = {{0.7, 0.2}, {0.1, 0.9}};
  const std::vector<double> weights = {0.0, 4.0};
  const int choice[2] = {1, 2};
  const SimilarityFit fit = CorrespondenceFits(centres.data(), weights.data(), 2, kite()).fit(choice);
  EXPECT_EQ(fit.scale_cos, 0.0);
  EXPECT_EQ(fit.scale_sin, 0.0);
  EXPECT_NEAR(fit.translation.u, 0.1, 1e-15);
  EXPECT_NEAR(fit.translation.v, 0.9, 1e-15);
  expect_same_fit(fit, reference_fit(centres, weights, kite(), {1, 2}), "one weighted cluster");
}

}  // namespace
}  // namespace blocklab
