// The `exhaustive` solver (solvers/exhaustive/exhaustive_solver.h), the solver interface pieces it exercises
// (Termination strings, Summary, option resolution) and the solver registry.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "core/error.h"
#include "core/problem.h"
#include "solvers/exhaustive/exhaustive_solver.h"
#include "solvers/registry.h"
#include "tests/contract/example_problems.h"

namespace blocklab {
namespace {

// The BC4-like palette error written out again as plain double code, independently of the templated functor:
// palette entry k = e0 (3 - k)/3 + e1 k/3, error = sum over texels of the smallest squared distance.
double independent_palette_error(const examples::PaletteFitError& block, double e0, double e1) {
  double total = 0.0;
  for (double texel : block.texels) {
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 4; ++k) {
      const double entry = e0 * ((3.0 - k) / 3.0) + e1 * (k / 3.0);
      const double distance = (texel - entry) * (texel - entry);
      if (distance < best) best = distance;
    }
    total += best;
  }
  return total;
}

ErrorProblem<examples::PaletteFitError> coarse_palette_problem(std::int64_t levels) {
  return make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}},
                      {Lattice::uniform(0.0, 1.0, levels), Lattice::uniform(0.0, 1.0, levels)});
}

TEST(ExhaustiveSolver, FindsTheTrueMinimumOfThePaletteFitOnACoarseLattice) {
  const auto problem = coarse_palette_problem(64);
  const SolveResult result = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 1);

  // Independent brute force: nested loops, first strictly smaller error wins.
  const Lattice lattice = Lattice::uniform(0.0, 1.0, 64);
  double best = std::numeric_limits<double>::infinity();
  std::int64_t best_i = -1, best_j = -1;
  for (std::int64_t i = 0; i < 64; ++i)
    for (std::int64_t j = 0; j < 64; ++j) {
      const double error = independent_palette_error(problem.error(), lattice.point(i), lattice.point(j));
      if (error < best) { best = error; best_i = i; best_j = j; }
    }

  ASSERT_EQ(result.lattice_indices.size(), 2u);
  EXPECT_EQ(result.lattice_indices[0], best_i);
  EXPECT_EQ(result.lattice_indices[1], best_j);
  EXPECT_NEAR(result.summary.final_error, best, 1e-15);
  EXPECT_EQ(result.parameters[0], lattice.point(best_i));
  EXPECT_EQ(result.parameters[1], lattice.point(best_j));
  EXPECT_EQ(result.summary.termination, Termination::optimal);
  EXPECT_EQ(result.summary.evaluations, 64u * 64u);
  EXPECT_EQ(result.summary.lower_bound, result.summary.final_error);
  EXPECT_EQ(result.summary.gap, 0.0);
  EXPECT_TRUE(std::isnan(result.summary.initial_error));   // no start point given
}

// Three parameters with different counts: the odometer visits every tuple exactly once.
TEST(ExhaustiveSolver, EnumeratesEveryTupleOfAThreeParameterLattice) {
  const auto problem = make_problem(examples::log_yuv_fit_example(), Bounds{{-8.0, 0.05, 0.05}, {8.0, 0.45, 0.45}},
                                    {Lattice::uniform(-8.0, 8.0, 17), Lattice::uniform(0.05, 0.45, 9),
                                     Lattice::uniform(0.05, 0.45, 5)});
  const SolveResult result = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 3);
  double best = std::numeric_limits<double>::infinity();
  std::int64_t best_tuple[3] = {-1, -1, -1};
  for (std::int64_t a = 0; a < 17; ++a)
    for (std::int64_t b = 0; b < 9; ++b)
      for (std::int64_t c = 0; c < 5; ++c) {
        const double x[3] = {problem.lattice(0).point(a), problem.lattice(1).point(b), problem.lattice(2).point(c)};
        const double error = problem.eval(x);
        if (error < best) { best = error; best_tuple[0] = a; best_tuple[1] = b; best_tuple[2] = c; }
      }
  EXPECT_EQ(result.summary.evaluations, 17u * 9u * 5u);
  EXPECT_EQ(result.summary.final_error, best);
  EXPECT_EQ(result.lattice_indices, (std::vector<std::int64_t>{best_tuple[0], best_tuple[1], best_tuple[2]}));
}

// min((x - 0.25)^2, (x - 0.75)^2): exactly zero at both 0.25 and 0.75.
struct TwoEqualMinimaError {
  static constexpr int kDim = 1;
  template <typename T>
  T operator()(const T* x) const { return min(square(x[0] - T(0.25)), square(x[0] - T(0.75))); }
};

