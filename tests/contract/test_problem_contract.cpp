// The Problem contract (tests/contract/problem_contract.h) on real small problems (tests/contract/
// example_problems.h) and on every registered format's every block problem (Format::block_problems(), drawn from
// real blocks of the bundled samples by tests/contract/registered_problem_checks.h: a format that declares a problem
// is covered without an edit here), plus the adapter's own behaviour: validation of bounds and lattices, residual
// detection, the empty-enclosure rule and concurrent evaluation.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <thread>
#include <type_traits>
#include <vector>

#include "core/error.h"
#include "core/problem.h"
#include "tests/contract/example_problems.h"
#include "tests/contract/problem_contract.h"
#include "tests/contract/registered_problem_checks.h"

namespace blocklab {
namespace {

using examples::ExponentialFitError;
using examples::GammaFitError;
using examples::LogYuvFitError;
using examples::PaletteFitError;

class RegisteredBlockProblemContract : public ::testing::TestWithParam<std::string> {};

TEST_P(RegisteredBlockProblemContract, HoldsTheContractOnRealBlocks) {
  contract::check_registered_problem_contract(find_block_problem(GetParam()));
}

INSTANTIATE_TEST_SUITE_P(Formats, RegisteredBlockProblemContract,
                         ::testing::ValuesIn(contract::registered_problem_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return contract::test_name_of(info.param);
                         });

TEST(ProblemContract, ExponentialCurveFitHoldsTheContract) {
  const auto problem = make_problem(examples::exponential_fit_example(), Bounds{{0.5, -2.0}, {3.0, 0.5}});
  EXPECT_TRUE(problem.is_smooth());
  EXPECT_EQ(problem.residual_count(), 8);
  contract::check_problem_contract(problem);
}

TEST(ProblemContract, PaletteEndpointFitHoldsTheContract) {
  const auto problem = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}},
                                    {Lattice::uniform(0.0, 1.0, 256), Lattice::uniform(0.0, 1.0, 256)});
  EXPECT_FALSE(problem.is_smooth());
  EXPECT_EQ(problem.residual_count(), 0);
  contract::check_problem_contract(problem);
}

TEST(ProblemContract, LogYuvFitWithExp2AndLog2HoldsTheContract) {
  const auto problem =
      make_problem(examples::log_yuv_fit_example(), Bounds{{-8.0, 0.05, 0.05}, {8.0, 0.45, 0.45}});
  contract::check_problem_contract(problem);
}

TEST(ProblemContract, RealExponentGammaFitHoldsTheContract) {
  const auto problem = make_problem(examples::gamma_fit_example(), Bounds{{0.5, 0.3}, {2.0, 3.0}});
  contract::check_problem_contract(problem);
}

TEST(ProblemContract, BranchAndBoundSizedBoxesStayTight) {
  // Enclosures must shrink with the box (what makes branch-and-bound converge): on a 1e-6 box around a point the
  // palette error's enclosure is within a small multiple of the error's variation.
  const auto problem = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}});
  const double x[2] = {0.21, 0.83};
  const Interval box[2] = {Interval(x[0] - 1e-6, x[0] + 1e-6), Interval(x[1] - 1e-6, x[1] + 1e-6)};
  const Interval enclosure = problem.eval(box);
  EXPECT_TRUE(contains(enclosure, problem.eval(x)));
  EXPECT_LT(width(enclosure), 1e-4) << to_string(enclosure);
}

// ---- the contract catches broken problems (each breaks one evaluation path on purpose) ------------------------

// Interval path returns the error at the box centre only: not an enclosure.
struct CentreOnlyIntervalError {
  static constexpr int kDim = 1;
  static constexpr bool kSmooth = true;
  template <typename T>
  T operator()(const T* x) const {
    if constexpr (std::is_same_v<T, Interval>) {
      return Interval(square(midpoint(x[0]) - 0.3));
    } else {
      return square(x[0] - T(0.3));
    }
  }
};

// Jet path has the right value but a wrong derivative (3x instead of 2x).
struct WrongDerivativeError {
  static constexpr int kDim = 1;
  static constexpr bool kSmooth = true;
  template <typename T>
  T operator()(const T* x) const {
    if constexpr (std::is_same_v<T, ceres::Jet<double, 1>>) {
      // Value a^2, derivative 3a (the constant part carries the value, the linear part the wrong slope).
      return T(x[0].a * x[0].a) + T(3.0 * x[0].a) * (x[0] - T(x[0].a));
    } else {
      return square(x[0]);
    }
  }
};

