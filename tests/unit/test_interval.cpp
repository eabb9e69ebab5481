// blocklab::Interval (core/interval.h): outward rounding encloses exact results of arithmetic and of
// exp/log/exp2/log2/sqrt (checked against long double), the dependency-free square, the real-exponent pow with
// its floor, and the non-throwing empty/NaN behaviour.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "core/interval.h"

namespace blocklab {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Long double holds 64 mantissa bits on x86-64, 11 more than double: a long double result is far closer to the
// exact value than the one-ulp (double) widening, so "lower <= long double result <= upper" is a sound check.
static_assert(std::numeric_limits<long double>::digits >= 64, "the enclosure checks need x87 extended precision");

bool encloses(const Interval& x, long double exact) {
  return !is_empty(x) && static_cast<long double>(x.lower()) <= exact && exact <= static_cast<long double>(x.upper());
}

double random_magnitude_double(std::mt19937_64& random) {
  // Values spread over many binades, both signs: sign * 2^e * m with e in [-60, 60].
  std::uniform_real_distribution<double> mantissa(1.0, 2.0), exponent(-60.0, 60.0);
  const double value = std::ldexp(mantissa(random), static_cast<int>(std::floor(exponent(random))));
  return (random() & 1) ? value : -value;
}

TEST(NextUpDown, MatchStdNextafterOnSpecialAndRandomDoubles) {
  std::vector<double> values = {0.0, -0.0, 1.0, -1.0, std::numeric_limits<double>::min(),
                                std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::denorm_min(),
                                std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(), kInf, -kInf,
                                0.5, 2.0, 1e-310};
  std::mt19937_64 random(7);
  for (int i = 0; i < 100000; ++i) {
    const std::uint64_t bits = random();
    double value;
    std::memcpy(&value, &bits, sizeof value);
    if (!std::isnan(value)) values.push_back(value);
  }
  for (double value : values) {
    EXPECT_EQ(next_up(value), std::nextafter(value, kInf)) << value;
    EXPECT_EQ(next_down(value), std::nextafter(value, -kInf)) << value;
  }
  EXPECT_TRUE(std::isnan(next_up(kNaN)));
  EXPECT_TRUE(std::isnan(next_down(kNaN)));
}

TEST(Interval, ArithmeticOfPointIntervalsEnclosesTheLongDoubleResult) {
  std::mt19937_64 random(11);
  int widened_needed = 0;   // cases where the round-to-nearest double alone misses the exact result
  for (int i = 0; i < 100000; ++i) {
    const double x = random_magnitude_double(random), y = random_magnitude_double(random);
    const Interval a(x), b(y);
    const long double lx = x, ly = y;
    const long double exact_product = lx * ly;
    ASSERT_TRUE(encloses(a + b, lx + ly)) << x << " + " << y << " -> " << to_string(a + b);
    ASSERT_TRUE(encloses(a - b, lx - ly)) << x << " - " << y << " -> " << to_string(a - b);
    ASSERT_TRUE(encloses(a * b, exact_product)) << x << " * " << y << " -> " << to_string(a * b);
    ASSERT_TRUE(encloses(a / b, lx / ly)) << x << " / " << y << " -> " << to_string(a / b);
    if (static_cast<long double>(x * y) != exact_product) ++widened_needed;
  }
  // The widening is not decorative: most products are inexact in double.
  EXPECT_GT(widened_needed, 50000);
}

TEST(Interval, ArithmeticOfRandomIntervalsEnclosesEverySampledResult) {
  std::mt19937_64 random(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    double a0 = random_magnitude_double(random), a1 = random_magnitude_double(random);
    double b0 = random_magnitude_double(random), b1 = random_magnitude_double(random);
    if (a1 < a0) std::swap(a0, a1);
    if (b1 < b0) std::swap(b0, b1);
    const Interval a(a0, a1), b(b0, b1);
    const Interval sum = a + b, difference = a - b, product = a * b, quotient = a / b;
    const bool b_has_zero = b0 <= 0.0 && 0.0 <= b1;
    for (int s = 0; s < 50; ++s) {
      // Endpoints first (where extremes of + - * / are attained), then uniform samples.
      const long double x = s < 2 ? (s == 0 ? a0 : a1) : a0 + (a1 - a0) * unit(random);
      const long double y = s < 2 ? (s == 0 ? b1 : b0) : b0 + (b1 - b0) * unit(random);
      ASSERT_TRUE(encloses(sum, x + y));
      ASSERT_TRUE(encloses(difference, x - y));
      ASSERT_TRUE(encloses(product, x * y)) << to_string(a) << " * " << to_string(b);
      if (!b_has_zero) {
        ASSERT_TRUE(encloses(quotient, x / y)) << to_string(a) << " / " << to_string(b);
      }
    }
  }
}

TEST(Interval, SquareHasNoDependencyProblemUnlikeSelfMultiplication) {
  const Interval x(-0.9, 1.0);
  const Interval product = x * x;
  const Interval squared = square(x);
  EXPECT_LT(product.lower(), -0.89);   // x * x treats the two factors as independent
  EXPECT_EQ(squared.lower(), 0.0);     // square knows they are the same number
  EXPECT_GE(squared.upper(), 1.0);
  EXPECT_LE(squared.upper(), next_up(1.0));
  EXPECT_EQ(square(Interval(-3.0, -2.0)).lower(), next_down(4.0));
}

TEST(Interval, ExactZeroResultsAreNotWidened) {
  const Interval sum = Interval(1.0) + Interval(-1.0);
  EXPECT_EQ(sum.lower(), 0.0);
  EXPECT_EQ(sum.upper(), 0.0);
  const Interval product = Interval(0.0) * Interval(3.0, 5.0);
  EXPECT_EQ(product.lower(), 0.0);
  EXPECT_EQ(product.upper(), 0.0);
  // An underflowing square is a tiny positive number: its lower bound is 0, never negative.
  const Interval tiny_square = square(Interval(1e-200));
  EXPECT_EQ(tiny_square.lower(), 0.0);
  EXPECT_GT(tiny_square.upper(), 0.0);
  const Interval tiny_product = Interval(1e-200) * Interval(-1e-200);
  EXPECT_LT(tiny_product.lower(), 0.0);
  EXPECT_EQ(tiny_product.upper(), 0.0);
}

TEST(Interval, ExpLogExp2Log2SqrtEncloseLongDoubleOver1e5RandomInputs) {
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> exponent_argument(-700.0, 700.0), binade(-1000.0, 1000.0);
  int rounded_below_exact = 0;   // glibc exp below the exact value: a one-sided (non-widened) bound would fail
  for (int i = 0; i < 100000; ++i) {
    const double x = exponent_argument(random);
    const double positive = std::exp2(binade(random));
    const long double lx = x, lp = positive;
    ASSERT_TRUE(encloses(boost::numeric::exp(Interval(x)), std::exp(lx))) << "exp(" << x << ")";
    ASSERT_TRUE(encloses(exp2(Interval(x)), std::exp2(lx))) << "exp2(" << x << ")";
    ASSERT_TRUE(encloses(boost::numeric::log(Interval(positive)), std::log(lp))) << "log(" << positive << ")";
    ASSERT_TRUE(encloses(log2(Interval(positive)), std::log2(lp))) << "log2(" << positive << ")";
    ASSERT_TRUE(encloses(boost::numeric::sqrt(Interval(positive)), std::sqrt(lp))) << "sqrt(" << positive << ")";
    if (static_cast<long double>(std::exp(x)) < std::exp(lx)) ++rounded_below_exact;
  }
  EXPECT_GT(rounded_below_exact, 0);
}

TEST(Interval, TranscendentalsOfWideIntervalsEncloseSampledValues) {
  std::mt19937_64 random(19);
  std::uniform_real_distribution<double> argument(-30.0, 30.0), unit(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    double lo = argument(random), hi = argument(random);
    if (hi < lo) std::swap(lo, hi);
    const Interval x(lo, hi);
    const Interval positive(std::exp(lo), std::exp(hi));
    const Interval e = boost::numeric::exp(x), e2 = exp2(x), l = boost::numeric::log(positive),
                   l2 = log2(positive);
    for (int s = 0; s < 20; ++s) {
      const double t = s == 0 ? lo : (s == 1 ? hi : lo + (hi - lo) * unit(random));
      const double p = positive.lower() + (positive.upper() - positive.lower()) * unit(random);
      ASSERT_TRUE(encloses(e, std::exp(static_cast<long double>(t))));
      ASSERT_TRUE(encloses(e2, std::exp2(static_cast<long double>(t))));
      ASSERT_TRUE(encloses(l, std::log(static_cast<long double>(p))));
      ASSERT_TRUE(encloses(l2, std::log2(static_cast<long double>(p))));
    }
  }
}

TEST(Interval, ExpOfVeryNegativeArgumentsHasLowerBoundZero) {
  const Interval tiny = boost::numeric::exp(Interval(-1000.0, -900.0));
  EXPECT_EQ(tiny.lower(), 0.0);
  EXPECT_GT(tiny.upper(), 0.0);
  EXPECT_EQ(exp2(Interval(-kInf, 0.0)).lower(), 0.0);
  EXPECT_EQ(boost::numeric::exp(Interval(0.0, 800.0)).upper(), kInf);
}

TEST(Interval, LogOfOneIsExactlyZero) {
  EXPECT_EQ(boost::numeric::log(Interval(1.0)).lower(), 0.0);
  EXPECT_EQ(boost::numeric::log(Interval(1.0)).upper(), 0.0);
  EXPECT_EQ(log2(Interval(1.0)).lower(), 0.0);
  EXPECT_EQ(log2(Interval(1.0, 8.0)).upper(), next_up(next_up(next_up(next_up(3.0)))));
}

TEST(Interval, IntegerPowerMatchesRepeatedMultiplicationBounds) {
  const Interval x(-2.0, 3.0);
  const Interval cube = boost::numeric::pow(x, 3);
  EXPECT_LE(cube.lower(), -8.0);
  EXPECT_GE(cube.upper(), 27.0);
  const Interval even = pow(x, 2);   // pow(I, int) is Boost's exact power: like square, never negative
  EXPECT_EQ(even.lower(), 0.0);
  EXPECT_GE(even.upper(), 9.0);
}

TEST(Interval, RealExponentPowEnclosesSampledPowersIncludingTheFloorRegion) {
  std::mt19937_64 random(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    // Bases from exactly 0 (a quarter of the trials) up to 8, exponents in [-3, 3].
    double x0 = trial % 4 == 0 ? 0.0 : 8.0 * unit(random) * unit(random), x1 = 8.0 * unit(random);
    double y0 = -3.0 + 6.0 * unit(random), y1 = -3.0 + 6.0 * unit(random);
    if (x1 < x0) std::swap(x0, x1);
    if (y1 < y0) std::swap(y0, y1);
    const Interval result = pow(Interval(x0, x1), Interval(y0, y1));
    for (int s = 0; s < 30; ++s) {
      const long double x = s == 0 ? x0 : x0 + (x1 - x0) * unit(random);
      const long double y = y0 + (y1 - y0) * unit(random);
      const long double exact = std::pow(x, y);
      ASSERT_TRUE(encloses(result, exact)) << "pow(" << static_cast<double>(x) << ", " << static_cast<double>(y)
                                           << ") = " << static_cast<double>(exact) << " not in " << to_string(result);
    }
  }
}

TEST(Interval, PositiveConstantExponentPowEnclosesLongDoubleOver1e5RandomInputs) {
  std::mt19937_64 random(29);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 100000; ++trial) {
    // Bases over many binades (down to 2^-40) and exactly 0, exponents in (0, 3] including the stretch's 0.455.
    const double x = trial % 50 == 0 ? 0.0 : std::ldexp(unit(random), -static_cast<int>(trial % 41));
    const double y = trial % 3 == 0 ? 0.455 : 3.0 * (1.0 - unit(random));
    const Interval point = pow(Interval(x), y);
    ASSERT_TRUE(encloses(point, std::pow(static_cast<long double>(x), static_cast<long double>(y))))
        << "pow(" << x << ", " << y << ") -> " << to_string(point);
    ASSERT_GE(point.lower(), 0.0);
    // A wide interval (part of it below 0) encloses the powers of sampled bases of its non-negative part.
    const Interval wide = pow(Interval(-0.5 * x, x + 0.25), y);
    const long double inside = static_cast<long double>((x + 0.25) * unit(random));
    ASSERT_TRUE(encloses(wide, std::pow(inside, static_cast<long double>(y)))) << to_string(wide);
  }
  EXPECT_TRUE(is_empty(pow(Interval(-2.0, -1.0), 0.5)));
  EXPECT_EQ(pow(Interval(0.0), 0.455).upper(), 0.0);   // 0^y = 0 exactly
}

