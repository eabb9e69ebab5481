// The `anneal` solver (solvers/anneal/anneal_solver.h): lattice and continuous searches, cooling schedules,
// seeding, option handling and errors.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/problem.h"
#include "solvers/anneal/anneal_solver.h"
#include "solvers/exhaustive/exhaustive_solver.h"
#include "solvers/registry.h"
#include "tests/contract/example_problems.h"

namespace blocklab {
namespace {

ErrorProblem<examples::PaletteFitError> palette_problem(std::int64_t levels) {
  return make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}},
                      {Lattice::uniform(0.0, 1.0, levels), Lattice::uniform(0.0, 1.0, levels)});
}

TEST(AnnealSolver, FindsTheExhaustiveOptimumOfAPaletteFitOnA32LevelLattice) {
  const auto problem = palette_problem(32);
  const SolveResult oracle = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
  const SolveResult result = solve_anneal(problem, AnnealOptions{}, nullptr, 5);
  EXPECT_EQ(result.summary.final_error, oracle.summary.final_error) << result.summary.brief_report();
  ASSERT_EQ(result.lattice_indices.size(), 2u);
  EXPECT_EQ(result.parameters[0], problem.lattice(0).point(result.lattice_indices[0]));
  EXPECT_EQ(result.parameters[1], problem.lattice(1).point(result.lattice_indices[1]));
  EXPECT_EQ(result.summary.termination, Termination::max_iterations);
  // 4 runs: each evaluates its start point and `iterations` moves.
  EXPECT_EQ(result.summary.evaluations, 4u * (AnnealOptions{}.iterations + 1u));
}

TEST(AnnealSolver, SameSeedSameAnswerAndTheSeedIsRecorded) {
  const auto problem = palette_problem(64);
  AnnealOptions options;
  options.iterations = 300;
  options.restarts = 1;
  options.restart_from = RestartPoint::random;
  const SolveResult a = solve_anneal(problem, options, nullptr, 11);
  const SolveResult b = solve_anneal(problem, options, nullptr, 11);
  EXPECT_EQ(a.parameters, b.parameters);
  EXPECT_EQ(a.lattice_indices, b.lattice_indices);
  EXPECT_EQ(a.summary.final_error, b.summary.final_error);
  EXPECT_EQ(a.summary.message, b.summary.message);   // includes the count of accepted moves
  EXPECT_EQ(a.summary.seed, 11u);
  // Different seeds take different paths (the accepted-move counts differ for at least one of a few seeds).
  bool any_differs = false;
  for (std::uint64_t seed = 12; seed < 16; ++seed)
    if (solve_anneal(problem, options, nullptr, seed).summary.message != a.summary.message) any_differs = true;
  EXPECT_TRUE(any_differs);
}

TEST(AnnealSolver, GetsCloseToTheContinuousMinimumOfTheGammaFit) {
  const auto problem = make_problem(examples::gamma_fit_example(), Bounds{{0.1, 0.5}, {2.0, 4.0}});
  AnnealOptions options;
  options.iterations = 4000;
  const double start[2] = {1.5, 1.0};
  const SolveResult result = solve_anneal(problem, options, start, 3);
  EXPECT_LT(result.summary.final_error, result.summary.initial_error);
  EXPECT_NEAR(result.parameters[0], 0.9, 0.02);   // the data are exactly 0.9 t^2.2
  EXPECT_NEAR(result.parameters[1], 2.2, 0.05);
  EXPECT_TRUE(result.lattice_indices.empty());
  for (int p = 0; p < 2; ++p) {
    EXPECT_GE(result.parameters[static_cast<std::size_t>(p)], problem.lower(p));
    EXPECT_LE(result.parameters[static_cast<std::size_t>(p)], problem.upper(p));
  }
}

TEST(AnnealSolver, EveryScheduleStartsAtT0AndEndsAtTheFinalRatio) {
  for (CoolingSchedule schedule : {CoolingSchedule::geometric, CoolingSchedule::linear, CoolingSchedule::exponential}) {
    AnnealOptions options;
    options.cooling = schedule;
    options.iterations = 101;
    options.final_temperature_ratio = 1e-3;
    EXPECT_DOUBLE_EQ(anneal_temperature(options, 2.0, 0, 3), 2.0) << to_string(schedule);
    EXPECT_NEAR(anneal_temperature(options, 2.0, 100, 3), 2e-3, 1e-15) << to_string(schedule);
    double previous = 2.0;
    for (int k = 1; k <= 100; ++k) {
      const double t = anneal_temperature(options, 2.0, k, 3);
      EXPECT_LT(t, previous) << to_string(schedule) << " k=" << k;   // strictly cooling
      previous = t;
    }
  }
  AnnealOptions linear;
  linear.cooling = CoolingSchedule::linear;
  linear.iterations = 11;
  linear.final_temperature_ratio = 0.5;
  EXPECT_DOUBLE_EQ(anneal_temperature(linear, 1.0, 5, 1), 0.75);   // halfway between 1 and 0.5
  AnnealOptions geometric;
  geometric.iterations = 3;
  geometric.final_temperature_ratio = 0.25;
  EXPECT_DOUBLE_EQ(anneal_temperature(geometric, 1.0, 1, 1), 0.5);   // sqrt(0.25)
}

