// Branch-free outward bounds (formats/munkberg/shape_fit/outward_bounds.h): widen_up / widen_down move a double one to two ulps outward
// across the whole double range (subnormals and signed zeros included), the squared-difference bounds enclose
// (t - L)^2 over the interval, and the SSE2 pair versions give the scalar versions' bits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "core/interval.h"
#include "formats/munkberg/shape_fit/outward_bounds.h"

namespace blocklab {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::uint64_t bits_of(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}

// Finite doubles of every kind: random bit patterns (so every binade, subnormals included, is equally likely),
// plus the edges.
std::vector<double> finite_doubles(std::uint64_t seed, int count) {
  std::vector<double> values = {0.0, -0.0, std::numeric_limits<double>::denorm_min(),
                                -std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::min(),
                                -std::numeric_limits<double>::min(), 1.0, -1.0, 0x1.fffffffffffffp0,
                                std::numeric_limits<double>::max() / 4, -std::numeric_limits<double>::max() / 4};
  std::mt19937_64 random(seed);
  while (static_cast<int>(values.size()) < count) {
    const std::uint64_t bits = random();
    double x;
    std::memcpy(&x, &bits, sizeof x);
    if (std::isfinite(x)) values.push_back(x);
  }
  return values;
}

TEST(OutwardBounds, WidenLandsOneToTwoDoublesOutwardAndUpToThreeNearTheSubnormals) {
  int tiny = 0;
  for (const double r : finite_doubles(1, 200000)) {
    const double up = widen_up(r), down = widen_down(r);
    // At least the neighbouring double; at most the one after it, or the third one for |r| < 2^-1020, where
    // |r| 2^-52 is a rounded subnormal (ulp(r) = 2^-1074 there, and the added 2^-1074 is a whole ulp).
    const bool near_subnormal = std::abs(r) < 0x1p-1020;
    tiny += near_subnormal;
    const double farthest_up = near_subnormal ? next_up(next_up(next_up(r))) : next_up(next_up(r));
    const double farthest_down = near_subnormal ? next_down(next_down(next_down(r))) : next_down(next_down(r));
    ASSERT_GE(up, next_up(r)) << std::hexfloat << r;
    ASSERT_LE(up, farthest_up) << std::hexfloat << r;
    ASSERT_LE(down, next_down(r)) << std::hexfloat << r;
    ASSERT_GE(down, farthest_down) << std::hexfloat << r;
  }
  EXPECT_GT(tiny, 10);   // random bit patterns reach the subnormal range (1 in ~500)
}

TEST(OutwardBounds, WidenedOperationResultsEncloseTheExactResult) {
  // Sums and products of two doubles, exact in long double (64-bit mantissa) for these magnitudes: the rounded result
  // widened outward must contain them.
  std::mt19937_64 random(2);
  std::uniform_real_distribution<double> mantissa(1.0, 2.0);
  std::uniform_int_distribution<int> exponent(-20, 20);
  for (int i = 0; i < 200000; ++i) {
    const double x = std::ldexp(mantissa(random), exponent(random)) * (i % 2 ? -1.0 : 1.0);
    const double y = std::ldexp(mantissa(random), exponent(random));
    const long double exact_product = static_cast<long double>(x) * static_cast<long double>(y);
    ASSERT_LE(static_cast<long double>(widen_down(x * y)), exact_product);
    ASSERT_GE(static_cast<long double>(widen_up(x * y)), exact_product);
    const double small = std::ldexp(y, -30);   // x + small is exact in long double (at most 61 bits apart)
    const long double exact_sum = static_cast<long double>(x) + static_cast<long double>(small);
    ASSERT_LE(static_cast<long double>(widen_down(x + small)), exact_sum);
    ASSERT_GE(static_cast<long double>(widen_up(x + small)), exact_sum);
  }
}

TEST(OutwardBounds, SquaredDifferenceBoundsEncloseEverySquareOverTheInterval) {
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20000; ++trial) {
    const double t = unit(random);
    double lo = unit(random), hi = trial % 5 == 0 ? lo : unit(random);   // some degenerate intervals
    if (hi < lo) std::swap(lo, hi);
    double lower, upper;
    squared_difference_bounds(t, lo, hi, &lower, &upper);
    ASSERT_GE(lower, 0.0);
    for (int k = 0; k <= 16; ++k) {
      const double l = k == 16 ? hi : lo + (hi - lo) * k / 16.0;
      const long double d = static_cast<long double>(t) - static_cast<long double>(l);
      ASSERT_LE(static_cast<long double>(lower), d * d) << t << " " << lo << " " << hi;
      ASSERT_GE(static_cast<long double>(upper), d * d) << t << " " << lo << " " << hi;
    }
    // Tight: t inside the interval has a zero lower bound; the upper bound is the farther end's square, widened.
    if (lo <= t && t <= hi) {
      ASSERT_EQ(lower, 0.0);
    }
  }
}

#if defined(__SSE2__)
TEST(OutwardBounds, PairVersionsGiveTheScalarBitsLaneForLane) {
  const std::vector<double> values = finite_doubles(4, 20000);
  const double special[] = {0.0, -0.0, kInf, -kInf, std::numeric_limits<double>::quiet_NaN()};
  std::vector<double> inputs(values);
  inputs.insert(inputs.end(), std::begin(special), std::end(special));
  for (std::size_t i = 0; i + 1 < inputs.size(); ++i) {
    const __m128d pair = _mm_set_pd(inputs[i + 1], inputs[i]);
    double up[2], down[2];
    _mm_storeu_pd(up, widen_up_pair(pair));
    _mm_storeu_pd(down, widen_down_pair(pair));
    for (int lane = 0; lane < 2; ++lane) {
      ASSERT_EQ(bits_of(up[lane]), bits_of(widen_up(inputs[i + lane]))) << std::hexfloat << inputs[i + lane];
      ASSERT_EQ(bits_of(down[lane]), bits_of(widen_down(inputs[i + lane]))) << std::hexfloat << inputs[i + lane];
    }
  }
  // Squared differences: random triples, signed zeros and coinciding ends, where the max operand order matters.
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 50000; ++trial) {
    double t[2], lo[2], hi[2];
    for (int lane = 0; lane < 2; ++lane) {
      t[lane] = trial % 7 == 0 ? (lane ? -0.0 : 0.0) : unit(random);
      lo[lane] = trial % 11 == 0 ? t[lane] : unit(random);
      hi[lane] = trial % 13 == 0 ? lo[lane] : unit(random);
      if (hi[lane] < lo[lane]) std::swap(lo[lane], hi[lane]);
    }
    __m128d lower_pair, upper_pair;
    squared_difference_bounds_pair(_mm_loadu_pd(t), _mm_loadu_pd(lo), _mm_loadu_pd(hi), &lower_pair, &upper_pair);
    double lower[2], upper[2];
    _mm_storeu_pd(lower, lower_pair);
    _mm_storeu_pd(upper, upper_pair);
    for (int lane = 0; lane < 2; ++lane) {
      double scalar_lower, scalar_upper;
      squared_difference_bounds(t[lane], lo[lane], hi[lane], &scalar_lower, &scalar_upper);
      ASSERT_EQ(bits_of(lower[lane]), bits_of(scalar_lower)) << trial;
      ASSERT_EQ(bits_of(upper[lane]), bits_of(scalar_upper)) << trial;
    }
  }
}
#endif

}  // namespace
}  // namespace blocklab
