// core/scalar.h: select/min/max/clamp/abs/square and comparisons for double, float, ceres::Jet and Interval, with
// the per-type meaning the header documents (Jets: derivative of the chosen branch; Intervals: three-valued).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/scalar.h"

namespace blocklab {
namespace {

using Jet2 = ceres::Jet<double, 2>;

// One templated function using every helper, evaluated with all scalar types below.
template <typename T>
T shaped(const T& x, const T& y) {
  const T clipped = clamp(x, T(-1.0), T(1.0));
  const T folded = select(less(clipped, T(0.0)), square(clipped), abs(clipped));
  return max(folded, min(y, T(0.25))) + square(x - y);
}

TEST(Tribool, TruthTablesOfAndOrNot) {
  const Tribool values[] = {Tribool::no, Tribool::yes, Tribool::maybe};
  for (Tribool a : values) {
    EXPECT_EQ(logical_and(Tribool::no, a), Tribool::no);
    EXPECT_EQ(logical_or(Tribool::yes, a), Tribool::yes);
    EXPECT_EQ(logical_and(Tribool::yes, a), a);
    EXPECT_EQ(logical_or(Tribool::no, a), a);
    EXPECT_EQ(logical_not(logical_not(a)), a);
  }
  EXPECT_EQ(logical_and(Tribool::maybe, Tribool::maybe), Tribool::maybe);
  EXPECT_EQ(logical_not(Tribool::maybe), Tribool::maybe);
  EXPECT_TRUE(certainly(Tribool::yes));
  EXPECT_FALSE(certainly(Tribool::maybe));
  EXPECT_TRUE(possibly(Tribool::maybe));
  EXPECT_FALSE(possibly(Tribool::no));
  EXPECT_TRUE(certainly(true));
  EXPECT_FALSE(possibly(false));
  EXPECT_STREQ(to_string(Tribool::maybe), "maybe");
}

TEST(ScalarDouble, MinMaxKeepTheFirstArgumentOnTiesAndClampBounds) {
  EXPECT_EQ(min(2.0, 3.0), 2.0);
  EXPECT_EQ(max(2.0, 3.0), 3.0);
  EXPECT_TRUE(std::signbit(min(-0.0, 0.0)));   // tie: the first argument
  EXPECT_FALSE(std::signbit(min(0.0, -0.0)));
  EXPECT_EQ(clamp(5.0, 0.0, 1.0), 1.0);
  EXPECT_EQ(clamp(-5.0, 0.0, 1.0), 0.0);
  EXPECT_EQ(clamp(0.5, 0.0, 1.0), 0.5);
  EXPECT_EQ(clamp(5.0f, 0.0f, 1.0f), 1.0f);
  EXPECT_EQ(select(true, 1.0, 2.0), 1.0);
  EXPECT_EQ(select(false, 1.0f, 2.0f), 2.0f);
  EXPECT_EQ(abs(-2.5), 2.5);
  EXPECT_EQ(abs(-2.5f), 2.5f);
  EXPECT_EQ(square(-3.0), 9.0);
  EXPECT_EQ(square(-3.0f), 9.0f);
  EXPECT_TRUE(less(1.0, 2.0));
  EXPECT_TRUE(greater(2.0, 1.0));
  EXPECT_TRUE(greater_equal(2.0, 2.0));
  EXPECT_FALSE(less(std::numeric_limits<double>::quiet_NaN(), 1.0));
}

TEST(ScalarJet, ComparisonsUseScalarPartsAndSelectCarriesTheChosenDerivative) {
  const Jet2 x(0.5, 0);   // dx = (1, 0)
  const Jet2 y(2.0, 1);   // dy = (0, 1)
  EXPECT_TRUE(less(x, y));
  EXPECT_FALSE(less_equal(y, x));
  EXPECT_TRUE(greater(y, x));
  const Jet2 chosen = select(less(x, y), x, y);
  EXPECT_EQ(chosen.a, 0.5);
  EXPECT_EQ(chosen.v[0], 1.0);
  EXPECT_EQ(chosen.v[1], 0.0);
  const Jet2 smaller = min(x, y), larger = max(x, y);
  EXPECT_EQ(smaller.v[0], 1.0);
  EXPECT_EQ(larger.v[1], 1.0);
  // Tie: the first argument, with its derivative.
  const Jet2 tie_a(1.0, 0), tie_b(1.0, 1);
  EXPECT_EQ(min(tie_a, tie_b).v[0], 1.0);
  EXPECT_EQ(max(tie_a, tie_b).v[0], 1.0);
}

TEST(ScalarJet, ClampAbsAndSquareHaveTheDerivativesOfTheirBranches) {
  const Jet2 inside(0.3, 0), above(1.7, 0), below(-2.0, 0);
  const Jet2 lo(0.0), hi(1.0);
  EXPECT_EQ(clamp(inside, lo, hi).v[0], 1.0);   // identity branch
  EXPECT_EQ(clamp(above, lo, hi).a, 1.0);
  EXPECT_EQ(clamp(above, lo, hi).v[0], 0.0);    // constant bound branch
  EXPECT_EQ(clamp(below, lo, hi).v[0], 0.0);
  EXPECT_EQ(abs(below).a, 2.0);
  EXPECT_EQ(abs(below).v[0], -1.0);
  EXPECT_EQ(abs(inside).v[0], 1.0);
  const Jet2 squared = square(Jet2(-3.0, 1));
  EXPECT_EQ(squared.a, 9.0);
  EXPECT_EQ(squared.v[1], -6.0);
  EXPECT_EQ(scalar_value(squared), 9.0);
}

TEST(ScalarInterval, ComparisonsAreThreeValuedAndNeverThrow) {
  const Interval low(0.0, 1.0), high(2.0, 3.0), overlapping(0.5, 2.5), touching(1.0, 2.0);
  EXPECT_EQ(less(low, high), Tribool::yes);
  EXPECT_EQ(less(high, low), Tribool::no);
  EXPECT_EQ(less(low, overlapping), Tribool::maybe);
  EXPECT_EQ(less(low, touching), Tribool::maybe);          // 1 < 1 is false at the shared point
  EXPECT_EQ(less_equal(low, touching), Tribool::yes);      // every point of low is <= every point of touching
  EXPECT_EQ(less_equal(high, low), Tribool::no);
  EXPECT_EQ(greater(high, low), Tribool::yes);
  EXPECT_EQ(greater_equal(touching, low), Tribool::yes);
  EXPECT_EQ(less(Interval::empty(), high), Tribool::maybe);
  EXPECT_EQ(less_equal(low, Interval::empty()), Tribool::maybe);
}

TEST(ScalarInterval, SelectOnAnUncertainConditionReturnsTheHullOfBothBranches) {
  const Interval a(0.0, 1.0), b(5.0, 6.0);
  const Interval certain_true = select(Tribool::yes, a, b);
  EXPECT_EQ(certain_true.lower(), 0.0);
  EXPECT_EQ(certain_true.upper(), 1.0);
  const Interval certain_false = select(Tribool::no, a, b);
  EXPECT_EQ(certain_false.lower(), 5.0);
  const Interval hull = select(Tribool::maybe, a, b);
  EXPECT_EQ(hull.lower(), 0.0);
  EXPECT_EQ(hull.upper(), 6.0);
  const Interval from_bool = select(false, a, b);
  EXPECT_EQ(from_bool.lower(), 5.0);
}

TEST(ScalarInterval, MinMaxClampAreIntervalExtensionsAndSquareIsNonNegative) {
  const Interval a(0.0, 2.0), b(1.0, 3.0);
  EXPECT_EQ(min(a, b).lower(), 0.0);
  EXPECT_EQ(min(a, b).upper(), 2.0);
  EXPECT_EQ(max(a, b).lower(), 1.0);
  EXPECT_EQ(max(a, b).upper(), 3.0);
  const Interval clamped = clamp(Interval(-1.0, 0.5), Interval(0.0), Interval(1.0));
  EXPECT_EQ(clamped.lower(), 0.0);
  EXPECT_EQ(clamped.upper(), 0.5);
  EXPECT_EQ(abs(Interval(-3.0, 2.0)).upper(), 3.0);
  EXPECT_EQ(square(Interval(-0.9, 1.0)).lower(), 0.0);
}

TEST(Scalar, OneTemplateAgreesAcrossDoubleJetAndInterval) {
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> value(-2.0, 2.0), unit(0.0, 1.0);
  for (int i = 0; i < 5000; ++i) {
    const double x = value(random), y = value(random);
    const double expected = shaped(x, y);
    const Jet2 jet = shaped(Jet2(x, 0), Jet2(y, 1));
    ASSERT_EQ(jet.a, expected);
    const Interval point = shaped(Interval(x), Interval(y));
    ASSERT_TRUE(contains(point, expected)) << to_string(point) << " vs " << expected;
    // A box around the point encloses the function at samples inside it (the hull rule of select at work).
    const double r = 0.3 * unit(random);
    const Interval box = shaped(Interval(x - r, x + r), Interval(y - r, y + r));
    for (int s = 0; s < 10; ++s) {
      const double sx = x - r + 2 * r * unit(random), sy = y - r + 2 * r * unit(random);
      ASSERT_TRUE(contains(box, shaped(sx, sy)));
    }
  }
}

TEST(Scalar, UnqualifiedCallsResolveInsideNamespaceBlocklab) {
  // abs, min, square written unqualified pick the blocklab overloads for each type (no ambiguity with std:: or
  // Boost's templates); a compile-time check as much as a run-time one.
  using std::abs;
  EXPECT_EQ(abs(-1.0), 1.0);
  EXPECT_EQ(abs(Interval(-2.0, -1.0)).lower(), 1.0);
  EXPECT_EQ(abs(Jet2(-1.0, 0)).v[0], -1.0);
  EXPECT_EQ(min(Interval(0.0, 4.0), Interval(1.0, 2.0)).upper(), 2.0);
}

}  // namespace
}  // namespace blocklab
