// The `wang` encoder's search pieces (formats/wang/): the residual texel error seen through the shader's clamp
// (wang_block_problem.h), the joint code choice against an exhaustive search of its 8 x 8 x 4 combinations
// (wang_joint_codes.h), the radix sort of the zone splits against std::sort (wang_sorted_values.h), the presets'
// ordering of effort, the BC4 fast path the 1D codec's start takes on a constant channel and the descent's trial
// error (wang_trial_error.h: the float screen never refuses a trial the exact total would accept).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/cpu_features.h"
#include "formats/bc4/bc4_encoder.h"
#include "formats/wang/wang_block.h"
#include "formats/wang/wang_block_problem.h"
#include "formats/wang/wang_joint_codes.h"
#include "formats/wang/wang_luminance_codec.h"
#include "formats/wang/wang_presets.h"
#include "formats/wang/wang_residual_codec.h"
#include "formats/wang/wang_sorted_values.h"
#include "formats/wang/wang_trial_error.h"
#include "tests/unit/test_wang_random_block.h"

namespace blocklab {
namespace {

TEST(WangEncoderSearch, ResidualTexelErrorIsEq9AboveTheSourceAndChargesABlackDecodeLOverC) {
  wang::ResidualBlockError error;
  error.c = 1.0 / 16384.0;
  const double l = 0.005;
  // At or above L: eq. 9, |L - D| / (L + c).
  EXPECT_DOUBLE_EQ(error.texel_error(l, 0.006), 0.001 / (l + error.c));
  EXPECT_DOUBLE_EQ(error.texel_error(l, l), 0.0);
  // Below L: the same ratio the other way, (L + c) / (D + c) - 1.
  EXPECT_NEAR(error.texel_error(l, 0.004), (l + error.c) / (0.004 + error.c) - 1.0, 1e-12);
  // A decode <= 0 is shown black: the error is L / c whatever the negative value, far above a positive overshoot
  // that eq. 9 alone would rank behind it (eq. 9: black 1.0 or more, 0.012 gives 1.38).
  EXPECT_DOUBLE_EQ(error.texel_error(l, -0.001), l / error.c);
  EXPECT_DOUBLE_EQ(error.texel_error(l, 0.0), l / error.c);
  EXPECT_LT(error.texel_error(l, 0.012), error.texel_error(l, -0.001));
  // A black source decoded black costs nothing.
  EXPECT_DOUBLE_EQ(error.texel_error(0.0, -0.5), 0.0);
}

TEST(WangEncoderSearch, JointCodeChoiceFindsTheExhaustiveMinimumOfEveryTexel) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    // Dark texels in a third of the trials.
    test_wang::RandomJointBlock block =
        test_wang::random_joint_block(rng, 2.0, trial % 3 == 2, 1e-3, trial % 3 == 0 ? 0.01 : 40.0);
    wang::BlockParams& params = block.params;
    const wang::LuminanceBlockError& luminance = block.luminance;
    wang::ResidualBlockError& residual = block.residual;
    double part0[8], part1[8], entry[4];
    wang::alpha_parts(luminance, params.tex0.alpha, params.tex1.alpha, part0, part1);
    wang::residual_entries(residual, params.tex1.color, entry);
    double exhaustive = 0.0;
    for (int texel = 0; texel < 16; ++texel) {
      double best = std::numeric_limits<double>::infinity();
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
          for (int k = 0; k < 4; ++k)
            best = std::min(best, residual.texel_error(residual.luminance[texel],
                                                       residual.reconstruct(part0[i] + part1[j], entry[k])));
      exhaustive += best;
    }
    const double joint = wang::choose_codes_jointly(luminance, residual, params);
    EXPECT_NEAR(joint, exhaustive, 1e-12 * (1.0 + exhaustive)) << "trial " << trial;
  }
}

TEST(WangEncoderSearch, SortedValuesEqualStdSortIncludingNegativesDuplicatesAndExtremes) {
  std::mt19937 rng(12);
  std::lognormal_distribution<double> magnitude(0.0, 8.0);
  std::vector<double> values = {0.0, 1e30, -1e30, 5e-324, -5e-324, std::numeric_limits<double>::max()};
  for (int k = 0; k < 20000; ++k) {
    const double v = magnitude(rng) * ((rng() & 1u) ? 1.0 : -1.0);
    values.push_back(v);
    if (k % 7 == 0) values.push_back(v);   // duplicates
  }
  std::vector<double> expected = values;
  std::sort(expected.begin(), expected.end());
  const std::vector<double> sorted = wang::sorted_values(values);
  ASSERT_EQ(sorted.size(), expected.size());
  for (std::size_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], expected[i]) << "position " << i;
  EXPECT_TRUE(wang::sorted_values({}).empty());
  const std::vector<double> one = wang::sorted_values({3.5});
  EXPECT_EQ(one, std::vector<double>{3.5});
}

