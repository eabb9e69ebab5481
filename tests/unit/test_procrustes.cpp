// The `procrustes` solver and its parts (solvers/procrustes/): weighted 2D Procrustes against the closed-form
// complex least-squares solution, reflection exclusion and degenerate inputs; PNN + k-means clustering; the solver
// on certified problems (points on a transformed template, constant block, two colours, one outlier), against the
// exhaustive optimum on coarse lattices, determinism, thread safety and its refusal of problems without the
// landmark-fit capability; the 16-point PNN scan against the row-wise PNN, search=screened and
// search=start_error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"
#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "solvers/exhaustive/exhaustive_solver.h"
#include "solvers/procrustes/point_clustering.h"
#include "solvers/procrustes/procrustes_screening.h"
#include "solvers/procrustes/procrustes_solver.h"
#include "solvers/procrustes/weighted_procrustes.h"
#include "solvers/registry.h"
#include "tests/contract/example_problems.h"

namespace blocklab {
namespace {

// The 8-bit storage value k (origin + k * step: not always bit-equal to k / 255.0).
double q8(int k) { return Lattice::uniform(0.0, 1.0, 256).point(k); }

ShapeTemplate kite() {
  return ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
}

// ---- weighted Procrustes ----------------------------------------------------------------------------------------

// Independent reference: minimise sum w |c - (z s + t)|^2 over complex z, t (a similarity without reflection):
// z = sum w conj(S) C / sum w |S|^2 on the centred sets.
SimilarityFit complex_reference(const std::vector<Point2>& source, const std::vector<Point2>& target,
                                const std::vector<double>& w) {
  using C = std::complex<double>;
  double total = 0;
  C ms = 0, mt = 0;
  for (std::size_t j = 0; j < source.size(); ++j) {
    total += w[j];
    ms += w[j] * C(source[j].u, source[j].v);
    mt += w[j] * C(target[j].u, target[j].v);
  }
  ms /= total;
  mt /= total;
  C numerator = 0;
  double denominator = 0;
  for (std::size_t j = 0; j < source.size(); ++j) {
    const C s = C(source[j].u, source[j].v) - ms, t = C(target[j].u, target[j].v) - mt;
    numerator += w[j] * std::conj(s) * t;
    denominator += w[j] * std::norm(s);
  }
  const C z = numerator / denominator, translation = mt - z * ms;
  SimilarityFit fit;
  fit.scale_cos = z.real();
  fit.scale_sin = z.imag();
  fit.translation = {translation.real(), translation.imag()};
  for (std::size_t j = 0; j < source.size(); ++j)
    fit.residual += w[j] * std::norm(C(target[j].u, target[j].v) - z * C(source[j].u, source[j].v) - translation);
  return fit;
}

TEST(WeightedProcrustes, MatchesTheComplexLeastSquaresSolutionOnRandomInputs) {
  std::mt19937_64 random(1);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int count = 2 + trial % 3;
    std::vector<Point2> source, target;
    std::vector<double> w;
    for (int j = 0; j < count; ++j) {
      source.push_back({unit(random), unit(random)});
      target.push_back({unit(random), unit(random)});
      w.push_back(0.1 + std::abs(unit(random)));
    }
    const SimilarityFit fit = fit_weighted_similarity(source.data(), target.data(), w.data(), count);
    const SimilarityFit reference = complex_reference(source, target, w);
    EXPECT_NEAR(fit.scale_cos, reference.scale_cos, 1e-12);
    EXPECT_NEAR(fit.scale_sin, reference.scale_sin, 1e-12);
    EXPECT_NEAR(fit.translation.u, reference.translation.u, 1e-12);
    EXPECT_NEAR(fit.translation.v, reference.translation.v, 1e-12);
    EXPECT_NEAR(fit.residual, reference.residual, 1e-12);
  }
}

// The closed form and Eigen's SVD solve the same minimisation: same transform and residual on random inputs and on
// every degenerate kind (collinear, coincident targets, coincident sources, one weighted correspondence, no weight).
TEST(WeightedProcrustes, ClosedFormAndEigenSvdAgree) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 600; ++trial) {
    const int count = 1 + trial % 4;
    std::vector<Point2> source, target;
    std::vector<double> w;
    for (int j = 0; j < count; ++j) {
      source.push_back({unit(random), unit(random)});
      target.push_back({unit(random), unit(random)});
      w.push_back(0.1 + std::abs(unit(random)));
    }
    switch (trial % 6) {
      case 1:   // collinear sources and targets
        for (int j = 0; j < count; ++j) {
          source[static_cast<std::size_t>(j)] = {0.3 * j, 0.0};
          target[static_cast<std::size_t>(j)] = {0.5, 0.1 + 0.2 * j};
        }
        break;
      case 2:   // coincident targets
        for (Point2& t : target) t = {0.25, -0.5};
        break;
      case 3:   // coincident sources
        for (Point2& s : source) s = {0.4, 0.4};
        break;
      case 4:   // only the first correspondence weighs
        for (std::size_t j = 1; j < w.size(); ++j) w[j] = 0.0;
        break;
      case 5:   // no weight at all
        for (double& weight : w) weight = 0.0;
        break;
      default:
        break;
    }
    const SimilarityFit closed =
        fit_weighted_similarity(source.data(), target.data(), w.data(), count, ProcrustesMethod::closed_form);
    const SimilarityFit svd =
        fit_weighted_similarity(source.data(), target.data(), w.data(), count, ProcrustesMethod::eigen_svd);
    EXPECT_NEAR(closed.scale_cos, svd.scale_cos, 1e-12) << "trial " << trial;
    EXPECT_NEAR(closed.scale_sin, svd.scale_sin, 1e-12) << "trial " << trial;
    EXPECT_NEAR(closed.translation.u, svd.translation.u, 1e-12) << "trial " << trial;
    EXPECT_NEAR(closed.translation.v, svd.translation.v, 1e-12) << "trial " << trial;
    EXPECT_NEAR(closed.residual, svd.residual, 1e-12) << "trial " << trial;
  }
}

