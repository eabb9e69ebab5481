// The portable random streams of solvers/seeding.h: SplitMix64 against its reference outputs, per-block seed
// derivation, and the hand-written uniform / index / normal draws.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "solvers/seeding.h"

namespace blocklab {
namespace {

// Reference outputs of Vigna's splitmix64.c started from state 0 (the values every SplitMix64 port checks).
TEST(Seeding, SplitMix64MatchesTheReferenceSequenceFromStateZero) {
  std::uint64_t state = 0;
  EXPECT_EQ(splitmix64_next(state), 0xe220a8397b1dcdafULL);
  EXPECT_EQ(splitmix64_next(state), 0x6e789e6aa1b965f4ULL);
  EXPECT_EQ(splitmix64_next(state), 0x06c45d188009454fULL);
}

TEST(Seeding, StreamSeedsAreReproducibleAndDistinctPerBlockAndGlobalSeed) {
  EXPECT_EQ(derive_stream_seed(42, 7), derive_stream_seed(42, 7));
  std::set<std::uint64_t> seen;
  for (std::uint64_t global = 0; global < 4; ++global)
    for (std::uint64_t block = 0; block < 1000; ++block) seen.insert(derive_stream_seed(global, block));
  EXPECT_EQ(seen.size(), 4000u);
  // Swapping the roles of the two arguments gives another stream (the index is mixed before the xor).
  EXPECT_NE(derive_stream_seed(1, 2), derive_stream_seed(2, 1));
}

TEST(Seeding, Uniform01IsAMultipleOfTwoToTheMinus53InTheHalfOpenUnitInterval) {
  RandomStream stream(123);
  double sum = 0.0;
  constexpr int kDraws = 100000;
  for (int i = 0; i < kDraws; ++i) {
    const double u = stream.uniform01();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    ASSERT_EQ(u * 0x1.0p53, std::floor(u * 0x1.0p53));
    sum += u;
  }
  // Mean 1/2 with standard error sqrt(1/12 / n) ~ 0.0009: 5 standard errors.
  EXPECT_NEAR(sum / kDraws, 0.5, 0.0046);
}

TEST(Seeding, UniformIndexCoversEveryValueEvenlyAndHandlesTrivialBounds) {
  RandomStream stream(9);
  EXPECT_EQ(stream.uniform_index(1), 0u);
  EXPECT_EQ(stream.uniform_index(0), 0u);
  std::vector<int> counts(7, 0);
  constexpr int kDraws = 70000;
  for (int i = 0; i < kDraws; ++i) {
    const std::uint64_t k = stream.uniform_index(7);
    ASSERT_LT(k, 7u);
    ++counts[k];
  }
  // Each count is Binomial(70000, 1/7): mean 10000, standard deviation ~93; 5 standard deviations.
  for (int count : counts) EXPECT_NEAR(count, 10000, 465);
}

TEST(Seeding, NormalDrawsHaveUnitVarianceAndZeroMean) {
  RandomStream stream(2024);
  constexpr int kDraws = 200000;
  double sum = 0.0, sum_squares = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    const double z = stream.normal();
    ASSERT_TRUE(std::isfinite(z));
    sum += z;
    sum_squares += z * z;
  }
  const double mean = sum / kDraws;
  EXPECT_NEAR(mean, 0.0, 5.0 / std::sqrt(kDraws));
  EXPECT_NEAR(sum_squares / kDraws - mean * mean, 1.0, 5.0 * std::sqrt(2.0 / kDraws));
}

TEST(Seeding, EqualSeedsGiveEqualStreams) {
  RandomStream a(77), b(77), c(78);
  bool differs = false;
  for (int i = 0; i < 100; ++i) {
    const double x = a.normal();
    EXPECT_EQ(x, b.normal());
    if (x != c.normal()) differs = true;
  }
  EXPECT_TRUE(differs);
}

}  // namespace
}  // namespace blocklab
