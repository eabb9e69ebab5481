// The `lattice_polish` solver (solvers/lattice_polish/lattice_polish_solver.h): snapping, the full 3^dim
// neighbourhood at radius 1, coordinate descent at larger radius, passes, invalid points, determinism, thread
// safety and errors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"
#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "solvers/exhaustive/exhaustive_solver.h"
#include "solvers/lattice_polish/lattice_polish_solver.h"
#include "solvers/registry.h"
#include "tests/contract/example_problems.h"

namespace blocklab {
namespace {

// The 8-bit storage value k (origin + k * step: not always bit-equal to k / 255.0).
double q8(int k) { return Lattice::uniform(0.0, 1.0, 256).point(k); }

// A separable bowl with its minimum between lattice points: (x0 - 0.31)^2 + (x1 - 0.62)^2 + (x2 - 0.5)^2 on a
// 0.1 lattice; the best lattice point is (0.3, 0.6, 0.5).
struct BowlError {
  static constexpr int kDim = 3;
  template <typename T>
  T operator()(const T* x) const {
    return square(x[0] - T(0.31)) + square(x[1] - T(0.62)) + square(x[2] - T(0.5));
  }
};

ErrorProblem<BowlError> bowl() {
  const Lattice tenth = Lattice::uniform(0.0, 1.0, 11);
  return make_problem(BowlError{}, Bounds{{0, 0, 0}, {1, 1, 1}}, {tenth, tenth, tenth});
}

TEST(LatticePolish, SnapsToTheNearestLatticePointWhenItIsBest) {
  const auto problem = bowl();
  const double start[3] = {0.31, 0.62, 0.5};
  LatticePolishOptions options;
  options.max_passes = 1;
  const SolveResult result = solve_lattice_polish(problem, options, start, 0);
  EXPECT_EQ(result.lattice_indices, (std::vector<std::int64_t>{3, 6, 5}));
  EXPECT_EQ(result.summary.termination, Termination::converged);
  EXPECT_EQ(result.summary.evaluations, 1u + 27u);   // start itself + the snapped point and its 26 neighbours
  EXPECT_NEAR(result.summary.initial_error, 0.0, 1e-30);
}

TEST(LatticePolish, OnePassMovesAtMostOneStepAndPassesWalkFurther) {
  const auto problem = bowl();
  const double far_start[3] = {0.0, 1.0, 0.9};
  LatticePolishOptions one;
  one.max_passes = 1;
  const SolveResult single = solve_lattice_polish(problem, one, far_start, 0);
  EXPECT_EQ(single.lattice_indices, (std::vector<std::int64_t>{1, 9, 8}));
  EXPECT_EQ(single.summary.termination, Termination::max_iterations);
  const SolveResult walked = solve_lattice_polish(problem, LatticePolishOptions{}, far_start, 0);
  EXPECT_EQ(walked.lattice_indices, (std::vector<std::int64_t>{3, 6, 5}));
  EXPECT_EQ(walked.summary.termination, Termination::converged);
}

TEST(LatticePolish, CoordinateDescentAtLargerRadius) {
  const auto problem = bowl();
  const double far_start[3] = {0.0, 1.0, 0.9};
  LatticePolishOptions options;
  options.radius = 4;
  options.max_passes = 1;
  const SolveResult result = solve_lattice_polish(problem, options, far_start, 0);
  // Separable error: one coordinate sweep of +-4 steps reaches each coordinate's best index within reach.
  EXPECT_EQ(result.lattice_indices, (std::vector<std::int64_t>{3, 6, 5}));
  EXPECT_NE(result.summary.message.find("coordinate descent"), std::string::npos);
}

TEST(LatticePolish, NeverWorseThanTheSnappedStartOnShapeFits) {
  std::mt19937_64 random(2);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    ShapeFitData data;
    data.error_kind = trial % 2 ? ShapeErrorKind::stretched : ShapeErrorKind::linear;
    for (int i = 0; i < 16; ++i) data.points.push_back({unit(random), unit(random)});
    const ShapeFitProblem problem(data);
    const double start[4] = {unit(random), unit(random), unit(random), unit(random)};
    double snapped[4];
    for (int p = 0; p < 4; ++p) snapped[p] = problem.lattice(p).point(problem.lattice(p).nearest_index(start[p]));
    const SolveResult result = solve_lattice_polish(problem, LatticePolishOptions{}, start, 0);
    EXPECT_LE(result.summary.final_error, problem.eval(snapped));
    EXPECT_EQ(problem.eval(result.parameters.data()), result.summary.final_error);
  }
}

// The plain full-neighbourhood polish, written out: every pass evaluates all 3^4 - 1 neighbours of its centre and
// the strictly best one seen becomes the incumbent. Returns the final index and counts evaluations.
std::vector<std::int64_t> plain_full_polish(const Problem& problem, std::vector<std::int64_t> index, int max_passes,
                                            std::uint64_t* evaluations) {
  const auto error_at = [&](const std::vector<std::int64_t>& at) {
    double x[4];
    for (int p = 0; p < 4; ++p) x[p] = problem.lattice(p).point(at[static_cast<std::size_t>(p)]);
    ++*evaluations;
    return problem.eval(x);
  };
  double best = error_at(index);
  for (int pass = 0; pass < max_passes; ++pass) {
    const std::vector<std::int64_t> centre = index;
    bool improved = false;
    for (int code = 0; code < 81; ++code) {
      std::vector<std::int64_t> at = centre;
      bool inside = true;
      for (int p = 0, rest = code; p < 4; ++p, rest /= 3) {
        at[static_cast<std::size_t>(3 - p)] += rest % 3 - 1;   // last parameter fastest
        if (at[static_cast<std::size_t>(3 - p)] < 0 || at[static_cast<std::size_t>(3 - p)] > 255) inside = false;
      }
      if (!inside || at == centre) continue;
      const double error = error_at(at);
      if (error < best) {
        best = error;
        index = at;
        improved = true;
      }
    }
    if (!improved) break;
  }
  return index;
}

// lattice_polish skips the points its previous pass already evaluated: the same answer as the plain search, with
// fewer evaluations whenever the centre moved.
TEST(LatticePolish, SkippingPointsOfThePreviousPassKeepsThePlainSearchsAnswer) {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int moved_twice = 0;
  for (int trial = 0; trial < 60; ++trial) {
    ShapeFitData data;
    data.error_kind = trial % 2 ? ShapeErrorKind::stretched : ShapeErrorKind::linear;
    for (int i = 0; i < 16; ++i) data.points.push_back({0.3 * unit(random), 0.2 + 0.3 * unit(random)});
    const ShapeFitProblem problem(data);
    // Starts a few lattice steps from a good fit, so that several passes move the centre.
    const SolveResult fit = solve_lattice_polish(problem, LatticePolishOptions{}, nullptr, 0);
    double start[4];
    std::vector<std::int64_t> start_index(4);
    for (int p = 0; p < 4; ++p) {
      start[p] = fit.parameters[static_cast<std::size_t>(p)] + (unit(random) - 0.5) * 12.0 / 255.0;
      start_index[static_cast<std::size_t>(p)] = problem.lattice(p).nearest_index(start[p]);
    }
    const SolveResult result = solve_lattice_polish(problem, LatticePolishOptions{}, start, 0);
    std::uint64_t plain_evaluations = 0;
    const std::vector<std::int64_t> plain =
        plain_full_polish(problem, start_index, LatticePolishOptions{}.max_passes, &plain_evaluations);
    EXPECT_EQ(result.lattice_indices, plain);
    EXPECT_LE(result.summary.evaluations, plain_evaluations);
    if (result.summary.message.find("1 pass") == std::string::npos &&
        result.summary.message.find(" 2 passes") == std::string::npos) {
      ++moved_twice;
      EXPECT_LT(result.summary.evaluations, plain_evaluations);
    }
  }
  EXPECT_GT(moved_twice, 10);   // the skip is really exercised
}

TEST(LatticePolish, ReachesTheZeroErrorShapeFromANearbyStart) {
  ShapeFitData data;
  data.shape = ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
  data.points = {Point2{0.5, 0.5}};
  const double truth[4] = {q8(70), q8(50), q8(160), q8(120)};
  const auto landmarks = ShapeFitProblem(data).decoded_landmarks(truth);
  data.points.clear();
  for (int i = 0; i < 16; ++i) data.points.push_back(landmarks[static_cast<std::size_t>(i % 4)]);
  const ShapeFitProblem problem(data);
  const double start[4] = {71.4 / 255, 48.7 / 255, 161.2 / 255, 119.3 / 255};
  const SolveResult result = solve_lattice_polish(problem, LatticePolishOptions{}, start, 0);
  EXPECT_EQ(result.summary.final_error, 0.0);
  EXPECT_EQ(result.lattice_indices, (std::vector<std::int64_t>{70, 50, 160, 120}));
}

TEST(LatticePolish, WithoutAStartBeginsAtTheLatticeMiddle) {
  const auto problem = bowl();
  LatticePolishOptions options;
  options.max_passes = 1;
  const SolveResult result = solve_lattice_polish(problem, options, nullptr, 0);
  EXPECT_TRUE(std::isnan(result.summary.initial_error));
  EXPECT_NE(result.summary.message.find("lattice middle"), std::string::npos);
  EXPECT_EQ(result.lattice_indices, (std::vector<std::int64_t>{4, 6, 5}));   // one step from (5, 5, 5)
}

TEST(LatticePolish, SameInputSameAnswerAcrossThreads) {
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ShapeFitProblem> problems;
  std::vector<std::array<double, 4>> starts;
  for (int b = 0; b < 32; ++b) {
    ShapeFitData data;
    for (int i = 0; i < 16; ++i) data.points.push_back({unit(random), unit(random)});
    problems.emplace_back(data);
    starts.push_back({unit(random), unit(random), unit(random), unit(random)});
  }
  std::vector<SolveResult> serial, threaded(problems.size());
  for (std::size_t i = 0; i < problems.size(); ++i)
    serial.push_back(solve_lattice_polish(problems[i], LatticePolishOptions{}, starts[i].data(), 0));
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (std::size_t i = t; i < problems.size(); i += 4)
        threaded[i] = solve_lattice_polish(problems[i], LatticePolishOptions{}, starts[i].data(), 0);
    });
  for (std::thread& thread : threads) thread.join();
  for (std::size_t i = 0; i < problems.size(); ++i) {
    EXPECT_EQ(threaded[i].lattice_indices, serial[i].lattice_indices);
    EXPECT_EQ(threaded[i].summary.final_error, serial[i].summary.final_error);
  }
}

TEST(LatticePolish, ErrorsNameTheSolverAndTheReason) {
  const auto continuous = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}});
  try {
    solve_lattice_polish(continuous, LatticePolishOptions{}, nullptr, 0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lattice_polish: parameter 0 has no storage lattice"), std::string::npos);
  }
  const Solver& solver = find_solver("lattice_polish");
  EXPECT_THROW(resolve_solver_options(solver, {{"radius", "0"}}), Error);
  EXPECT_EQ(resolve_solver_options(solver, {}).at("radius"), "1");
}

}  // namespace
}  // namespace blocklab