TEST(WeightedProcrustes, RecoversAnExactSimilarity) {
  const std::vector<Point2> source = {{0, 0}, {1, 0}, {0.6, 0.5}, {0.2, -0.4}};
  const double angle = 0.7, scale = 0.3;
  std::vector<Point2> target;
  for (const Point2& s : source)
    target.push_back({0.4 + scale * (std::cos(angle) * s.u - std::sin(angle) * s.v),
                      0.2 + scale * (std::sin(angle) * s.u + std::cos(angle) * s.v)});
  const std::vector<double> w = {1, 2, 3, 4};
  const SimilarityFit fit = fit_weighted_similarity(source.data(), target.data(), w.data(), 4);
  EXPECT_NEAR(fit.scale_cos, scale * std::cos(angle), 1e-14);
  EXPECT_NEAR(fit.scale_sin, scale * std::sin(angle), 1e-14);
  EXPECT_NEAR(fit.translation.u, 0.4, 1e-14);
  EXPECT_NEAR(fit.translation.v, 0.2, 1e-14);
  EXPECT_NEAR(fit.residual, 0.0, 1e-14);
}

TEST(WeightedProcrustes, NeverReturnsAReflection) {
  // Target = mirror image of an asymmetric source: the best proper rotation cannot reproduce it, so the residual
  // stays positive and the transform keeps its orientation (z is a scaled rotation by construction: check the
  // fitted points are not the mirrored ones).
  const std::vector<Point2> source = {{0, 0}, {1, 0}, {0.6, 0.5}, {0.2, -0.4}};
  std::vector<Point2> target;
  for (const Point2& s : source) target.push_back({0.5 + 0.3 * s.u, 0.5 - 0.3 * s.v});   // reflected across u
  const std::vector<double> w(4, 1.0);
  const SimilarityFit fit = fit_weighted_similarity(source.data(), target.data(), w.data(), 4);
  const SimilarityFit reference = complex_reference(source, target, w);
  EXPECT_GT(fit.residual, 1e-3);
  EXPECT_NEAR(fit.residual, reference.residual, 1e-12);
  EXPECT_GE(std::hypot(fit.scale_cos, fit.scale_sin), 0.0);
}

TEST(WeightedProcrustes, CoincidentTargetsGiveScaleZeroAtTheirPoint) {
  const std::vector<Point2> source = {{0, 0}, {1, 0}, {0.6, 0.5}};
  const std::vector<Point2> target(3, Point2{0.3, 0.7});
  const std::vector<double> w = {1, 1, 2};
  const SimilarityFit fit = fit_weighted_similarity(source.data(), target.data(), w.data(), 3);
  EXPECT_EQ(fit.scale_cos, 0.0);
  EXPECT_EQ(fit.scale_sin, 0.0);
  EXPECT_NEAR(fit.translation.u, 0.3, 1e-15);
  EXPECT_NEAR(fit.translation.v, 0.7, 1e-15);
  EXPECT_NEAR(fit.residual, 0.0, 1e-15);
}

TEST(WeightedProcrustes, SingleCorrespondenceAndZeroWeightsAreHandled) {
  const Point2 source[2] = {{0, 0}, {1, 0}};
  const Point2 target[2] = {{0.2, 0.4}, {0.8, 0.1}};
  // Only the first correspondence has weight: scale 0 at its target (minimum-norm solution).
  const double one[2] = {2.0, 0.0};
  SimilarityFit fit = fit_weighted_similarity(source, target, one, 2);
  EXPECT_EQ(fit.scale_cos, 0.0);
  EXPECT_NEAR(fit.translation.u, 0.2, 1e-15);
  EXPECT_NEAR(fit.translation.v, 0.4, 1e-15);
  // No weight at all: plain mean of the targets.
  const double none[2] = {0.0, 0.0};
  fit = fit_weighted_similarity(source, target, none, 2);
  EXPECT_EQ(fit.scale_cos, 0.0);
  EXPECT_NEAR(fit.translation.u, 0.5, 1e-15);
  EXPECT_NEAR(fit.translation.v, 0.25, 1e-15);
}