TEST(Interval, RealExponentPowHandlesZeroBaseByItsLimit) {
  const Interval root = pow(Interval(0.0, 0.5), 0.5);
  EXPECT_EQ(root.lower(), 0.0);
  EXPECT_GE(root.upper(), std::sqrt(0.5));
  EXPECT_EQ(pow(Interval(0.0, 1.0), -1.0).upper(), kInf);
  const Interval spanning = pow(Interval(0.0, 1.0), Interval(-1.0, 1.0));
  EXPECT_EQ(spanning.lower(), 0.0);
  EXPECT_EQ(spanning.upper(), kInf);
  EXPECT_TRUE(is_empty(pow(Interval(-2.0, -1.0), 2.5)));   // no real power of a negative base
}

TEST(Interval, DomainErrorsAndNaNGiveEmptyIntervalsWithoutThrowing) {
  EXPECT_NO_THROW({
    EXPECT_TRUE(is_empty(boost::numeric::log(Interval(-2.0, -1.0))));
    EXPECT_TRUE(is_empty(log2(Interval(-2.0, 0.0))));
    EXPECT_TRUE(is_empty(boost::numeric::sqrt(Interval(-4.0, -1.0))));
    EXPECT_TRUE(is_empty(Interval(kNaN)));
    EXPECT_TRUE(is_empty(Interval(2.0, 1.0)));
    EXPECT_TRUE(is_empty(Interval(kNaN) + Interval(1.0)));
    EXPECT_TRUE(is_empty(boost::numeric::exp(Interval::empty())));
  });
  // Partly outside the domain: clipped, like the set image.
  const Interval clipped_log = log2(Interval(-1.0, 4.0));
  EXPECT_EQ(clipped_log.lower(), -kInf);
  EXPECT_GE(clipped_log.upper(), 2.0);
  const Interval clipped_sqrt = boost::numeric::sqrt(Interval(-1.0, 4.0));
  EXPECT_EQ(clipped_sqrt.lower(), 0.0);
  EXPECT_GE(clipped_sqrt.upper(), 2.0);
}