TEST(AnnealSolver, MovesOnlyOnTheLatticeAndKeepsAFixedParameterFixed) {
  // Parameter 1 has a single lattice point: nothing can move it.
  const auto problem = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.3}, {1.0, 0.3}},
                                    {Lattice::uniform(0.0, 1.0, 17), Lattice::uniform(0.3, 0.3, 1)});
  AnnealOptions options;
  options.iterations = 500;
  const SolveResult result = solve_anneal(problem, options, nullptr, 1);
  EXPECT_EQ(result.parameters[1], 0.3);
  EXPECT_EQ(result.lattice_indices[1], 0);
  const SolveResult oracle = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
  EXPECT_EQ(result.summary.final_error, oracle.summary.final_error);
}

TEST(AnnealSolver, AbsoluteZeroTemperatureIsAGreedyDescentThatNeverGoesUphill) {
  const auto problem = palette_problem(32);
  AnnealOptions options;
  options.temperature_scale = TemperatureScale::absolute;
  options.initial_temperature = 0.0;
  options.restarts = 0;
  const double start[2] = {0.5, 0.5};
  const SolveResult result = solve_anneal(problem, options, start, 2);
  EXPECT_LE(result.summary.final_error, result.summary.initial_error);
}

// sqrt(x - 0.5): NaN below 0.5.
struct NaNBelowHalfError {
  static constexpr int kDim = 1;
  template <typename T>
  T operator()(const T* x) const {
    using std::sqrt;
    return sqrt(x[0] - T(0.5)) + square(x[0] - T(0.8));
  }
};

TEST(AnnealSolver, NeverReturnsAnInvalidPointAndReportsFailureWhenAllAreInvalid) {
  const auto valid_part = make_problem(NaNBelowHalfError{}, Bounds{{0.0}, {1.0}}, {Lattice::uniform(0.0, 1.0, 101)});
  const SolveResult result = solve_anneal(valid_part, AnnealOptions{}, nullptr, 4);
  EXPECT_GE(result.parameters[0], 0.5);
  EXPECT_FALSE(std::isnan(result.summary.final_error));
  const auto invalid = make_problem(NaNBelowHalfError{}, Bounds{{0.0}, {0.4}});
  AnnealOptions short_run;
  short_run.iterations = 50;
  const SolveResult failed = solve_anneal(invalid, short_run, nullptr, 4);
  EXPECT_EQ(failed.summary.termination, Termination::failed);
  EXPECT_TRUE(std::isnan(failed.summary.final_error));
  ASSERT_EQ(failed.parameters.size(), 1u);
}

TEST(AnnealSolver, RejectsAContinuousParameterWithAnInfiniteBound) {
  const auto problem = make_problem(examples::exponential_fit_example(),
                                    Bounds{{0.0, -std::numeric_limits<double>::infinity()}, {3.0, 0.0}});
  try {
    solve_anneal(problem, AnnealOptions{}, nullptr, 0);
    FAIL() << "expected an Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("anneal: parameter 1"), std::string::npos) << error.what();
  }
}

TEST(AnnealSolver, OptionsResolveThroughTheRegistryAndBadValuesAreErrors) {
  const Solver& solver = find_solver("anneal");
  const SolverOptions resolved = resolve_solver_options(solver, {});
  EXPECT_EQ(resolved.at("cooling"), "geometric");
  EXPECT_EQ(resolved.at("temperature_scale"), "relative");
  const AnnealOptions parsed = AnnealOptions::from_resolved(
      resolve_solver_options(solver, {{"cooling", "exponential"}, {"iterations", "17"}, {"restart_from", "random"}}));
  EXPECT_EQ(parsed.cooling, CoolingSchedule::exponential);
  EXPECT_EQ(parsed.iterations, 17);
  EXPECT_EQ(parsed.restart_from, RestartPoint::random);
  const auto problem = palette_problem(8);
  EXPECT_THROW(solver.solve(problem, {{"cooling", "logarithmic"}}, nullptr, 0), Error);
  EXPECT_THROW(solver.solve(problem, {{"iterations", "0"}}, nullptr, 0), Error);
  EXPECT_THROW(solver.solve(problem, {{"step", "0.1"}}, nullptr, 0), Error);
  EXPECT_THROW(cooling_schedule_from_string("fast"), Error);
  for (CoolingSchedule schedule : {CoolingSchedule::geometric, CoolingSchedule::linear, CoolingSchedule::exponential})
    EXPECT_EQ(cooling_schedule_from_string(to_string(schedule)), schedule);
  AnnealOptions bad;
  bad.final_temperature_ratio = 0.0;
  std::string why;
  EXPECT_FALSE(bad.is_valid(&why));
  EXPECT_NE(why.find("final_temperature_ratio"), std::string::npos);
}

}  // namespace
}  // namespace blocklab