// The per-level fitter shares the target-side sums between fits; every fit must be fit_weighted_similarity's
// closed form bit for bit (the candidate ranking, and with it the munkberg golden bytes, depends on every bit).
TEST(WeightedProcrustes, SharedTargetFitterGivesTheClosedFormBitForBit) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coordinate(-0.5, 1.5), weight(0.0, 5.0);
  const auto same_bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  for (int trial = 0; trial < 4000; ++trial) {
    const int count = 1 + trial % kShapeLandmarkCount;
    Point2 target[kShapeLandmarkCount];
    double w[kShapeLandmarkCount];
    for (int j = 0; j < count; ++j) {
      target[j] = {coordinate(rng), coordinate(rng)};
      // Degenerate cases on purpose: zero weights (all of them every 7th trial), coincident targets.
      w[j] = trial % 7 == 0 || (trial % 5 == 0 && j == 0) ? 0.0 : weight(rng);
      if (trial % 11 == 0 && j > 0) target[j] = target[0];
    }
    const SimilarityFitter fitter(target, w, count);
    for (int s = 0; s < 6; ++s) {
      Point2 source[kShapeLandmarkCount];
      for (int j = 0; j < count; ++j) source[j] = {coordinate(rng), coordinate(rng)};
      if (s == 5 && count > 1) source[1] = source[0];   // coincident sources
      const SimilarityFit expected = fit_weighted_similarity(source, target, w, count, ProcrustesMethod::closed_form);
      const SimilarityFit got = fitter.fit(source);
      ASSERT_TRUE(same_bits(got.scale_cos, expected.scale_cos)) << "trial " << trial;
      ASSERT_TRUE(same_bits(got.scale_sin, expected.scale_sin)) << "trial " << trial;
      ASSERT_TRUE(same_bits(got.translation.u, expected.translation.u)) << "trial " << trial;
      ASSERT_TRUE(same_bits(got.translation.v, expected.translation.v)) << "trial " << trial;
      ASSERT_TRUE(same_bits(got.residual, expected.residual)) << "trial " << trial;
    }
  }
}

TEST(WeightedProcrustes, CollinearPointsGiveTheBestProperRotation) {
  // Rank-1 cross matrix: sources and targets on lines at 90 degrees to each other.
  const std::vector<Point2> source = {{0, 0}, {1, 0}, {2, 0}};
  const std::vector<Point2> target = {{0.5, 0.1}, {0.5, 0.3}, {0.5, 0.5}};
  const std::vector<double> w(3, 1.0);
  const SimilarityFit fit = fit_weighted_similarity(source.data(), target.data(), w.data(), 3);
  EXPECT_NEAR(fit.scale_cos, 0.0, 1e-15);
  EXPECT_NEAR(fit.scale_sin, 0.2, 1e-15);
  EXPECT_NEAR(fit.residual, 0.0, 1e-15);
}

// ---- clustering ---------------------------------------------------------------------------------------------

TEST(PointClustering, PnnFindsSeparatedGroupsAtEveryLevel) {
  const std::vector<Point2> points = {{0.1, 0.1}, {0.9, 0.9}, {0.12, 0.1}, {0.9, 0.1}, {0.88, 0.9}, {0.5, 0.5}};
  const std::vector<double> w(points.size(), 1.0);
  const auto levels = pnn_cluster_levels(points, w, 4);
  ASSERT_EQ(levels.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(levels[k].clusters.size(), k + 1);
  const PointClustering& four = levels[3];
  EXPECT_EQ(four.assignment[0], four.assignment[2]);   // the two near (0.1, 0.1)
  EXPECT_EQ(four.assignment[1], four.assignment[4]);   // the two near (0.9, 0.9)
  EXPECT_NE(four.assignment[3], four.assignment[5]);
  // Two pairs 0.02 apart: each point 0.01 from its pair's centre.
  EXPECT_NEAR(four.total_scatter(), 4 * 0.0001, 1e-15);
  EXPECT_NEAR(levels[0].clusters[0].centre.u, (0.1 + 0.9 + 0.12 + 0.9 + 0.88 + 0.5) / 6, 1e-15);
}

TEST(PointClustering, KmeansNeverIncreasesTheScatterAndWeightsMoveCentres) {
  std::mt19937_64 random(4);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<Point2> points;
    std::vector<double> w;
    for (int i = 0; i < 16; ++i) {
      points.push_back({unit(random), unit(random)});
      w.push_back(trial % 2 ? unit(random) : 1.0);
    }
    auto levels = pnn_cluster_levels(points, w, 4);
    for (PointClustering& clustering : levels) {
      const double before = clustering.total_scatter();
      refine_with_kmeans(points, w, 20, clustering);
      EXPECT_LE(clustering.total_scatter(), before + 1e-12);
    }
  }
  // Weighted centre: weight 3 at u = 0, weight 1 at u = 1 -> centre 0.25.
  const auto levels = pnn_cluster_levels({{0, 0}, {1, 0}}, {3.0, 1.0}, 1);
  EXPECT_NEAR(levels[0].clusters[0].centre.u, 0.25, 1e-15);
  EXPECT_NEAR(levels[0].clusters[0].weight, 4.0, 1e-15);
}