TEST(ExhaustiveSolver, TiesGoToTheLowestLatticeIndex) {
  const auto problem = make_problem(TwoEqualMinimaError{}, Bounds{{0.0}, {1.0}}, {Lattice::uniform(0.0, 1.0, 5)});
  const SolveResult result = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 1);
  EXPECT_EQ(result.lattice_indices, std::vector<std::int64_t>{1});
  EXPECT_EQ(result.parameters[0], 0.25);
  EXPECT_EQ(result.summary.final_error, 0.0);
}

// sqrt(x - 0.5) - x: NaN below 0.5.
struct NaNBelowHalfError {
  static constexpr int kDim = 1;
  template <typename T>
  T operator()(const T* x) const {
    using std::sqrt;
    return sqrt(x[0] - T(0.5)) - x[0];
  }
};

TEST(ExhaustiveSolver, SkipsPointsWithANaNError) {
  const auto problem = make_problem(NaNBelowHalfError{}, Bounds{{0.0}, {1.0}}, {Lattice::uniform(0.0, 1.0, 11)});
  const SolveResult result = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 1);
  EXPECT_EQ(result.summary.termination, Termination::optimal);
  EXPECT_FALSE(std::isnan(result.summary.final_error));
  EXPECT_GE(result.parameters[0], 0.5);
  EXPECT_NE(result.summary.message.find("5 with a NaN error skipped"), std::string::npos) << result.summary.message;
}

TEST(ExhaustiveSolver, ReportsFailureWhenEveryPointIsInvalid) {
  const auto problem = make_problem(NaNBelowHalfError{}, Bounds{{0.0}, {0.4}}, {Lattice::uniform(0.0, 0.4, 5)});
  const SolveResult result = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 1);
  EXPECT_EQ(result.summary.termination, Termination::failed);
  EXPECT_TRUE(std::isnan(result.summary.final_error));
  EXPECT_FALSE(result.summary.has_lower_bound());
  ASSERT_EQ(result.parameters.size(), 1u);
  EXPECT_EQ(result.parameters[0], 0.0);
}

TEST(ExhaustiveSolver, RecordsTheStartErrorAndCountsItsEvaluation) {
  const auto problem = coarse_palette_problem(16);
  const double start[2] = {0.0, 1.0};
  const SolveResult result = solve_exhaustive(problem, ExhaustiveOptions{}, start, 42);
  EXPECT_EQ(result.summary.initial_error, problem.eval(start));
  EXPECT_EQ(result.summary.evaluations, 16u * 16u + 1u);
  EXPECT_LE(result.summary.final_error, result.summary.initial_error);   // the start is a lattice point here
  EXPECT_EQ(result.summary.seed, 42u);
}

TEST(ExhaustiveSolver, IsDeterministicWhateverTheSeed) {
  const auto problem = coarse_palette_problem(32);
  const SolveResult first = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 1);
  const SolveResult second = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 987654321);
  EXPECT_EQ(first.parameters, second.parameters);
  EXPECT_EQ(first.summary.final_error, second.summary.final_error);
}

TEST(ExhaustiveSolver, RefusesALatticeLargerThanMaxPoints) {
  const auto problem = coarse_palette_problem(64);
  ExhaustiveOptions options;
  options.max_points = 4095;
  try {
    solve_exhaustive(problem, options, nullptr, 1);
    FAIL() << "a 4096-point lattice was accepted with max_points = 4095";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("exhaustive"), std::string::npos) << message;
    EXPECT_NE(message.find("4096 points"), std::string::npos) << message;
    EXPECT_NE(message.find("max_points = 4095"), std::string::npos) << message;
  }
  options.max_points = 4096;
  EXPECT_NO_THROW(solve_exhaustive(problem, options, nullptr, 1));
}

TEST(ExhaustiveSolver, RefusesAParameterWithoutALattice) {
  const auto problem = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}},
                                    {Lattice::uniform(0.0, 1.0, 8), Lattice::none()});
  try {
    solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 1);
    FAIL() << "a continuous parameter was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("parameter 1 has no storage lattice"), std::string::npos)
        << error.what();
  }
}

TEST(ExhaustiveOptions, IsValidExplainsAnOutOfRangeMaxPoints) {
  ExhaustiveOptions options;
  std::string why;
  EXPECT_TRUE(options.is_valid(&why));
  options.max_points = 0;
  EXPECT_FALSE(options.is_valid(&why));
  EXPECT_NE(why.find("max_points"), std::string::npos);
  EXPECT_FALSE(options.is_valid(nullptr));
  EXPECT_THROW(solve_exhaustive(coarse_palette_problem(4), options, nullptr, 1), Error);
}

