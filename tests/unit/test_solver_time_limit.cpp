// Every solver's `time_limit` option (solvers/solver.h TimeLimit): a solve with an enormous iteration or
// evaluation budget and time_limit = 0.05 s returns within about a second with termination max_seconds and a valid
// answer (finite error, parameters inside the bounds); the option is declared by every registered solver with the
// default 10 s and rejects 0, negative and infinite values.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <utility>
#include <string>
#include <vector>

#include "core/error.h"
#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "solvers/anneal/anneal_solver.h"
#include "solvers/ceres_lm/ceres_lm_solver.h"
#include "solvers/coeff_search/coeff_search_solver.h"
#include "solvers/exhaustive/exhaustive_solver.h"
#include "solvers/interval_bb/interval_bb_solver.h"
#include "solvers/lattice_polish/lattice_polish_solver.h"
#include "solvers/nlopt/nlopt_solver.h"
#include "solvers/procrustes/procrustes_solver.h"
#include "solvers/registry.h"
#include "tests/contract/example_problems.h"

namespace blocklab {
namespace {

constexpr double kLimit = 0.05;
constexpr double kPromptSeconds = 1.0;   // a solve stopped by the limit returns well within this
constexpr std::int64_t kHugeLattice = std::int64_t{1} << 20;

// A solve and the wall time it took.
template <typename Solve>
std::pair<SolveResult, double> timed(Solve solve) {
  const auto started = std::chrono::steady_clock::now();
  SolveResult result = solve();
  return {std::move(result), std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count()};
}

void expect_stopped_by_the_limit(const Problem& problem, const SolveResult& result, double seconds) {
  EXPECT_LT(seconds, kPromptSeconds) << result.summary.brief_report();
  EXPECT_EQ(result.summary.termination, Termination::max_seconds) << result.summary.brief_report();
  EXPECT_NE(result.summary.message.find("time limit of 0.05 s reached"), std::string::npos) << result.summary.message;
  EXPECT_TRUE(std::isfinite(result.summary.final_error)) << result.summary.brief_report();
  ASSERT_EQ(result.parameters.size(), static_cast<std::size_t>(problem.dim()));
  for (int p = 0; p < problem.dim(); ++p) {
    EXPECT_GE(result.parameters[static_cast<std::size_t>(p)], problem.lower(p)) << "parameter " << p;
    EXPECT_LE(result.parameters[static_cast<std::size_t>(p)], problem.upper(p)) << "parameter " << p;
  }
  EXPECT_EQ(problem.eval(result.parameters.data()), result.summary.final_error);
}

// The BC4-like palette fit on 2^20-point lattices (2^40 points in all).
ErrorProblem<examples::PaletteFitError> palette_on_a_huge_lattice() {
  const Lattice fine = Lattice::uniform(0.0, 1.0, kHugeLattice);
  return make_problem(examples::palette_fit_example(), Bounds{{0, 0}, {1, 1}}, {fine, fine});
}

// x0 x1 - x0 x1 + 1: exactly 1 at every point, but interval arithmetic loses the dependency, so every box wider than a
// point has a lower bound below 1 and branch-and-bound must descend to every lattice point.
struct DependencyError {
  static constexpr int kDim = 2;
  template <typename T>
  T operator()(const T* x) const {
    return x[0] * x[1] - x[0] * x[1] + T(1.0);
  }
};

// sum of x_p over 12 parameters: every full-neighbourhood pass from the top corner moves one lattice step down.
struct DescentError {
  static constexpr int kDim = 12;
  template <typename T>
  T operator()(const T* x) const {
    T sum = T(0.0);
    for (int p = 0; p < kDim; ++p) sum += x[p];
    return sum;
  }
};

// r = 1 / x on [1, inf): the minimum lies at infinity, so Levenberg-Marquardt keeps taking successful steps (about
// 30 before the gradient underflows); each evaluation carries ~2 million extra operations so that those steps take
// far longer than the limit.
struct RunawayResidualError {
  static constexpr int kDim = 1;
  static constexpr int kResiduals = 1;
  static constexpr bool kSmooth = true;
  template <typename T>
  void residuals(const T* x, T* r) const {
    T zero = T(0.0);
    for (int i = 1; i <= 2000000; ++i) zero += (x[0] - x[0]) * T(1.0 / i);
    r[0] = T(1.0) / x[0] + zero;
  }
  template <typename T>
  T operator()(const T* x) const {
    return sum_of_squared_residuals<kResiduals>(*this, x);
  }
};

TEST(SolverTimeLimit, ExhaustiveStopsWithTheBestPointSoFar) {
  const auto problem = palette_on_a_huge_lattice();
  ExhaustiveOptions options;
  options.max_points = kMaxExactInteger;
  options.time_limit = kLimit;
  const auto [result, seconds] = timed([&] { return solve_exhaustive(problem, options, nullptr, 0); });
  expect_stopped_by_the_limit(problem, result, seconds);
  EXPECT_LT(result.summary.evaluations, problem.lattice_point_count());
}

TEST(SolverTimeLimit, AnnealStopsMidRunWithTheBestPointSoFar) {
  const auto problem = palette_on_a_huge_lattice();
  AnnealOptions options;
  options.iterations = 1000000000LL;
  options.time_limit = kLimit;
  const auto [result, seconds] = timed([&] { return solve_anneal(problem, options, nullptr, 7); });
  expect_stopped_by_the_limit(problem, result, seconds);
}

TEST(SolverTimeLimit, CoeffSearchStopsInsideTheFirstGrid) {
  const auto problem = palette_on_a_huge_lattice();
  CoeffSearchOptions options;
  options.grid_points = 1000000;
  options.hill_climb_steps = 1000000000;
  options.max_grid_points = kMaxExactInteger;
  options.time_limit = kLimit;
  const auto [result, seconds] = timed([&] { return solve_coeff_search(problem, options, nullptr, 0); });
  expect_stopped_by_the_limit(problem, result, seconds);
}

TEST(SolverTimeLimit, CoeffSearchStopsInsideHillClimbing) {
  const auto problem = make_problem(DescentError{}, Bounds{std::vector<double>(12, 0.0), std::vector<double>(12, 1e9)});
  CoeffSearchOptions options;
  options.grid_points = 2;
  options.refinement_levels = 0;
  options.hill_climb_steps = 1000000000;
  options.tolerance = 0.0;
  options.time_limit = kLimit;
  const auto [result, seconds] = timed([&] { return solve_coeff_search(problem, options, nullptr, 0); });
  expect_stopped_by_the_limit(problem, result, seconds);
}

TEST(SolverTimeLimit, IntervalBranchAndBoundStopsWithItsProvenBound) {
  const Lattice fine = Lattice::uniform(0.0, 1.0, kHugeLattice);
  const auto problem = make_problem(DependencyError{}, Bounds{{0, 0}, {1, 1}}, {fine, fine});
  IntervalBbOptions options;
  options.max_boxes = kMaxExactInteger;
  options.time_limit = kLimit;
  const auto [result, seconds] = timed([&] { return solve_interval_bb(problem, options, nullptr, 0); });
  expect_stopped_by_the_limit(problem, result, seconds);
  EXPECT_EQ(result.summary.final_error, 1.0);
  EXPECT_LT(result.summary.lower_bound, 1.0);
}

TEST(SolverTimeLimit, LatticePolishStopsBetweenNeighbourhoodPasses) {
  const Lattice fine = Lattice::uniform(0.0, 1.0, kHugeLattice);
  const auto problem = make_problem(DescentError{}, Bounds{std::vector<double>(12, 0.0), std::vector<double>(12, 1.0)},
                                    std::vector<Lattice>(12, fine));
  LatticePolishOptions options;
  options.max_passes = 1 << 20;
  options.time_limit = kLimit;
  const std::vector<double> top(12, 1.0);
  const auto [result, seconds] = timed([&] { return solve_lattice_polish(problem, options, top.data(), 0); });
  expect_stopped_by_the_limit(problem, result, seconds);
  EXPECT_LT(result.summary.final_error, 12.0);   // it moved down before the limit
}

TEST(SolverTimeLimit, CeresLevenbergMarquardtStopsAtCeresSolverTime) {
  const auto problem =
      make_problem(RunawayResidualError{}, Bounds{{1.0}, {std::numeric_limits<double>::infinity()}});
  CeresLmOptions options;
  options.max_iterations = 1000000000;
  options.gradient_tolerance = 0.0;
  options.parameter_tolerance = 0.0;
  options.time_limit = kLimit;
  const auto [result, seconds] = timed([&] { return solve_ceres_lm(problem, options, nullptr, 0); });
  expect_stopped_by_the_limit(problem, result, seconds);
}

TEST(SolverTimeLimit, NloptStopsAtNloptMaxtime) {
  const auto problem = make_problem(examples::palette_fit_example(), Bounds{{0, 0}, {1, 1}});
  NloptOptions options;
  options.algorithm = "GN_DIRECT_L";
  options.max_evaluations = 2000000000;
  options.xtol_rel = 0.0;
  options.ftol_rel = 0.0;
  options.time_limit = kLimit;
  const auto [result, seconds] = timed([&] { return solve_nlopt(problem, options, nullptr, 0); });
  expect_stopped_by_the_limit(problem, result, seconds);
}

// Procrustes' work is bounded by its option ranges (at most 1000 refined candidates), so no budget runs for long:
// a limit far below one refinement stops it after the first evaluated candidate.
TEST(SolverTimeLimit, ProcrustesStopsBeforeRefiningAndKeepsAnEvaluatedCandidate) {
  ShapeFitData data;
  data.shape = ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
  for (int i = 0; i < 16; ++i) data.points.push_back(Point2{0.05 * i, 0.9 - 0.04 * (i % 5)});
  const ShapeFitProblem problem(data);
  ProcrustesOptions options;
  options.refined_candidates = 1000;
  options.refine_iterations = 1000;
  options.evaluated_candidates = 0;
  options.time_limit = 1e-9;
  const SolveResult result = solve_procrustes(problem, options, nullptr, 0);
  EXPECT_EQ(result.summary.termination, Termination::max_seconds) << result.summary.brief_report();
  EXPECT_EQ(result.summary.evaluations, 1u);
  EXPECT_TRUE(std::isfinite(result.summary.final_error));
  EXPECT_EQ(problem.eval(result.parameters.data()), result.summary.final_error);
}

TEST(SolverTimeLimit, EverySolverDeclaresTheOptionWithATenSecondDefault) {
  for (const Solver* registered : all_solvers()) {
    const Solver& solver = *registered;
    const std::string name = solver.name();
    EXPECT_EQ(resolve_solver_options(solver, {}).at("time_limit"), "10") << name;
    EXPECT_EQ(resolve_solver_options(solver, {{"time_limit", "0.01"}}).at("time_limit"), "0.01") << name;
    for (const char* bad : {"0", "-1", "inf", "nan"})
      EXPECT_THROW(resolve_solver_options(solver, {{"time_limit", bad}}), Error) << name << " time_limit=" << bad;
  }
}

}  // namespace
}  // namespace blocklab