// pnn_cluster_levels runs up to 16 points by a full lexicographic scan of the surviving pairs and falls back to the
// row-wise cheapest-partner bookkeeping otherwise; both must give the same partitions bit for bit (same assignment,
// same cluster sums), including ties: coincident points (8-bit chroma), zero weights, equal weights.
TEST(PointClustering, SixteenPointScanGivesTheRowWisePartitionsBitForBit) {
  std::mt19937_64 random(11);
  std::uniform_int_distribution<int> code(0, 255), small_code(100, 103), grid(0, 2), count(1, 16), kind(0, 4);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<PointClustering> scanned, row_wise;
  for (int trial = 0; trial < 4000; ++trial) {
    const int n = count(random), style = kind(random);
    std::vector<Point2> points;
    std::vector<double> w;
    for (int i = 0; i < n; ++i) {
      // Styles: spread 8-bit values, a few nearby codes (many exact ties), continuous values, a 3x3 grid with
      // weights 1 and 2 (equal merge costs between merged and unmerged clusters: the tie rules of the bookkeeping).
      if (style == 0) points.push_back({q8(code(random)), q8(code(random))});
      else if (style == 1) points.push_back({q8(small_code(random)), q8(small_code(random))});
      else if (style == 4) points.push_back({static_cast<double>(grid(random)), static_cast<double>(grid(random))});
      else points.push_back({unit(random), unit(random)});
      if (style == 4) w.push_back(1.0 + (i * 7 + trial) % 2);
      else w.push_back(style == 3 ? (i % 5 == 0 ? 0.0 : unit(random)) : (i % 7 == 3 ? 0.0 : 1.0));
    }
    pnn_cluster_levels(points, w, 4, scanned);
    pnn_cluster_levels_row_minima(points, w, 4, row_wise);
    ASSERT_EQ(scanned.size(), row_wise.size()) << trial;
    for (std::size_t l = 0; l < scanned.size(); ++l) {
      ASSERT_EQ(scanned[l].assignment, row_wise[l].assignment) << trial << " level " << l;
      ASSERT_EQ(scanned[l].clusters.size(), row_wise[l].clusters.size());
      for (std::size_t c = 0; c < scanned[l].clusters.size(); ++c) {
        const WeightedCluster &a = scanned[l].clusters[c], &b = row_wise[l].clusters[c];
        EXPECT_EQ(a.centre.u, b.centre.u);
        EXPECT_EQ(a.centre.v, b.centre.v);
        EXPECT_EQ(a.weight, b.weight);
        EXPECT_EQ(a.count, b.count);
        EXPECT_EQ(a.scatter, b.scatter);
      }
    }
  }
}

// The output-parameter form reuses the caller's storage: a vector that held a larger clustering gives the same
// levels as a fresh one.
TEST(PointClustering, ReusedLevelStorageGivesFreshResults) {
  const std::vector<Point2> many = {{0.1, 0.1}, {0.9, 0.9}, {0.12, 0.1}, {0.9, 0.1}, {0.88, 0.9}, {0.5, 0.5}};
  const std::vector<Point2> few = {{0.2, 0.3}, {0.25, 0.3}, {0.7, 0.6}};
  std::vector<PointClustering> reused;
  pnn_cluster_levels(many, std::vector<double>(many.size(), 1.0), 4, reused);
  pnn_cluster_levels(few, {1.0, 2.0, 1.0}, 4, reused);
  const std::vector<PointClustering> fresh = pnn_cluster_levels(few, {1.0, 2.0, 1.0}, 4);
  ASSERT_EQ(reused.size(), 3u);
  for (std::size_t l = 0; l < fresh.size(); ++l) {
    EXPECT_EQ(reused[l].assignment, fresh[l].assignment);
    ASSERT_EQ(reused[l].clusters.size(), l + 1);
    for (std::size_t c = 0; c <= l; ++c) {
      EXPECT_EQ(reused[l].clusters[c].centre.u, fresh[l].clusters[c].centre.u);
      EXPECT_EQ(reused[l].clusters[c].scatter, fresh[l].clusters[c].scatter);
    }
  }
  // Two points 0.05 apart with weights 1 and 2 merge first: centre at 1/3 of the way from the heavier one.
  EXPECT_NEAR(reused[1].clusters[0].centre.u, 0.2 + 0.05 * 2.0 / 3.0, 1e-15);
}

// ---- the refinement measure's stretch ----------------------------------------------------------------------

