// Multi-template Procrustes ranking (formats/munkberg/shape_fit/procrustes_templates.h): one clustering gives every
// template's candidates (the same transforms as enumerating each template on its own), the ranking is ascending by
// bound, each template keeps its best candidate with per_template, exact fits tie and are kept together, the
// refinement never raises the continuous error, and bad options are errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "core/error.h"
#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "formats/munkberg/shape_fit/procrustes_templates.h"

namespace blocklab {
namespace {

std::vector<ShapeTemplate> three_templates() {
  return {ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{1.0 / 3, 0}, Point2{2.0 / 3, 0}}),
          ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{1, 1}, Point2{0, 1}}),
          ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}})};
}

// Every candidate, unrefined: the whole ranking.
TemplateRankingOptions everything() {
  TemplateRankingOptions options;
  options.kept = 100000;
  options.tie_limit = 0;
  options.per_template = 0;
  options.refined = 0;
  return options;
}

// 16 random points in [0.2, 0.6]^2 with unit weights (distinct, so all four cluster levels exist).
void random_points(std::uint32_t seed, std::vector<Point2>* points, std::vector<double>* weights) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coordinate(0.2, 0.6);
  points->clear();
  for (int i = 0; i < 16; ++i) points->push_back({coordinate(random), coordinate(random)});
  weights->assign(16, 1.0);
}

TEST(ProcrustesTemplates, OneClusteringGivesEveryTemplatesOwnCandidates) {
  std::vector<Point2> points;
  std::vector<double> weights;
  random_points(3, &points, &weights);
  const std::vector<ShapeTemplate> shapes = three_templates();
  const TemplateRankingOptions options = everything();
  const std::vector<TemplateCandidate> ranked = rank_template_candidates(points, weights, shapes, options);
  // Levels 4, 3, 2: 24 + 24 + 12 ordered choices per template; level 1 once (scale 0, the same for every template).
  ASSERT_EQ(ranked.size(), 3u * 60u + 1u);
  for (std::size_t i = 1; i < ranked.size(); ++i)
    EXPECT_LE(ranked[i - 1].candidate.error_bound, ranked[i].candidate.error_bound) << i;
  // The same transforms as enumerating each template's levels on their own.
  const std::vector<PointClustering> levels = procrustes_cluster_levels(points, weights, options.procrustes);
  for (std::size_t t = 0; t < shapes.size(); ++t) {
    std::vector<ProcrustesCandidate> own;
    for (int level = 4; level >= 2; --level)
      append_level_candidates(levels[static_cast<std::size_t>(level - 1)], shapes[t], options.procrustes.svd, &own);
    ASSERT_EQ(own.size(), 60u);
    for (const ProcrustesCandidate& c : own) {
      const auto found = std::find_if(ranked.begin(), ranked.end(), [&](const TemplateCandidate& r) {
        return r.shape == static_cast<int>(t) && r.candidate.base0.u == c.base0.u && r.candidate.base0.v == c.base0.v &&
               r.candidate.base1.u == c.base1.u && r.candidate.base1.v == c.base1.v &&
               r.candidate.error_bound == c.error_bound;
      });
      EXPECT_NE(found, ranked.end()) << "template " << t;
    }
  }
}