// The 1D codec's start (wang_luminance_codec.cpp) fits a channel whose targets all equal one 8-bit value with the
// BC4 fast path: every search must give the same block there (a one-zone block's other channel is 0 or 255).
TEST(WangEncoderSearch, Bc4SearchesOfAConstantIntegralChannelAllReturnTheFastPathsBlock) {
  for (int value = 0; value <= 255; ++value) {
    float targets[16];
    std::fill(targets, targets + 16, static_cast<float>(value));
    const Bc4Params fast = fit_bc4_block(targets, S3tcSearch::fast);
    // The exhaustive search visits all 65536 pairs: a few values suffice for it.
    const bool exhaustive_too = value == 0 || value == 1 || value == 128 || value == 254 || value == 255;
    for (const S3tcSearch search : {S3tcSearch::standard, S3tcSearch::exhaustive}) {
      if (search == S3tcSearch::exhaustive && !exhaustive_too) continue;
      const Bc4Params other = fit_bc4_block(targets, search);
      EXPECT_EQ(other.endpoints, fast.endpoints) << "value " << value;
      EXPECT_EQ(other.mode, fast.mode) << "value " << value;
      EXPECT_EQ(other.indices, fast.indices) << "value " << value;
    }
  }
}

// The exhaustive weighted sum of min |L - (part0[i] + part1[j])| in double, the definition the trial error keeps.
double exhaustive_nearest_sum_total(const wang::LuminanceBlockError& error, const std::vector<double>& part0,
                                    const std::vector<double>& part1) {
  double total = 0.0;
  for (int texel = 0; texel < 16; ++texel) {
    double best = std::numeric_limits<double>::infinity();
    for (const double a : part0)
      for (const double b : part1) best = std::min(best, std::abs(error.luminance[texel] - (a + b)));
    total += error.weight[texel] * best;
  }
  return total;
}

TEST(WangEncoderSearch, TrialErrorIsTheExactTotalBelowTheBoundAndAtLeastTheBoundOtherwise) {
  std::mt19937 random(20261127);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int refused_near_ties = 0, accepted_near_ties = 0;
  int refused_far_below[2] = {0, 0};   // per screen (SSE2, AVX2): trials refused without the exact pass
  for (int trial = 0; trial < 4000; ++trial) {
    // Luminances over 12 stops (dark texels weigh up to 1 / c), parts as the eq. 4 terms form them.
    wang::LuminanceBlockError error;
    const double scale = std::exp2(-8.0 + 12.0 * unit(random));
    for (int texel = 0; texel < 16; ++texel) {
      error.luminance[texel] = trial % 7 == 0 ? scale : scale * std::exp2(-6.0 * unit(random));
      error.weight[texel] = 1.0 / (error.luminance[texel] + 1.0 / 16384.0);
    }
    std::vector<double> part0(1 + trial % 8), part1(1 + (trial / 8) % 8);
    for (double& a : part0) a = std::round(255.0 * unit(random)) / 255.0 * scale;
    for (double& b : part1) b = trial % 3 == 0 ? 0.0 : std::round(255.0 * unit(random)) / 255.0 * scale * 0.25;
    // Both screens: the AVX2 one where the CPU has it, and the SSE2 one (what a CPU without AVX2 runs).
    wang::TrialTexels texels = wang::make_trial_texels(error);
    ASSERT_TRUE(texels.screen);
    texels.wide_screen = trial % 2 == 0 && texels.wide_screen;
    const double exact = exhaustive_nearest_sum_total(error, part0, part1);
    const int count0 = static_cast<int>(part0.size()), count1 = static_cast<int>(part1.size());
    // Far above, at and around the exact total (the float screen's margin of doubt), far below.
    for (const double factor : {4.0, 1.0 + 1e-4, 1.0 + 1e-9, 1.0, 1.0 - 1e-9, 1.0 - 1e-6, 0.5}) {
      const double bound = exact * factor;
      const double answer = wang::nearest_sum_total_below(texels, part0.data(), count0, part1.data(), count1, bound);
      if (exact < bound) {
        EXPECT_EQ(answer, exact) << "trial " << trial << " factor " << factor;
      } else {
        EXPECT_GE(answer, bound) << "trial " << trial << " factor " << factor;
        (std::isinf(answer) ? refused_near_ties : accepted_near_ties) += factor >= 1.0 - 1e-6 && factor <= 1.0;
        if (factor == 0.5 && std::isinf(answer)) ++refused_far_below[texels.wide_screen ? 1 : 0];
      }
    }
    EXPECT_EQ(wang::nearest_sum_total_below(texels, part0.data(), count0, part1.data(), count1,
                                            std::numeric_limits<double>::infinity()),
              exact);
  }
  // Both stages decide some of the near ties: the float screen refuses where it can prove the answer, the exact
  // pass settles the rest.
  EXPECT_GT(accepted_near_ties, 0);
  // Each screen refuses the clear cases by itself (a total twice the bound).
  EXPECT_GT(refused_far_below[0], 1000);
  if (cpu_has_avx2()) {
    EXPECT_GT(refused_far_below[1], 1000);
  }
}

TEST(WangEncoderSearch, PresetsOrderTheirEffort) {
  const wang::SearchEffort fast = wang::preset_effort("fast", "test");
  const wang::SearchEffort medium = wang::preset_effort("medium", "test");
  const wang::SearchEffort thorough = wang::preset_effort("thorough", "test");
  EXPECT_LT(fast.descent_passes, medium.descent_passes);
  EXPECT_LE(medium.descent_passes, thorough.descent_passes);
  EXPECT_LT(medium.descent_steps.size(), thorough.descent_steps.size());
  EXPECT_FALSE(medium.search_inactive_channel);
  EXPECT_TRUE(thorough.search_inactive_channel);
  EXPECT_LT(fast.residual_candidates, medium.residual_candidates);
  EXPECT_LT(medium.residual_candidates, thorough.residual_candidates);
}

}  // namespace
}  // namespace blocklab