// The refinement measure's stretch and slope (procrustes_refinement.h) against std::pow and its derivative; a NaN
// coordinate stays NaN (it must never index the table), and the linear measure is the identity.
TEST(RefineMeasure, StretchAndSlopeFollowPowAndNanStaysNan) {
  const RefineMeasure linear(1.0);
  EXPECT_EQ(linear.map(0.3), 0.3);
  EXPECT_EQ(linear.slope(0.3, 0.3), 1.0);
  const RefineMeasure stretched(0.455);
  EXPECT_TRUE(std::isnan(stretched.map(std::nan(""))));
  EXPECT_EQ(stretched.map(0.0), std::pow(kStretchFloor, 0.455));
  EXPECT_EQ(stretched.slope(0.0, stretched.map(0.0)), 0.0);   // below the floor f is constant
  for (const double c : {1e-6, 0.02, 0.3, 0.999, 1.0}) {
    const double f = stretched.map(c);
    EXPECT_LE(std::abs(f - std::pow(c, 0.455)), 2e-13 * f) << c;
    EXPECT_LE(std::abs(stretched.slope(c, f) - 0.455 * std::pow(c, 0.455 - 1.0)), 1e-12 * 0.455 * std::pow(c, -0.545))
        << c;
  }
  // The table of a second exponent on the same thread leaves the first measure's table intact.
  const RefineMeasure other(0.75);
  EXPECT_LE(std::abs(stretched.map(0.3) - std::pow(0.3, 0.455)), 2e-13);
  EXPECT_LE(std::abs(other.map(0.3) - std::pow(0.3, 0.75)), 2e-13);
}

// ---- the solver ----------------------------------------------------------------------------------------------

ShapeFitProblem problem_on_template(const double* truth, ShapeErrorKind kind, int repeat = 4) {
  ShapeFitData data;
  data.shape = kite();
  data.error_kind = kind;
  data.points = {Point2{0.5, 0.5}};
  const auto landmarks = ShapeFitProblem(data).decoded_landmarks(truth);
  data.points.clear();
  for (int i = 0; i < 4 * repeat; ++i) data.points.push_back(landmarks[static_cast<std::size_t>(i % 4)]);
  return ShapeFitProblem(data);
}

TEST(ProcrustesSolver, PointsOnATransformedTemplateAreFitExactly) {
  const double truth[4] = {q8(70), q8(50), q8(160), q8(120)};
  for (const ShapeErrorKind kind : {ShapeErrorKind::linear, ShapeErrorKind::stretched}) {
    const ShapeFitProblem problem = problem_on_template(truth, kind);
    const SolveResult result = solve_procrustes(problem, ProcrustesOptions{}, nullptr, 0);
    EXPECT_EQ(result.summary.final_error, 0.0) << to_string(kind);
    EXPECT_EQ(result.summary.termination, Termination::converged);
    const std::vector<std::int64_t> expected = {70, 50, 160, 120};
    EXPECT_EQ(result.lattice_indices, expected);
    EXPECT_GE(result.summary.evaluations, 8u);   // 8 plus any candidates tied with the 8th
  }
}

TEST(ProcrustesSolver, ConstantBlockCollapsesTheShapeOntoThePoint) {
  ShapeFitData data;
  data.shape = kite();
  data.points.assign(16, Point2{q8(100), q8(30)});
  const ShapeFitProblem problem(data);
  const SolveResult result = solve_procrustes(problem, ProcrustesOptions{}, nullptr, 0);
  EXPECT_EQ(result.summary.final_error, 0.0);
  EXPECT_EQ(result.lattice_indices[0], 100);
  EXPECT_EQ(result.lattice_indices[1], 30);
}

TEST(ProcrustesSolver, TwoColourBlockPutsLandmarksOnBothColours) {
  ShapeFitData data;
  data.shape = kite();
  for (int i = 0; i < 16; ++i) data.points.push_back(i % 3 ? Point2{q8(40), q8(200)} : Point2{q8(180), q8(90)});
  const ShapeFitProblem problem(data);
  const SolveResult result = solve_procrustes(problem, ProcrustesOptions{}, nullptr, 0);
  // Matching the two colours to landmarks 0 and 1 places the base points exactly on them.
  EXPECT_EQ(result.summary.final_error, 0.0) << result.summary.brief_report();
}

TEST(ProcrustesSolver, OneOutlierStaysWithinTheCertifiedOptimumOnACoarseLattice) {
  // 15 points on a transformed template plus one outlier; on a 5-bit lattice the exhaustive optimum is known.
  ShapeFitData data;
  data.shape = kite();
  data.lattice_bits = 5;
  data.points = {Point2{0.5, 0.5}};
  const double truth[4] = {8.0 / 31, 6.0 / 31, 20.0 / 31, 14.0 / 31};
  const auto landmarks = ShapeFitProblem(data).decoded_landmarks(truth);
  data.points.clear();
  for (int i = 0; i < 15; ++i) data.points.push_back(landmarks[static_cast<std::size_t>(i % 4)]);
  data.points.push_back({0.95, 0.05});
  const ShapeFitProblem problem(data);
  const SolveResult brute = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
  const SolveResult result = solve_procrustes(problem, ProcrustesOptions{}, nullptr, 0);
  EXPECT_GE(result.summary.final_error, brute.summary.final_error);
  EXPECT_LE(result.summary.final_error, 1.05 * brute.summary.final_error) << result.summary.brief_report();
}