TEST(ProcrustesTemplates, PerTemplateKeepsEachTemplatesBestCandidate) {
  std::vector<Point2> points;
  std::vector<double> weights;
  random_points(11, &points, &weights);
  const std::vector<ShapeTemplate> shapes = three_templates();
  const TemplateRankingOptions all_options = everything();
  const std::vector<TemplateCandidate> all = rank_template_candidates(points, weights, shapes, all_options);
  TemplateRankingOptions options = all_options;
  options.kept = 1;
  options.per_template = 1;
  const std::vector<TemplateCandidate> ranked = rank_template_candidates(points, weights, shapes, options);
  ASSERT_GE(ranked.size(), 3u);
  ASSERT_LE(ranked.size(), 4u);   // the overall best, plus each other template's best
  EXPECT_EQ(ranked[0].candidate.error_bound, all[0].candidate.error_bound);
  for (int t = 0; t < 3; ++t) {
    // The template's best bound over all its candidates (level 1 counts for template 0 only).
    double best = 0.0;
    bool have = false;
    for (const TemplateCandidate& c : all)
      if (c.shape == t && (!have || c.candidate.error_bound < best)) {
        best = c.candidate.error_bound;
        have = true;
      }
    const auto found = std::find_if(ranked.begin(), ranked.end(), [&](const TemplateCandidate& r) {
      return r.shape == t && r.candidate.error_bound == best;
    });
    EXPECT_NE(found, ranked.end()) << "template " << t;
  }
  for (std::size_t i = 1; i < ranked.size(); ++i)
    EXPECT_LE(ranked[i - 1].candidate.error_bound, ranked[i].candidate.error_bound);
}

TEST(ProcrustesTemplates, TwoColourBlockKeepsItsTiedExactFits) {
  // Two colours, 8 texels each: every pair of landmarks fits them exactly (bound 0 + zero scatter at level 2).
  std::vector<Point2> points;
  for (int i = 0; i < 16; ++i) points.push_back(i < 8 ? Point2{0.2, 0.3} : Point2{0.5, 0.1});
  const std::vector<double> weights(16, 1.0);
  TemplateRankingOptions options = everything();
  options.kept = 2;
  options.tie_limit = 40;
  const std::vector<TemplateCandidate> ranked = rank_template_candidates(points, weights, three_templates(), options);
  // Far more than 2 candidates tie at ~0: the tie limit keeps them all (up to 2 + 40).
  EXPECT_EQ(ranked.size(), 42u);
  for (const TemplateCandidate& c : ranked) EXPECT_LT(c.candidate.error_bound, 1e-12);
}

TEST(ProcrustesTemplates, RefinementNeverRaisesTheLinearErrorOfACandidate) {
  std::vector<Point2> points;
  std::vector<double> weights;
  random_points(5, &points, &weights);
  const std::vector<ShapeTemplate> shapes = three_templates();
  TemplateRankingOptions plain = everything();
  plain.kept = 6;
  TemplateRankingOptions refined = plain;
  refined.refined = 6;
  const std::vector<TemplateCandidate> a = rank_template_candidates(points, weights, shapes, plain);
  const std::vector<TemplateCandidate> b = rank_template_candidates(points, weights, shapes, refined);
  ASSERT_EQ(a.size(), b.size());
  const auto linear_error = [&](const TemplateCandidate& c) {
    ShapeFitData data;
    data.points = points;
    data.weights = weights;
    data.shape = shapes[static_cast<std::size_t>(c.shape)];
    data.error_kind = ShapeErrorKind::linear;
    const ShapeFitError error = ShapeFitError::from_data(data);
    const double x[4] = {c.candidate.base0.u, c.candidate.base0.v, c.candidate.base1.u, c.candidate.base1.v};
    return error(x);
  };
  int improved = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].shape, b[i].shape);
    if (b[i].candidate.duplicate) continue;
    EXPECT_LE(linear_error(b[i]), linear_error(a[i]) * (1.0 + 1e-12)) << i;
    if (linear_error(b[i]) < linear_error(a[i])) ++improved;
  }
  EXPECT_GT(improved, 0);
}

TEST(ProcrustesTemplates, InvalidInputsAreErrors) {
  std::vector<Point2> points;
  std::vector<double> weights;
  random_points(1, &points, &weights);
  TemplateRankingOptions options;
  EXPECT_THROW(rank_template_candidates(points, weights, {}, options), Error);
  EXPECT_THROW(rank_template_candidates({}, {}, three_templates(), options), Error);
  options.kept = 0;
  EXPECT_THROW(rank_template_candidates(points, weights, three_templates(), options), Error);
  options.kept = 4;
  options.procrustes.max_clusters = 9;
  EXPECT_THROW(rank_template_candidates(points, weights, three_templates(), options), Error);
}

}  // namespace
}  // namespace blocklab
