// The `interval_bb` solver (solvers/interval_bb/interval_bb_solver.h): certified lattice optimum equal to the
// brute-force `exhaustive` solver on every enumerable lattice (BC4-like palette on full 8-bit lattices, the 2D
// chroma shape fit on 4-bit lattices for many random point sets, both error kinds), budgets and gaps, start points,
// invalid points, option validation, determinism and thread safety.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"
#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "solvers/exhaustive/exhaustive_solver.h"
#include "solvers/interval_bb/interval_bb_solver.h"
#include "solvers/registry.h"
#include "tests/contract/example_problems.h"

namespace blocklab {
namespace {

// The 8-bit storage value k (origin + k * step: not always bit-equal to k / 255.0).
double q8(int k) { return Lattice::uniform(0.0, 1.0, 256).point(k); }

// Rounding allowance when comparing a B&B error with exhaustive's: both are double evaluations of lattice points,
// so they are equal unless two lattice points tie up to rounding (then either may be returned).
constexpr double kTieTolerance = 1e-13;

ShapeFitData random_block(std::mt19937_64& random, ShapeErrorKind kind, int bits) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ShapeFitData data;
  data.error_kind = kind;
  data.lattice_bits = bits;
  data.shape = ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
  // Clustered points around a few random chroma centres, like a real block, or uniform ones.
  const bool clustered = unit(random) < 0.5;
  Point2 centres[3];
  for (Point2& c : centres) c = {0.15 + 0.5 * unit(random), 0.15 + 0.5 * unit(random)};
  for (int i = 0; i < 16; ++i) {
    Point2 p = clustered ? centres[i % 3] : Point2{unit(random), unit(random)};
    if (clustered) {
      p.u = std::min(1.0, std::max(0.0, p.u + 0.05 * (unit(random) - 0.5)));
      p.v = std::min(1.0, std::max(0.0, p.v + 0.05 * (unit(random) - 0.5)));
    }
    data.points.push_back(p);
  }
  return data;
}

void expect_same_optimum(const Problem& problem, const SolveResult& bb, const SolveResult& brute) {
  ASSERT_EQ(brute.summary.termination, Termination::optimal);
  EXPECT_EQ(bb.summary.termination, Termination::optimal) << bb.summary.brief_report();
  const double tolerance = kTieTolerance * (1.0 + std::abs(brute.summary.final_error));
  EXPECT_NEAR(bb.summary.final_error, brute.summary.final_error, tolerance) << bb.summary.brief_report();
  // The answer is a lattice point whose recomputed error is the reported one.
  EXPECT_EQ(problem.eval(bb.parameters.data()), bb.summary.final_error);
  ASSERT_EQ(bb.lattice_indices.size(), static_cast<std::size_t>(problem.dim()));
  for (int p = 0; p < problem.dim(); ++p)
    EXPECT_EQ(bb.parameters[static_cast<std::size_t>(p)], problem.lattice(p).point(bb.lattice_indices[static_cast<std::size_t>(p)]));
  EXPECT_EQ(bb.summary.gap, 0.0);
  EXPECT_EQ(bb.summary.lower_bound, bb.summary.final_error);
  // A unique optimum is the same lattice point.
  if (std::abs(bb.summary.final_error - brute.summary.final_error) == 0.0 && bb.lattice_indices != brute.lattice_indices) {
    const double brute_at_bb = problem.eval(bb.parameters.data());
    EXPECT_EQ(brute_at_bb, brute.summary.final_error) << "different lattice point with a different error";
  }
}

TEST(IntervalBb, EqualsExhaustiveOnTheFullEightBitPaletteLattice) {
  const auto problem = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}},
                                    {Lattice::uniform(0.0, 1.0, 256), Lattice::uniform(0.0, 1.0, 256)});
  const SolveResult brute = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
  const SolveResult bb = solve_interval_bb(problem, IntervalBbOptions{}, nullptr, 0);
  expect_same_optimum(problem, bb, brute);
  EXPECT_LT(bb.summary.evaluations, brute.summary.evaluations / 10) << "the search should prune most of the lattice";
}

TEST(IntervalBb, EqualsExhaustiveOnRandomEightBitPaletteBlocks) {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 8; ++trial) {
    examples::PaletteFitError error;
    for (double& texel : error.texels) texel = trial % 2 ? unit(random) : 0.3 + 0.2 * unit(random);
    const auto problem = make_problem(error, Bounds{{0.0, 0.0}, {1.0, 1.0}},
                                      {Lattice::uniform(0.0, 1.0, 256), Lattice::uniform(0.0, 1.0, 256)});
    const SolveResult brute = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
    const SolveResult bb = solve_interval_bb(problem, IntervalBbOptions{}, nullptr, 0);
    expect_same_optimum(problem, bb, brute);
  }
}