TEST(ProcrustesSolver, CollinearPointsAreFitByACollinearTemplate) {
  ShapeFitData data;
  data.shape = ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{3, 0}, Point2{1, 0}, Point2{2, 0}});
  for (int i = 0; i < 16; ++i) data.points.push_back({q8(30 + 30 * (i % 4)), q8(200 - 30 * (i % 4))});
  const ShapeFitProblem problem(data);
  const SolveResult result = solve_procrustes(problem, ProcrustesOptions{}, nullptr, 0);
  // Landmarks 2 and 3 at 1/3 and 2/3 of the base segment: exact up to the rounding of 1/3 in the template.
  EXPECT_NEAR(result.summary.final_error, 0.0, 1e-28) << result.summary.brief_report();
}

void expect_within_a_few_percent_of_the_exhaustive_optimum(const ProcrustesOptions& options) {
  std::mt19937_64 random(6);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double fit_total = 0, optimum_total = 0;
  for (int trial = 0; trial < 12; ++trial) {
    ShapeFitData data;
    data.shape = kite();
    data.lattice_bits = 4;
    Point2 centres[4];
    for (Point2& c : centres) c = {0.1 + 0.6 * unit(random), 0.1 + 0.6 * unit(random)};
    for (int i = 0; i < 16; ++i)
      data.points.push_back({centres[i % 4].u + 0.02 * unit(random), centres[i % 4].v + 0.02 * unit(random)});
    const ShapeFitProblem problem(data);
    const SolveResult result = solve_procrustes(problem, options, nullptr, 0);
    const SolveResult brute = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
    EXPECT_GE(result.summary.final_error, brute.summary.final_error);
    fit_total += result.summary.final_error;
    optimum_total += brute.summary.final_error;
  }
  // A heuristic: not optimal, but close on average on a coarse lattice (the exact ratio is reported, not tuned).
  EXPECT_LE(fit_total, 1.5 * optimum_total);
}

TEST(ProcrustesSolver, AveragesWithinAFewPercentOfTheExhaustiveOptimumOnClusteredBlocks) {
  expect_within_a_few_percent_of_the_exhaustive_optimum(ProcrustesOptions{});
}

TEST(ProcrustesSolver, EigenSvdTablesAndRefinementAlsoStayNearTheExhaustiveOptimum) {
  ProcrustesOptions eigen;
  eigen.svd = ProcrustesMethod::eigen_svd;
  expect_within_a_few_percent_of_the_exhaustive_optimum(eigen);
  ProcrustesOptions refined;
  refined.refined_candidates = 8;
  expect_within_a_few_percent_of_the_exhaustive_optimum(refined);
  ProcrustesOptions tables;
  tables.svd = ProcrustesMethod::tables;
  expect_within_a_few_percent_of_the_exhaustive_optimum(tables);
}

// Refinement only re-ranks candidates by a lower continuous error and reassigns points to their nearest landmark:
// points lying exactly on a transformed template stay fit exactly.
TEST(ProcrustesSolver, RefinementKeepsAnExactFitExact) {
  ShapeFitData data;
  data.shape = kite();
  data.points = {Point2{0.5, 0.5}};
  const double truth[4] = {q8(60), q8(80), q8(150), q8(100)};
  const auto landmarks = ShapeFitProblem(data).decoded_landmarks(truth);
  data.points.clear();
  for (int i = 0; i < 16; ++i) data.points.push_back(landmarks[static_cast<std::size_t>(i % 4)]);
  const ShapeFitProblem problem(data);
  ProcrustesOptions options;
  options.refined_candidates = 61;
  const SolveResult result = solve_procrustes(problem, options, nullptr, 0);
  EXPECT_EQ(result.summary.final_error, 0.0);
}

ProcrustesOptions screened_options(int refined = 12, int evaluated = 2) {
  ProcrustesOptions options;
  options.search = ProcrustesOptions::Search::screened;
  options.refined_candidates = refined;
  options.evaluated_candidates = evaluated;
  return options;
}

// Points on a transformed template (every landmark held by 4 points) are fit exactly, at the true lattice point;
// returns the solve for further checks.
SolveResult expect_exact_template_fit(const ProcrustesOptions& options, ShapeErrorKind kind) {
  const double truth[4] = {q8(70), q8(50), q8(160), q8(120)};
  const ShapeFitProblem problem = problem_on_template(truth, kind);
  const SolveResult result = solve_procrustes(problem, options, nullptr, 0);
  EXPECT_EQ(result.summary.final_error, 0.0) << to_string(kind) << " " << result.summary.brief_report();
  const std::vector<std::int64_t> expected = {70, 50, 160, 120};
  EXPECT_EQ(result.lattice_indices, expected) << to_string(kind);
  return result;
}

// A constant block collapses every landmark onto its one colour.
void expect_constant_block_fits_exactly(const ProcrustesOptions& options) {
  ShapeFitData constant;
  constant.shape = kite();
  constant.points.assign(16, Point2{q8(100), q8(30)});
  const ShapeFitProblem flat(constant);
  const SolveResult collapsed = solve_procrustes(flat, options, nullptr, 0);
  EXPECT_EQ(collapsed.summary.final_error, 0.0);
  EXPECT_EQ(collapsed.lattice_indices[0], 100);
  EXPECT_EQ(collapsed.lattice_indices[1], 30);
}