TEST(Interval, MinAndMaxAreIntervalExtensions) {
  const Interval a(0.0, 2.0), b(1.0, 3.0);
  EXPECT_EQ(boost::numeric::min(a, b).lower(), 0.0);
  EXPECT_EQ(boost::numeric::min(a, b).upper(), 2.0);
  EXPECT_EQ(boost::numeric::max(a, b).lower(), 1.0);
  EXPECT_EQ(boost::numeric::max(a, b).upper(), 3.0);
  const Interval magnitude = boost::numeric::abs(Interval(-3.0, 2.0));
  EXPECT_EQ(magnitude.lower(), 0.0);
  EXPECT_EQ(magnitude.upper(), 3.0);
}

TEST(Interval, HelpersReportWidthMidpointContainmentAndText) {
  const Interval x(1.0, 3.0);
  EXPECT_EQ(width(x), next_up(2.0));   // an upper bound on the width: rounded outward like everything else
  EXPECT_EQ(midpoint(x), 2.0);
  EXPECT_EQ(midpoint(Interval::whole()), 0.0);   // not inf - inf
  EXPECT_TRUE(contains(x, 1.0));
  EXPECT_TRUE(contains(x, 3.0));
  EXPECT_FALSE(contains(x, 3.0000000001));
  EXPECT_FALSE(contains(Interval::empty(), 0.0));
  EXPECT_EQ(to_string(Interval(0.5, 2.0)), "[0.5, 2]");
  EXPECT_EQ(to_string(Interval::empty()), "empty");
}

}  // namespace
}  // namespace blocklab