void shape_fit_equals_exhaustive(ShapeErrorKind kind, std::uint64_t seed, int blocks,
                                 const IntervalBbOptions& options = IntervalBbOptions{}) {
  std::mt19937_64 random(seed);
  for (int trial = 0; trial < blocks; ++trial) {
    const ShapeFitProblem problem(random_block(random, kind, 4));   // 16^4 = 65536 lattice points
    const SolveResult brute = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
    const SolveResult bb = solve_interval_bb(problem, options, nullptr, 0);
    SCOPED_TRACE("block " + std::to_string(trial));
    expect_same_optimum(problem, bb, brute);
  }
}

TEST(IntervalBb, EqualsExhaustiveOnFourBitLinearShapeFits) { shape_fit_equals_exhaustive(ShapeErrorKind::linear, 21, 24); }

TEST(IntervalBb, EqualsExhaustiveOnFourBitStretchedShapeFits) {
  shape_fit_equals_exhaustive(ShapeErrorKind::stretched, 22, 16);
}

// leaf_points only changes how small boxes are settled (bounded and split, or every point evaluated): the
// certified optimum is the same with every box bounded down to single points and with large enumerated leaves.
TEST(IntervalBb, LeafEnumerationSizeDoesNotChangeTheOptimum) {
  IntervalBbOptions bound_every_box;
  bound_every_box.leaf_points = 1;
  shape_fit_equals_exhaustive(ShapeErrorKind::linear, 23, 6, bound_every_box);
  IntervalBbOptions large_leaves;
  large_leaves.leaf_points = 4096;
  shape_fit_equals_exhaustive(ShapeErrorKind::stretched, 24, 6, large_leaves);
}

TEST(IntervalBb, LeavesCoveringTheLatticeAreAPlainEnumeration) {
  std::mt19937_64 random(25);
  const ShapeFitProblem problem(random_block(random, ShapeErrorKind::linear, 3));   // 8^4 = 4096 lattice points
  IntervalBbOptions options;
  options.leaf_points = 4096;
  const SolveResult brute = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
  const SolveResult bb = solve_interval_bb(problem, options, nullptr, 0);
  expect_same_optimum(problem, bb, brute);
  // One enclosure (the whole lattice, never pruned below its own optimum), then every point once, plus the
  // root box's centre point.
  EXPECT_EQ(bb.summary.interval_evaluations, 1u);
  EXPECT_EQ(bb.summary.evaluations, 4096u + 1u);
}

TEST(IntervalBb, AStartPointOnlyHelpsAndIsReportedAsInitialError) {
  std::mt19937_64 random(3);
  const ShapeFitProblem problem(random_block(random, ShapeErrorKind::linear, 4));
  const SolveResult brute = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
  const SolveResult cold = solve_interval_bb(problem, IntervalBbOptions{}, nullptr, 0);
  // Warm start at the optimum itself: nothing better exists, so the search only proves it.
  const SolveResult warm = solve_interval_bb(problem, IntervalBbOptions{}, brute.parameters.data(), 0);
  expect_same_optimum(problem, warm, brute);
  EXPECT_EQ(warm.summary.initial_error, brute.summary.final_error);
  EXPECT_LE(warm.summary.interval_evaluations, cold.summary.interval_evaluations);
  EXPECT_TRUE(std::isnan(cold.summary.initial_error));
}

TEST(IntervalBb, ZeroErrorBlockIsSolvedExactlyAtEightBits) {
  ShapeFitData data;
  data.shape = ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
  data.points = {Point2{0.5, 0.5}};
  const double truth[4] = {q8(60), q8(80), q8(150), q8(100)};
  const auto landmarks = ShapeFitProblem(data).decoded_landmarks(truth);
  data.points.clear();
  for (int i = 0; i < 16; ++i) data.points.push_back(landmarks[static_cast<std::size_t>(i % 4)]);
  const ShapeFitProblem problem(data);
  const SolveResult bb = solve_interval_bb(problem, IntervalBbOptions{}, nullptr, 0);
  EXPECT_EQ(bb.summary.termination, Termination::optimal);
  EXPECT_EQ(bb.summary.final_error, 0.0);
  EXPECT_EQ(bb.summary.gap, 0.0);
}

TEST(IntervalBb, BoxBudgetStopsWithAProvenLowerBoundAndGap) {
  const auto problem = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}},
                                    {Lattice::uniform(0.0, 1.0, 256), Lattice::uniform(0.0, 1.0, 256)});
  const SolveResult brute = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
  IntervalBbOptions options;
  options.max_boxes = 20;
  const SolveResult bb = solve_interval_bb(problem, options, nullptr, 0);
  EXPECT_EQ(bb.summary.termination, Termination::max_evaluations);
  EXPECT_LE(bb.summary.interval_evaluations, 21u);
  EXPECT_GE(bb.summary.final_error, brute.summary.final_error);
  EXPECT_LE(bb.summary.lower_bound, brute.summary.final_error);   // the bound is proven: never above the optimum
  EXPECT_GT(bb.summary.gap, 0.0);
  EXPECT_EQ(bb.summary.gap, bb.summary.final_error - bb.summary.lower_bound);
}

