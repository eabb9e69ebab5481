// The `nlopt` solver (solvers/nlopt/nlopt_solver.h): algorithms by NLopt name, Jet gradients for LD algorithms,
// bounds, seeding and thread determinism of stochastic algorithms, errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/problem.h"
#include "solvers/ceres_lm/ceres_lm_solver.h"
#include "solvers/nlopt/nlopt_solver.h"
#include "solvers/registry.h"
#include "tests/contract/example_problems.h"

namespace blocklab {
namespace {

ErrorProblem<examples::ExponentialFitError> exponential_problem() {
  return make_problem(examples::exponential_fit_example(), Bounds{{0.0, -3.0}, {3.0, 0.0}});
}

// The least-squares optimum of the exponential fit, from Levenberg-Marquardt (tests/unit/test_ceres_lm_solver.cpp
// checks that one to 1e-8).
std::vector<double> exponential_optimum() {
  const auto problem = exponential_problem();
  const double start[2] = {1.0, -1.0};
  return solve_ceres_lm(problem, CeresLmOptions{}, start, 0).parameters;
}

TEST(NloptSolver, LocalAlgorithmsReachTheExponentialFitOptimum) {
  const auto problem = exponential_problem();
  const std::vector<double> optimum = exponential_optimum();
  const double optimum_error = problem.eval(optimum.data());
  const double start[2] = {1.0, -1.0};
  for (const char* algorithm : {"LN_NELDERMEAD", "LN_SBPLX", "LN_BOBYQA", "LN_COBYLA", "LD_LBFGS", "LD_MMA",
                                "LD_SLSQP"}) {
    NloptOptions options;
    options.algorithm = algorithm;
    options.max_evaluations = 5000;
    const SolveResult result = solve_nlopt(problem, options, start, 0);
    EXPECT_NE(result.summary.termination, Termination::failed) << result.summary.brief_report();
    // Error within 1e-9 relative of the optimum; parameters within 1e-4 (the error is flat to second order).
    EXPECT_NEAR(result.summary.final_error, optimum_error, 1e-9 * optimum_error) << algorithm;
    EXPECT_NEAR(result.parameters[0], optimum[0], 1e-4) << algorithm;
    EXPECT_NEAR(result.parameters[1], optimum[1], 1e-4) << algorithm;
    const bool gradient_based = algorithm[1] == 'D';
    EXPECT_EQ(result.summary.gradient_evaluations > 0, gradient_based) << algorithm;
    EXPECT_EQ(result.summary.final_error, problem.eval(result.parameters.data())) << algorithm;
  }
}

// Two wells: (x - 0.2)^2 (x - 0.9)^2 + 0.01 x over [0, 1]; the global minimum is the left well near 0.2.
struct TwoWellsError {
  static constexpr int kDim = 1;
  static constexpr bool kSmooth = true;
  template <typename T>
  T operator()(const T* x) const {
    return square(x[0] - T(0.2)) * square(x[0] - T(0.9)) + T(0.01) * x[0];
  }
};

TEST(NloptSolver, GlobalAlgorithmsFindTheDeeperWell) {
  const auto problem = make_problem(TwoWellsError{}, Bounds{{0.0}, {1.0}});
  for (const char* algorithm : {"GN_DIRECT_L", "GN_CRS2_LM", "GN_ISRES", "GN_ESCH"}) {
    NloptOptions options;
    options.algorithm = algorithm;
    options.max_evaluations = 3000;
    const SolveResult result = solve_nlopt(problem, options, nullptr, 17);
    EXPECT_NEAR(result.parameters[0], 0.2, 0.02) << algorithm << ": " << result.summary.brief_report();
  }
}

TEST(NloptSolver, StaysInsideTheBoundsAndClampsTheStart) {
  // The unconstrained optimum (a ~ 1.5, b ~ -0.7) is outside a <= 1: the answer lies on a = 1.
  const auto problem = make_problem(examples::exponential_fit_example(), Bounds{{0.0, -3.0}, {1.0, 0.0}});
  const double outside[2] = {5.0, -10.0};
  NloptOptions options;
  options.algorithm = "LN_BOBYQA";
  const SolveResult result = solve_nlopt(problem, options, outside, 0);
  EXPECT_EQ(result.summary.initial_error, problem.eval(outside));
  EXPECT_LE(result.parameters[0], 1.0);
  EXPECT_NEAR(result.parameters[0], 1.0, 1e-6);
  EXPECT_GE(result.parameters[1], -3.0);
}

TEST(NloptSolver, SameSeedSameAnswerForAStochasticAlgorithm) {
  const auto problem = exponential_problem();
  NloptOptions options;
  options.algorithm = "GN_CRS2_LM";
  options.max_evaluations = 400;
  options.population = 30;
  const SolveResult a = solve_nlopt(problem, options, nullptr, 99);
  const SolveResult b = solve_nlopt(problem, options, nullptr, 99);
  EXPECT_EQ(a.parameters, b.parameters);
  EXPECT_EQ(a.summary.final_error, b.summary.final_error);
  EXPECT_EQ(a.summary.evaluations, b.summary.evaluations);
  bool any_differs = false;
  for (std::uint64_t seed = 100; seed < 104; ++seed)
    if (solve_nlopt(problem, options, nullptr, seed).parameters != a.parameters) any_differs = true;
  EXPECT_TRUE(any_differs);
}

TEST(NloptSolver, StochasticSolvesOnFourThreadsMatchTheSequentialAnswers) {
  const auto problem = exponential_problem();
  NloptOptions options;
  options.algorithm = "GN_ISRES";
  options.max_evaluations = 300;
  constexpr int kSolves = 8;
  std::vector<std::vector<double>> sequential(kSolves), threaded(kSolves);
  for (int i = 0; i < kSolves; ++i) sequential[i] = solve_nlopt(problem, options, nullptr, 1000 + i).parameters;
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int i = t; i < kSolves; i += 4) threaded[i] = solve_nlopt(problem, options, nullptr, 1000 + i).parameters;
    });
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(sequential, threaded);
}

