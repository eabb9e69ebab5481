// The `coeff_search` solver (solvers/coeff_search/coeff_search_solver.h): grid, zoom refinement and hill climbing
// on continuous and lattice parameters; determinism, start handling, limits and errors.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/problem.h"
#include "solvers/coeff_search/coeff_search_solver.h"
#include "solvers/exhaustive/exhaustive_solver.h"
#include "solvers/registry.h"
#include "tests/contract/example_problems.h"

namespace blocklab {
namespace {

// An image-level coefficient pair like the wavelet format's (clamp fraction c, gamma g): a smooth bowl with its
// minimum at (0.0137, 2.31), inside [0, 0.1] x [1, 3].
struct ClampGammaError {
  static constexpr int kDim = 2;
  static constexpr bool kSmooth = true;
  template <typename T>
  T operator()(const T* x) const {
    return square((x[0] - T(0.0137)) / T(0.1)) + T(0.5) * square(x[1] - T(2.31)) +
           T(0.3) * square((x[0] - T(0.0137)) / T(0.1)) * square(x[1] - T(2.31));
  }
};

TEST(CoeffSearchSolver, FindsAContinuousTwoCoefficientMinimumToTheTolerance) {
  const auto problem = make_problem(ClampGammaError{}, Bounds{{0.0, 1.0}, {0.1, 3.0}});
  const SolveResult result = solve_coeff_search(problem, CoeffSearchOptions{}, nullptr, 0);
  EXPECT_EQ(result.summary.termination, Termination::converged) << result.summary.brief_report();
  EXPECT_NEAR(result.parameters[0], 0.0137, 1e-8);
  EXPECT_NEAR(result.parameters[1], 2.31, 1e-8);
  EXPECT_LT(result.summary.final_error, 1e-14);
  EXPECT_TRUE(result.lattice_indices.empty());
}

TEST(CoeffSearchSolver, GammaFitReachesTheGeneratingParameters) {
  const auto problem = make_problem(examples::gamma_fit_example(), Bounds{{0.1, 0.5}, {2.0, 4.0}});
  const SolveResult result = solve_coeff_search(problem, CoeffSearchOptions{}, nullptr, 0);
  EXPECT_NEAR(result.parameters[0], 0.9, 1e-6) << result.summary.brief_report();   // data are exactly 0.9 t^2.2
  EXPECT_NEAR(result.parameters[1], 2.2, 1e-6);
}

// With grid_points >= the lattice size, the first grid enumerates the lattice: the answer is exhaustive's.
TEST(CoeffSearchSolver, AGridAsFineAsTheLatticeIsExhaustive) {
  const auto problem = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}},
                                    {Lattice::uniform(0.0, 1.0, 16), Lattice::uniform(0.0, 1.0, 16)});
  CoeffSearchOptions options;
  options.grid_points = 16;
  const SolveResult result = solve_coeff_search(problem, options, nullptr, 0);
  const SolveResult oracle = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
  EXPECT_EQ(result.lattice_indices, oracle.lattice_indices);
  EXPECT_EQ(result.summary.final_error, oracle.summary.final_error);
  EXPECT_EQ(result.summary.termination, Termination::converged);
}

TEST(CoeffSearchSolver, LatticeSearchReturnsLatticePointsAndHillClimbsToALocalLatticeOptimum) {
  const auto problem = make_problem(ClampGammaError{}, Bounds{{0.0, 1.0}, {0.1, 3.0}},
                                    {Lattice::uniform(0.0, 0.1, 1001), Lattice::uniform(1.0, 3.0, 2001)});
  const SolveResult result = solve_coeff_search(problem, CoeffSearchOptions{}, nullptr, 0);
  ASSERT_EQ(result.lattice_indices.size(), 2u);
  EXPECT_EQ(result.parameters[0], problem.lattice(0).point(result.lattice_indices[0]));
  EXPECT_EQ(result.parameters[1], problem.lattice(1).point(result.lattice_indices[1]));
  // The bowl is separable up to a positive cross term: the lattice optimum is the nearest point (137, 1310).
  EXPECT_EQ(result.lattice_indices[0], 137);
  EXPECT_EQ(result.lattice_indices[1], 1310);
  // No neighbour one lattice step away is better.
  for (int p = 0; p < 2; ++p)
    for (int direction : {-1, 1}) {
      std::vector<double> x = result.parameters;
      x[static_cast<std::size_t>(p)] = problem.lattice(p).point(result.lattice_indices[static_cast<std::size_t>(p)] + direction);
      EXPECT_GE(problem.eval(x.data()), result.summary.final_error);
    }
}