// Residuals that do not square-sum to the error.
struct InconsistentResidualsError {
  static constexpr int kDim = 1;
  static constexpr int kResiduals = 1;
  static constexpr bool kSmooth = true;
  template <typename T>
  void residuals(const T* x, T* r) const { r[0] = x[0]; }
  template <typename T>
  T operator()(const T* x) const { return T(2.0) * square(x[0]); }
};

void check_centre_only_interval() {
  contract::check_problem_contract(make_problem(CentreOnlyIntervalError{}, Bounds{{-1.0}, {1.0}}));
}
void check_wrong_derivative() {
  contract::check_problem_contract(make_problem(WrongDerivativeError{}, Bounds{{-1.0}, {1.0}}));
}
void check_inconsistent_residuals() {
  contract::check_problem_contract(make_problem(InconsistentResidualsError{}, Bounds{{-1.0}, {1.0}}));
}

// Runs `check` with its GoogleTest failures intercepted; returns how many failure messages contain `text`.
int intercepted_failures_containing(void (*check)(), const std::string& text) {
  ::testing::TestPartResultArray results;
  {
    ::testing::ScopedFakeTestPartResultReporter reporter(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
    check();
  }
  int matching = 0;
  for (int i = 0; i < results.size(); ++i)
    if (std::string(results.GetTestPartResult(i).message()).find(text) != std::string::npos) ++matching;
  return matching;
}

TEST(ProblemContractSelfTest, DetectsAnIntervalErrorThatIsNotAnEnclosure) {
  EXPECT_GT(intercepted_failures_containing(check_centre_only_interval, "is outside the box error"), 0);
}

TEST(ProblemContractSelfTest, DetectsAJetGradientThatDisagreesWithFiniteDifferences) {
  EXPECT_GT(intercepted_failures_containing(check_wrong_derivative, "central difference"), 0);
}

TEST(ProblemContractSelfTest, DetectsResidualsWhoseSquaresDoNotSumToTheError) {
  EXPECT_GT(intercepted_failures_containing(check_inconsistent_residuals, "is not the sum of squared residuals"), 0);
}

// An error that is undefined (log of a negative number) on part of its domain.
struct LogOfParameterError {
  static constexpr int kDim = 1;
  template <typename T>
  T operator()(const T* x) const {
    using std::log;
    return log(x[0]);
  }
};

TEST(Problem, EmptyEnclosureIsReturnedAsTheWholeLine) {
  const auto problem = make_problem(LogOfParameterError{}, Bounds{{-2.0}, {2.0}});
  const Interval negative_box[1] = {Interval(-2.0, -1.0)};
  const Interval enclosure = problem.eval(negative_box);
  EXPECT_FALSE(is_empty(enclosure));
  EXPECT_EQ(enclosure.lower(), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(enclosure.upper(), std::numeric_limits<double>::infinity());
  const double negative_point[1] = {-1.5};
  EXPECT_TRUE(std::isnan(problem.eval(negative_point)));
}

TEST(Problem, RejectsBoundsOfTheWrongSize) {
  EXPECT_THROW(make_problem(examples::palette_fit_example(), Bounds{{0.0}, {1.0}}), Error);
  EXPECT_THROW(make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0}}), Error);
}

TEST(Problem, RejectsInvertedOrNaNBoundsNamingTheParameter) {
  try {
    make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.8}, {1.0, 0.2}});
    FAIL() << "inverted bounds were accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("parameter 1"), std::string::npos) << error.what();
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(make_problem(examples::palette_fit_example(), Bounds{{nan, 0.0}, {1.0, 1.0}}), Error);
}

TEST(Problem, RejectsLatticesOutsideTheBoundsOrOfTheWrongCount) {
  const Bounds unit{{0.0, 0.0}, {1.0, 1.0}};
  EXPECT_THROW(make_problem(examples::palette_fit_example(), unit, {Lattice::uniform(0.0, 1.0, 4)}), Error);
  EXPECT_THROW(make_problem(examples::palette_fit_example(), unit,
                            {Lattice::uniform(0.0, 1.0, 4), Lattice::uniform(0.0, 1.5, 4)}),
               Error);
  Lattice zero_step{0.0, 0.0, 3};
  EXPECT_THROW(make_problem(examples::palette_fit_example(), unit, {zero_step, Lattice::none()}), Error);
}

TEST(Problem, AcceptsMixedLatticeAndContinuousParameters) {
  const auto problem = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}},
                                    {Lattice::uniform(0.0, 1.0, 16), Lattice::none()});
  EXPECT_TRUE(problem.lattice(0).present());
  EXPECT_FALSE(problem.lattice(1).present());
  EXPECT_FALSE(problem.has_full_lattice());
  EXPECT_EQ(problem.lattice_point_count(), 0u);
}