TEST(ProcrustesSolver, ScreenedSearchFitsExactCasesExactly) {
  for (const ShapeErrorKind kind : {ShapeErrorKind::linear, ShapeErrorKind::stretched}) {
    const SolveResult result = expect_exact_template_fit(screened_options(), kind);
    // Only the evaluated_candidates best by the measured error at their snapped points reach the problem's error.
    EXPECT_LE(result.summary.evaluations, 2u);
  }
  expect_constant_block_fits_exactly(screened_options());
  ShapeFitData two;
  two.shape = kite();
  for (int i = 0; i < 16; ++i) two.points.push_back(i % 3 ? Point2{q8(40), q8(200)} : Point2{q8(180), q8(90)});
  const ShapeFitProblem two_colours(two);
  EXPECT_EQ(solve_procrustes(two_colours, screened_options(), nullptr, 0).summary.final_error, 0.0);
}

TEST(ProcrustesSolver, ScreenedSearchStaysNearTheExhaustiveOptimum) {
  expect_within_a_few_percent_of_the_exhaustive_optimum(screened_options());
  expect_within_a_few_percent_of_the_exhaustive_optimum(screened_options(6, 1));
  ProcrustesOptions unrefined = screened_options(0, 4);   // screening alone, no refinement
  expect_within_a_few_percent_of_the_exhaustive_optimum(unrefined);
}

// A base point outside [0, 1] cannot be stored; search=screened keeps the refinement inside the box. On points that
// hug the u = 0 border (where unconstrained fits leave the box) its answer is a lattice point in [0, 1]^4 whose
// reported error is the problem's own, and repeated solves agree.
TEST(ProcrustesSolver, ScreenedSearchIsDeterministicAndBoxed) {
  std::mt19937_64 random(9);
  std::uniform_real_distribution<double> near_border(0.0, 0.06), unit(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    ShapeFitData data;
    data.shape = kite();
    data.error_kind = trial % 2 ? ShapeErrorKind::stretched : ShapeErrorKind::linear;
    // Real HDR chroma hugs u = 0: the unconstrained best transforms put base points outside the box.
    for (int i = 0; i < 16; ++i) data.points.push_back({near_border(random), 0.3 + 0.4 * unit(random)});
    const ShapeFitProblem problem(data);
    const SolveResult a = solve_procrustes(problem, screened_options(), nullptr, 0);
    const SolveResult b = solve_procrustes(problem, screened_options(), nullptr, 0);
    EXPECT_EQ(a.lattice_indices, b.lattice_indices);
    EXPECT_EQ(a.summary.final_error, b.summary.final_error);
    ASSERT_EQ(a.parameters.size(), 4u);
    for (const double x : a.parameters) {
      EXPECT_GE(x, 0.0);
      EXPECT_LE(x, 1.0);
    }
    EXPECT_EQ(a.summary.final_error, problem.eval(a.parameters.data()));
  }
}

ProcrustesOptions start_error_options(int refined = 6) {
  ProcrustesOptions options;
  options.search = ProcrustesOptions::Search::start_error;
  options.refined_candidates = refined;
  return options;
}

TEST(ProcrustesSolver, StartErrorSearchFitsExactCasesExactly) {
  for (const ShapeErrorKind kind : {ShapeErrorKind::linear, ShapeErrorKind::stretched}) {
    // Only the refined candidates reach the problem's error.
    EXPECT_LE(expect_exact_template_fit(start_error_options(), kind).summary.evaluations, 6u);
    // Without refinement the lowest start error alone is evaluated, and on exact data it is the exact fit.
    EXPECT_EQ(expect_exact_template_fit(start_error_options(0), kind).summary.evaluations, 1u);
  }
  expect_constant_block_fits_exactly(start_error_options());
}

TEST(ProcrustesSolver, StartErrorSearchStaysNearTheExhaustiveOptimum) {
  expect_within_a_few_percent_of_the_exhaustive_optimum(start_error_options());
  expect_within_a_few_percent_of_the_exhaustive_optimum(start_error_options(3));
}

// More refined candidates than distinct ones (a single point: every candidate collapses onto it) ends the search
// when the candidates run out, with a valid answer.
TEST(ProcrustesSolver, StartErrorSearchEndsWhenTheCandidatesRunOut) {
  ShapeFitData data;
  data.shape = kite();
  data.points = {Point2{q8(90), q8(140)}};
  const ShapeFitProblem problem(data);
  const SolveResult result = solve_procrustes(problem, start_error_options(1000), nullptr, 0);
  EXPECT_EQ(result.summary.termination, Termination::converged);
  EXPECT_EQ(result.summary.final_error, 0.0);
}