TEST(IntervalBb, RelativeGapBoundsTheDistanceToTheOptimum) {
  std::mt19937_64 random(8);
  for (int trial = 0; trial < 6; ++trial) {
    const ShapeFitProblem problem(random_block(random, ShapeErrorKind::linear, 4));
    const SolveResult brute = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
    IntervalBbOptions options;
    options.relative_gap = 0.05;
    const SolveResult bb = solve_interval_bb(problem, options, nullptr, 0);
    EXPECT_EQ(bb.summary.termination, Termination::optimal);
    EXPECT_LE(bb.summary.final_error, brute.summary.final_error * 1.05 + 1e-15);
    EXPECT_LE(bb.summary.lower_bound, brute.summary.final_error);
    EXPECT_LE(bb.summary.gap, 0.05 * bb.summary.final_error + 1e-15);
  }
}

// Error NaN on half of the lattice (invalid points): the optimum over the valid half is found.
struct HalfInvalidError {
  static constexpr int kDim = 2;
  template <typename T>
  T operator()(const T* x) const {
    return square(x[0] - T(0.3)) + square(x[1] - T(0.8));
  }
};

class HalfInvalidProblem final : public Problem {
 public:
  HalfInvalidProblem()
      : Problem(2, Bounds{{0, 0}, {1, 1}}, {Lattice::uniform(0, 1, 64), Lattice::uniform(0, 1, 64)}),
        inner_(make_problem(HalfInvalidError{}, Bounds{{0, 0}, {1, 1}})) {}
  double eval(const double* x) const override { return x[1] > 0.5 ? std::nan("") : inner_.eval(x); }
  Interval eval(const Interval* box) const override { return inner_.eval(box); }
  double eval_with_gradient(const double* x, double* g) const override { return inner_.eval_with_gradient(x, g); }
  bool is_smooth() const override { return true; }
  int residual_count() const override { return 0; }
  void eval_residuals(const double*, double*, double*) const override { fail_no_residuals(); }

 private:
  ErrorProblem<HalfInvalidError> inner_;
};

TEST(IntervalBb, SkipsPointsWithANanError) {
  const HalfInvalidProblem problem;
  const SolveResult brute = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
  const SolveResult bb = solve_interval_bb(problem, IntervalBbOptions{}, nullptr, 0);
  EXPECT_EQ(bb.summary.termination, Termination::optimal);
  EXPECT_EQ(bb.summary.final_error, brute.summary.final_error);
  EXPECT_LE(bb.parameters[1], 0.5);
  EXPECT_NE(bb.summary.message.find("NaN"), std::string::npos) << bb.summary.message;
}

// A shape fit seen through Problem::eval only: eval_below(box, bound) falls back to the default, the full
// enclosure. Counts the boxes the wrapped problem's own eval_below answered early (an upper end of +inf) when
// `early` is set.
class FullEnclosureShapeFit final : public Problem {
 public:
  FullEnclosureShapeFit(const ShapeFitProblem& inner, bool early)
      : Problem(inner.dim(), inner.bounds(), shape_fit_lattices(inner.data().lattice_bits)),
        inner_(inner),
        early_(early) {}
  double eval(const double* x) const override { return inner_.eval(x); }
  double eval_below(const double* x, double bound) const override { return inner_.eval_below(x, bound); }
  Interval eval(const Interval* box) const override { return inner_.eval(box); }
  Interval eval_below(const Interval* box, double bound) const override {
    if (!early_) return inner_.eval(box);
    const Interval enclosure = inner_.eval_below(box, bound);
    if (enclosure.upper() == std::numeric_limits<double>::infinity()) ++early_answers_;
    return enclosure;
  }
  double eval_with_gradient(const double* x, double* g) const override { return inner_.eval_with_gradient(x, g); }
  bool is_smooth() const override { return false; }
  int residual_count() const override { return 0; }
  void eval_residuals(const double*, double*, double*) const override { fail_no_residuals(); }
  int early_answers() const { return early_answers_; }

 private:
  const ShapeFitProblem& inner_;
  const bool early_;
  mutable int early_answers_ = 0;
};