TEST(Problem, WithoutLatticesEveryParameterIsContinuous) {
  const auto problem = make_problem(examples::exponential_fit_example(), Bounds{{0.5, -2.0}, {3.0, 0.5}});
  EXPECT_EQ(problem.dim(), 2);
  EXPECT_FALSE(problem.lattice(0).present());
  EXPECT_FALSE(problem.lattice(1).present());
}

TEST(Problem, LatticePointCountIsTheProductAndSaturates) {
  const auto small = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}},
                                  {Lattice::uniform(0.0, 1.0, 32), Lattice::uniform(0.0, 1.0, 64)});
  EXPECT_TRUE(small.has_full_lattice());
  EXPECT_EQ(small.lattice_point_count(), 32u * 64u);
  const Lattice huge{0.0, 1e-30, std::int64_t{1} << 40};
  const auto big = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}}, {huge, huge});
  EXPECT_EQ(big.lattice_point_count(), std::numeric_limits<std::uint64_t>::max());
}

TEST(Lattice, UniformLatticeHitsBothEndsAndRoundsToNearestIndex) {
  const Lattice lattice = Lattice::uniform(0.0, 1.0, 256);
  EXPECT_EQ(lattice.point(0), 0.0);
  EXPECT_NEAR(lattice.point(255), 1.0, 1e-15);
  EXPECT_EQ(lattice.nearest_index(0.5 / 255.0 + 1e-12), 1);
  EXPECT_EQ(lattice.nearest_index(0.5 / 255.0 - 1e-12), 0);
  EXPECT_EQ(lattice.nearest_index(-3.0), 0);
  EXPECT_EQ(lattice.nearest_index(7.0), 255);
  EXPECT_EQ(lattice.nearest_index(std::numeric_limits<double>::quiet_NaN()), 0);
  for (std::int64_t k = 0; k < 256; ++k) EXPECT_EQ(lattice.nearest_index(lattice.point(k)), k);
  const Lattice single = Lattice::uniform(0.25, 0.25, 1);
  EXPECT_EQ(single.point(0), 0.25);
  EXPECT_EQ(single.nearest_index(0.9), 0);
  EXPECT_THROW(Lattice::uniform(1.0, 0.0, 4), Error);
  EXPECT_THROW(Lattice::uniform(0.0, 1.0, 0), Error);
}

TEST(Problem, ResidualsThrowWhenTheErrorDeclaresNone) {
  const auto problem = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}});
  const double x[2] = {0.1, 0.9};
  double residual = 0.0;
  EXPECT_THROW(problem.eval_residuals(x, &residual, nullptr), Error);
}

TEST(Problem, JacobianIsRowMajorResidualByParameter) {
  const auto problem = make_problem(examples::exponential_fit_example(), Bounds{{0.5, -2.0}, {3.0, 0.5}});
  const double x[2] = {1.2, -0.4};
  double residuals[8], jacobian[16];
  problem.eval_residuals(x, residuals, jacobian);
  const ExponentialFitError& error = problem.error();
  for (int r = 0; r < 8; ++r) {
    const double e = std::exp(x[1] * error.t[static_cast<std::size_t>(r)]);
    EXPECT_NEAR(jacobian[r * 2 + 0], e, 1e-14);                                          // d/da
    EXPECT_NEAR(jacobian[r * 2 + 1], x[0] * error.t[static_cast<std::size_t>(r)] * e, 1e-14);   // d/db
  }
}

TEST(Problem, ConcurrentEvaluationGivesTheSameResultsAsSerial) {
  const auto problem = make_problem(examples::log_yuv_fit_example(), Bounds{{-8.0, 0.05, 0.05}, {8.0, 0.45, 0.45}});
  constexpr int kPoints = 2000;
  std::vector<double> serial(kPoints), parallel(kPoints);
  const auto point = [](int k, double* x) {
    x[0] = -8.0 + 16.0 * ((k * 37) % 1000) / 1000.0;
    x[1] = 0.05 + 0.4 * ((k * 91) % 997) / 997.0;
    x[2] = 0.05 + 0.4 * ((k * 53) % 991) / 991.0;
  };
  for (int k = 0; k < kPoints; ++k) {
    double x[3];
    point(k, x);
    serial[static_cast<std::size_t>(k)] = problem.eval(x);
  }
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int k = t; k < kPoints; k += 4) {
        double x[3], gradient[3];
        point(k, x);
        parallel[static_cast<std::size_t>(k)] = problem.eval(x);
        problem.eval_with_gradient(x, gradient);
      }
    });
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(serial, parallel);
}

}  // namespace
}  // namespace blocklab