TEST(ProcrustesSolver, MethodAndRefinementOptionsResolve) {
  const Solver& solver = procrustes_solver();
  const SolverOptions resolved = resolve_solver_options(solver, {});
  EXPECT_EQ(resolved.at("svd"), "closed_form");
  EXPECT_EQ(resolved.at("refined_candidates"), "12");
  EXPECT_THROW(resolve_solver_options(solver, {{"svd", "jacobi"}}), Error);
  EXPECT_EQ(ProcrustesOptions::from_resolved(resolve_solver_options(solver, {{"svd", "tables"}})).svd,
            ProcrustesMethod::tables);
  EXPECT_THROW(resolve_solver_options(solver, {{"refine_iterations", "-1"}}), Error);
  const ProcrustesOptions options =
      ProcrustesOptions::from_resolved(resolve_solver_options(solver, {{"svd", "eigen"}, {"refined_candidates", "3"}}));
  EXPECT_EQ(options.svd, ProcrustesMethod::eigen_svd);
  EXPECT_EQ(options.refined_candidates, 3);
  EXPECT_EQ(resolved.at("search"), "ranked");
  EXPECT_EQ(resolved.at("screened_candidates"), "0");
  EXPECT_EQ(options.search, ProcrustesOptions::Search::ranked);
  const ProcrustesOptions screened = ProcrustesOptions::from_resolved(
      resolve_solver_options(solver, {{"search", "screened"}, {"screened_candidates", "24"}}));
  EXPECT_EQ(screened.search, ProcrustesOptions::Search::screened);
  EXPECT_EQ(screened.screened_candidates, 24);
  EXPECT_EQ(ProcrustesOptions::from_resolved(resolve_solver_options(solver, {{"search", "start_error"}})).search,
            ProcrustesOptions::Search::start_error);
  EXPECT_THROW(resolve_solver_options(solver, {{"search", "lazy"}}), Error);
  EXPECT_THROW(resolve_solver_options(solver, {{"screened_candidates", "-1"}}), Error);
}

TEST(ProcrustesSolver, SameInputGivesTheSameAnswer) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ShapeFitData data;
  data.shape = kite();
  for (int i = 0; i < 16; ++i) data.points.push_back({unit(random), unit(random)});
  const ShapeFitProblem problem(data);
  const SolveResult a = procrustes_solver().solve(problem, {}, nullptr, 3);
  const SolveResult b = procrustes_solver().solve(problem, {}, nullptr, 3);
  EXPECT_EQ(a.lattice_indices, b.lattice_indices);
  EXPECT_EQ(a.summary.final_error, b.summary.final_error);
  EXPECT_EQ(a.summary.seed, 3u);
}

TEST(ProcrustesSolver, SolvingBlocksOnSeveralThreadsMatchesSerial) {
  std::mt19937_64 random(8);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ShapeFitProblem> problems;
  for (int b = 0; b < 64; ++b) {
    ShapeFitData data;
    data.shape = kite();
    data.error_kind = b % 2 ? ShapeErrorKind::stretched : ShapeErrorKind::linear;
    for (int i = 0; i < 16; ++i) data.points.push_back({unit(random), unit(random)});
    problems.emplace_back(data);
  }
  // The default search and search=start_error (its per-thread scratch and single-precision screening).
  for (const ProcrustesOptions& options : {ProcrustesOptions{}, start_error_options()}) {
    std::vector<SolveResult> serial, threaded(problems.size());
    for (const auto& problem : problems) serial.push_back(solve_procrustes(problem, options, nullptr, 0));
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < 4; ++t)
      threads.emplace_back([&, t] {
        for (std::size_t i = t; i < problems.size(); i += 4)
          threaded[i] = solve_procrustes(problems[i], options, nullptr, 0);
      });
    for (std::thread& thread : threads) thread.join();
    for (std::size_t i = 0; i < problems.size(); ++i) {
      EXPECT_EQ(threaded[i].lattice_indices, serial[i].lattice_indices);
      EXPECT_EQ(threaded[i].summary.final_error, serial[i].summary.final_error);
    }
  }
}

TEST(ProcrustesSolver, RefusesProblemsWithoutTheLandmarkFitCapability) {
  const auto problem = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}});
  try {
    find_solver("procrustes").solve(problem, {}, nullptr, 0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("procrustes: needs a problem with the landmark_fit capability"),
              std::string::npos)
        << e.what();
  }
}

TEST(ProcrustesSolver, OptionsAreValidated) {
  const Solver& solver = procrustes_solver();
  EXPECT_THROW(resolve_solver_options(solver, {{"max_clusters", "5"}}), Error);
  EXPECT_THROW(resolve_solver_options(solver, {{"seed", "1"}}), Error);
  ProcrustesOptions options;
  options.min_clusters = 3;
  options.max_clusters = 2;
  std::string why;
  EXPECT_FALSE(options.is_valid(&why));
  EXPECT_NE(why.find("min_clusters"), std::string::npos);
  ShapeFitData data;
  data.points = {Point2{0.5, 0.5}};
  const ShapeFitProblem problem(data);
  EXPECT_THROW(solve_procrustes(problem, options, nullptr, 0), Error);
}

}  // namespace
}  // namespace blocklab