TEST(CoeffSearchSolver, IsDeterministicAndCountsEveryEvaluation) {
  const auto problem = make_problem(ClampGammaError{}, Bounds{{0.0, 1.0}, {0.1, 3.0}});
  CoeffSearchOptions options;
  options.grid_points = 5;
  options.refinement_levels = 2;
  options.hill_climb_steps = 0;
  const SolveResult a = solve_coeff_search(problem, options, nullptr, 1);
  const SolveResult b = solve_coeff_search(problem, options, nullptr, 2);
  EXPECT_EQ(a.parameters, b.parameters);
  EXPECT_EQ(a.summary.final_error, b.summary.final_error);
  EXPECT_EQ(a.summary.evaluations, 3u * 25u);   // three full 5 x 5 grids, no hill climbing
  EXPECT_EQ(a.summary.termination, Termination::max_iterations);
}

TEST(CoeffSearchSolver, KeepsABetterStartPoint) {
  const auto problem = make_problem(ClampGammaError{}, Bounds{{0.0, 1.0}, {0.1, 3.0}});
  CoeffSearchOptions options;
  options.grid_points = 3;
  options.refinement_levels = 0;
  options.hill_climb_steps = 0;
  const double start[2] = {0.0137, 2.31};   // the exact minimum, not on the 3-point grid
  const SolveResult result = solve_coeff_search(problem, options, start, 0);
  EXPECT_EQ(result.parameters[0], 0.0137);
  EXPECT_EQ(result.parameters[1], 2.31);
  EXPECT_EQ(result.summary.initial_error, result.summary.final_error);
}

TEST(CoeffSearchSolver, RefusesOversizedGridsAndInfiniteContinuousBounds) {
  const auto problem = make_problem(ClampGammaError{}, Bounds{{0.0, 1.0}, {0.1, 3.0}});
  CoeffSearchOptions options;
  options.grid_points = 2000;
  try {
    solve_coeff_search(problem, options, nullptr, 0);
    FAIL() << "expected an Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("max_grid_points"), std::string::npos) << error.what();
  }
  const auto unbounded = make_problem(ClampGammaError{}, Bounds{{0.0, 1.0}, {0.1, std::numeric_limits<double>::infinity()}});
  EXPECT_THROW(solve_coeff_search(unbounded, CoeffSearchOptions{}, nullptr, 0), Error);
}

TEST(CoeffSearchSolver, OptionsResolveThroughTheRegistry) {
  const Solver& solver = find_solver("coeff_search");
  const auto problem = make_problem(ClampGammaError{}, Bounds{{0.0, 1.0}, {0.1, 3.0}});
  EXPECT_THROW(solver.solve(problem, {{"grid_points", "1"}}, nullptr, 0), Error);
  EXPECT_THROW(solver.solve(problem, {{"levels", "2"}}, nullptr, 0), Error);
  const SolveResult result = solver.solve(problem, {{"grid_points", "7"}, {"refinement_levels", "1"}}, nullptr, 0);
  EXPECT_EQ(result.summary.solver, "coeff_search");
  EXPECT_NEAR(result.parameters[1], 2.31, 1e-6);
}

}  // namespace
}  // namespace blocklab