TEST(NloptSolver, ClassifiesStochasticAlgorithms) {
  for (const char* name : {"GN_CRS2_LM", "GN_ISRES", "GN_ESCH", "GN_DIRECT_L_RAND", "GN_MLSL", "G_MLSL_LDS", "LN_PRAXIS"})
    EXPECT_TRUE(nlopt_algorithm_is_stochastic(name)) << name;
  for (const char* name : {"GN_DIRECT_L", "LN_NELDERMEAD", "LN_SBPLX", "LN_BOBYQA", "LD_LBFGS", "LD_MMA"})
    EXPECT_FALSE(nlopt_algorithm_is_stochastic(name)) << name;
}

TEST(NloptSolver, UnknownAlgorithmIsAnErrorListingTheValidNames) {
  const auto problem = exponential_problem();
  try {
    nlopt_solver().solve(problem, {{"algorithm", "LN_NELDERMAED"}}, nullptr, 0);
    FAIL() << "expected an Error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("LN_NELDERMAED"), std::string::npos) << message;
    EXPECT_NE(message.find("LN_NELDERMEAD"), std::string::npos) << message;
    EXPECT_NE(message.find("GN_DIRECT_L"), std::string::npos) << message;
  }
  NloptOptions options;
  options.algorithm = "SIMPLEX";
  std::string why;
  EXPECT_FALSE(options.is_valid(&why));
  EXPECT_NE(why.find("LD_LBFGS"), std::string::npos) << why;
  const auto& names = nlopt_algorithm_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "LN_SBPLX"), names.end());
}

TEST(NloptSolver, GlobalAlgorithmsNeedFiniteBounds) {
  const auto problem = make_problem(examples::exponential_fit_example(),
                                    Bounds{{0.0, -std::numeric_limits<double>::infinity()}, {3.0, 0.0}});
  NloptOptions options;
  options.algorithm = "GN_DIRECT_L";
  EXPECT_THROW(solve_nlopt(problem, options, nullptr, 0), Error);
  options.algorithm = "LN_SBPLX";   // local: fine with an infinite bound
  const double start[2] = {1.0, -1.0};
  EXPECT_NE(solve_nlopt(problem, options, start, 0).summary.termination, Termination::failed);
}

TEST(NloptSolver, AlgorithmsWithASubsidiaryOptimiserUseLocalAlgorithm) {
  const auto problem = make_problem(TwoWellsError{}, Bounds{{0.0}, {1.0}});
  NloptOptions options;
  options.algorithm = "G_MLSL_LDS";
  options.local_algorithm = "LN_BOBYQA";
  options.max_evaluations = 2000;
  const SolveResult result = solve_nlopt(problem, options, nullptr, 5);
  EXPECT_NEAR(result.parameters[0], 0.2, 0.02) << result.summary.brief_report();
}

TEST(NloptSolver, HonoursMaxEvaluationsAndInitialStep) {
  const auto problem = exponential_problem();
  const double start[2] = {1.0, -1.0};
  const SolveResult result =
      nlopt_solver().solve(problem, {{"algorithm", "LN_NELDERMEAD"}, {"max_evaluations", "25"},
                                     {"initial_step", "0.25"}}, start, 0);
  EXPECT_EQ(result.summary.termination, Termination::max_evaluations) << result.summary.brief_report();
  EXPECT_EQ(result.summary.evaluations, 25u + 1u);   // 25 by NLopt + the start error
  EXPECT_LT(result.summary.final_error, result.summary.initial_error);
}

// sqrt(x - 0.5) + (x - 0.8)^2: NaN below 0.5.
struct NaNBelowHalfError {
  static constexpr int kDim = 1;
  template <typename T>
  T operator()(const T* x) const {
    using std::sqrt;
    return sqrt(x[0] - T(0.5)) + square(x[0] - T(0.8));
  }
};

TEST(NloptSolver, SkipsInvalidPointsAndFailsWhenNoPointIsValid) {
  const auto partly = make_problem(NaNBelowHalfError{}, Bounds{{0.0}, {1.0}});
  NloptOptions options;
  options.algorithm = "GN_DIRECT_L";
  options.max_evaluations = 500;
  const SolveResult result = solve_nlopt(partly, options, nullptr, 0);
  EXPECT_GE(result.parameters[0], 0.5);
  EXPECT_FALSE(std::isnan(result.summary.final_error));
  const auto invalid = make_problem(NaNBelowHalfError{}, Bounds{{0.0}, {0.4}});
  const SolveResult failed = solve_nlopt(invalid, options, nullptr, 0);
  EXPECT_EQ(failed.summary.termination, Termination::failed);
  EXPECT_TRUE(std::isnan(failed.summary.final_error));
}

}  // namespace
}  // namespace blocklab