TEST(SolverOptions, ResolutionFillsDefaultsNormalisesAndRejectsUnknownKeys) {
  const Solver& solver = exhaustive_solver();
  const SolverOptions defaults = resolve_solver_options(solver, {});
  EXPECT_EQ(defaults, (SolverOptions{{"max_points", "4194304"}, {"time_limit", "10"}}));
  EXPECT_EQ(resolve_solver_options(solver, {{"max_points", "+0100"}}).at("max_points"), "100");
  // Idempotent: resolving a resolved map changes nothing.
  EXPECT_EQ(resolve_solver_options(solver, defaults), defaults);
  try {
    resolve_solver_options(solver, {{"max_pionts", "10"}});
    FAIL() << "a misspelled key was accepted";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()), "exhaustive: unknown option 'max_pionts'; valid options: max_points, time_limit");
  }
  // The formats' common `seed` key is not a solver option: the seed is an argument of solve().
  EXPECT_THROW(resolve_solver_options(solver, {{"seed", "3"}}), Error);
  EXPECT_THROW(resolve_solver_options(solver, {{"max_points", "0"}}), Error);
  EXPECT_THROW(resolve_solver_options(solver, {{"max_points", "many"}}), Error);
}

TEST(SolverInterface, SolveThroughTheRegistryUsesStringOptions) {
  const auto problem = coarse_palette_problem(64);
  const Solver& solver = find_solver("exhaustive");
  const SolveResult via_interface = solver.solve(problem, {{"max_points", "5000"}}, nullptr, 5);
  const SolveResult direct = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 5);
  EXPECT_EQ(via_interface.parameters, direct.parameters);
  EXPECT_EQ(via_interface.summary.solver, "exhaustive");
  EXPECT_THROW(solver.solve(problem, {{"max_points", "100"}}, nullptr, 5), Error);
  EXPECT_THROW(solver.solve(problem, {{"unknown", "1"}}, nullptr, 5), Error);
}

TEST(Termination, RoundTripsThroughStringsAndRejectsUnknownNames) {
  std::set<std::string> names;
  for (Termination termination : all_terminations()) {
    const std::string name = to_string(termination);
    EXPECT_TRUE(names.insert(name).second) << "duplicate name " << name;
    EXPECT_EQ(termination_from_string(name), termination);
  }
  EXPECT_EQ(names.size(), 7u);
  try {
    termination_from_string("done");
    FAIL() << "an unknown termination was accepted";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("unknown termination 'done'"), std::string::npos) << message;
    EXPECT_NE(message.find("optimal, converged"), std::string::npos) << message;
  }
}

TEST(Summary, BriefReportStatesTerminationErrorsBoundAndCounts) {
  const SolveResult result = solve_exhaustive(coarse_palette_problem(8), ExhaustiveOptions{}, nullptr, 7);
  const std::string report = result.summary.brief_report();
  EXPECT_EQ(report.rfind("exhaustive: optimal, error nan -> ", 0), 0u) << report;
  EXPECT_NE(report.find("lower bound"), std::string::npos) << report;
  EXPECT_NE(report.find("gap 0"), std::string::npos) << report;
  EXPECT_NE(report.find("64 evaluations"), std::string::npos) << report;
  EXPECT_NE(report.find("seed 7"), std::string::npos) << report;
  Summary unproven;
  unproven.solver = "x";
  EXPECT_EQ(unproven.brief_report().find("lower bound"), std::string::npos);
}

TEST(SolverRegistry, NamesAreUniqueAndEveryDefaultOptionSetResolves) {
  std::set<std::string> names;
  for (const Solver* solver : all_solvers()) {
    EXPECT_TRUE(names.insert(solver->name()).second) << solver->name();
    EXPECT_FALSE(solver->description().empty());
    EXPECT_NO_THROW(resolve_solver_options(*solver, {}));
    EXPECT_EQ(&find_solver(solver->name()), solver);
  }
  EXPECT_TRUE(names.count("exhaustive"));
}

TEST(SolverRegistry, UnknownNameListsTheValidSolvers) {
  try {
    find_solver("exhaustiv");
    FAIL() << "an unknown solver was found";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("unknown solver 'exhaustiv'"), std::string::npos) << message;
    EXPECT_NE(message.find("valid solvers: exhaustive"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace blocklab