// The shape fit's eval_below(box) stops at the natural bound once it discards a box (the stretched kind also at its
// floor, whose early answers keep a finite upper end and are not counted below); the search must not change: the
// same answer, lower bound, point evaluations and boxes as with the full enclosure of every box.
TEST(IntervalBb, EarlyExitEnclosuresLeaveTheSearchUnchanged) {
  std::mt19937_64 random(12);
  for (const ShapeErrorKind kind : {ShapeErrorKind::linear, ShapeErrorKind::stretched})
    for (int b = 0; b < 3; ++b) {
      const ShapeFitProblem problem(random_block(random, kind, 7));
      const FullEnclosureShapeFit full(problem, false), early(problem, true);
      const SolveResult a = solve_interval_bb(full, IntervalBbOptions{}, nullptr, 0);
      const SolveResult c = solve_interval_bb(early, IntervalBbOptions{}, nullptr, 0);
      SCOPED_TRACE(to_string(kind) + " block " + std::to_string(b));
      EXPECT_EQ(c.lattice_indices, a.lattice_indices);
      EXPECT_EQ(c.summary.final_error, a.summary.final_error);
      EXPECT_EQ(c.summary.lower_bound, a.summary.lower_bound);
      EXPECT_EQ(c.summary.evaluations, a.summary.evaluations);
      EXPECT_EQ(c.summary.interval_evaluations, a.summary.interval_evaluations);
      EXPECT_GT(early.early_answers(), 0) << "no box was discarded by its natural bound alone";
    }
}

TEST(IntervalBb, SameInputGivesTheSameAnswerAndCounts) {
  std::mt19937_64 random(9);
  const ShapeFitProblem problem(random_block(random, ShapeErrorKind::stretched, 5));
  const SolveResult a = solve_interval_bb(problem, IntervalBbOptions{}, nullptr, 1);
  const SolveResult b = solve_interval_bb(problem, IntervalBbOptions{}, nullptr, 1);
  EXPECT_EQ(a.lattice_indices, b.lattice_indices);
  EXPECT_EQ(a.summary.final_error, b.summary.final_error);
  EXPECT_EQ(a.summary.evaluations, b.summary.evaluations);
  EXPECT_EQ(a.summary.interval_evaluations, b.summary.interval_evaluations);
}

TEST(IntervalBb, SolvingBlocksOnSeveralThreadsMatchesSerial) {
  std::mt19937_64 random(10);
  std::vector<ShapeFitProblem> problems;
  for (int i = 0; i < 8; ++i) problems.emplace_back(random_block(random, ShapeErrorKind::linear, 5));
  std::vector<SolveResult> serial, threaded(problems.size());
  for (const ShapeFitProblem& problem : problems) serial.push_back(solve_interval_bb(problem, IntervalBbOptions{}, nullptr, 0));
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (std::size_t i = t; i < problems.size(); i += 4)
        threaded[i] = solve_interval_bb(problems[i], IntervalBbOptions{}, nullptr, 0);
    });
  for (std::thread& thread : threads) thread.join();
  for (std::size_t i = 0; i < problems.size(); ++i) {
    EXPECT_EQ(threaded[i].lattice_indices, serial[i].lattice_indices);
    EXPECT_EQ(threaded[i].summary.final_error, serial[i].summary.final_error);
    EXPECT_EQ(threaded[i].summary.interval_evaluations, serial[i].summary.interval_evaluations);
  }
}

TEST(IntervalBb, RegistryEntryResolvesOptionsAndRejectsBadValues) {
  const Solver& solver = find_solver("interval_bb");
  const SolverOptions resolved = resolve_solver_options(solver, {});
  EXPECT_EQ(resolved.at("time_limit"), "10");
  EXPECT_EQ(resolved.at("relative_gap"), "0");
  EXPECT_THROW(resolve_solver_options(solver, {{"relative_gap", "-1"}}), Error);
  EXPECT_THROW(resolve_solver_options(solver, {{"max_boxes", "0"}}), Error);
  EXPECT_THROW(resolve_solver_options(solver, {{"depth", "3"}}), Error);
  EXPECT_EQ(resolved.at("leaf_points"), "32");
  EXPECT_THROW(resolve_solver_options(solver, {{"leaf_points", "0"}}), Error);
  const auto problem = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}},
                                    {Lattice::uniform(0.0, 1.0, 32), Lattice::uniform(0.0, 1.0, 32)});
  const SolveResult result = solver.solve(problem, {{"max_boxes", "100000"}}, nullptr, 4);
  EXPECT_EQ(result.summary.solver, "interval_bb");
  EXPECT_EQ(result.summary.seed, 4u);
  EXPECT_EQ(result.summary.termination, Termination::optimal);
}

TEST(IntervalBb, AParameterWithoutALatticeIsAnError) {
  const auto problem = make_problem(examples::palette_fit_example(), Bounds{{0.0, 0.0}, {1.0, 1.0}});
  try {
    solve_interval_bb(problem, IntervalBbOptions{}, nullptr, 0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("interval_bb: parameter 0 has no storage lattice"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace blocklab
