// The `munkberg` chroma reconstruction error (formats/munkberg/munkberg_log_error.h) holds the Problem contract
// (tests/contract/problem_contract.h): double, Jet and Interval evaluations agree, intervals enclose sampled errors,
// Jet gradients match finite differences where the error is smooth; and at lattice points it equals the log2[RGB]
// error of the decoded block up to the float rounding of decoded values. The same holds with the weights of every
// block error choice (formats/common/hdr_block_error.h), and each choice moves the base-colour polish elsewhere on a
// block where they disagree.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>
#include <random>

#include "formats/munkberg/munkberg_encoder.h"
#include "formats/common/hdr_block_error.h"
#include "formats/munkberg/munkberg_log_error.h"
#include "problem_contract.h"

namespace blocklab::munkberg {
namespace {

// A block of two chroma clusters with varying luminance, one decoded-black texel and one zero source channel.
ChromaLogTargets targets(std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ChromaLogTargets t;
  for (int i = 0; i < kTexels; ++i) {
    const std::size_t ii = static_cast<std::size_t>(i);
    t.log2_luminance[ii] = -3.0 + 6.0 * unit(random);
    t.black[ii] = i == 5;
    for (int c = 0; c < 3; ++c)
      t.source_log2[ii][static_cast<std::size_t>(c)] = (i == 7 && c == 2) ? -24.0 : t.log2_luminance[ii] - 1.5 * unit(random);
  }
  return t;
}

TEST(MunkbergLogErrorContract, ShapeOneProblemHoldsTheContract) {
  contract::check_problem_contract(make_chroma_log_problem(Mode::shape_i, default_shape_set().shapes[3], targets(1)));
}

TEST(MunkbergLogErrorContract, ShapeTwoProblemHoldsTheContract) {
  contract::check_problem_contract(make_chroma_log_problem(Mode::shape_ii, default_shape_set().shapes[1], targets(2)));
}

// The source texels behind targets(seed)'s source_log2 (a -24 stands for an exact zero).
BlockTexels source_of(const ChromaLogTargets& t) {
  BlockTexels source{};
  for (int i = 0; i < kTexels; ++i)
    for (int c = 0; c < 3; ++c) {
      const double s = t.source_log2[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)];
      source.rgba[i][c] = s <= -24.0 ? 0.0f : static_cast<float>(std::exp2(s));
    }
  return source;
}

TEST(MunkbergLogErrorContract, WeightedProblemsOfEveryErrorChoiceHoldTheContract) {
  for (const auto& [name, error] : hdr_block_error_choices()) {
    SCOPED_TRACE(name);
    ChromaLogTargets t = targets(4);
    t.set_error_weights(source_of(t), error);
    contract::check_problem_contract(make_chroma_log_problem(Mode::shape_i, default_shape_set().shapes[2], t));
  }
}

TEST(MunkbergLogErrorContract, EachErrorChoiceMovesThePolishToCodesTheOthersWouldLeave) {
  // Dark reddish texels (2^-8 .. 2^-4), bright bluish ones (2^1 .. 2^5) and a zero blue channel on a dark texel: the
  // log2 rules weigh every octave alike (floor pays for the zero, skip does not), mpsnr_weighted the bright texels.
  ChromaLogTargets t;
  for (int i = 0; i < kTexels; ++i) {
    const std::size_t ii = static_cast<std::size_t>(i);
    const bool bright = i >= 8;
    t.log2_luminance[ii] = (bright ? 1.0 : -8.0) + 0.5 * (i % 8);
    const double tint[3] = {bright ? -2.5 : -0.3, -1.2, bright ? -0.4 : -3.0 - 0.2 * (i % 3)};
    for (int c = 0; c < 3; ++c)
      t.source_log2[ii][static_cast<std::size_t>(c)] = (i == 2 && c == 2) ? -24.0 : t.log2_luminance[ii] + tint[c];
  }
  const ShapeTemplate& shape = default_shape_set().shapes[0];
  std::vector<ChromaLogError> errors;
  std::vector<std::array<int, kBaseCoordinateCount>> polished;
  for (const auto& [name, error] : hdr_block_error_choices()) {
    ChromaLogTargets weighted = t;
    weighted.set_error_weights(source_of(t), error);
    errors.push_back(ChromaLogError::make(Mode::shape_i, shape, weighted));
    std::array<int, kBaseCoordinateCount> codes = {40, 40, 40, 40};
    double value = std::numeric_limits<double>::infinity();
    polish_log_error_full(errors.back(), 256, &codes, &value);
    polished.push_back(codes);
  }
  const auto& choices = hdr_block_error_choices();
  for (std::size_t own = 0; own < choices.size(); ++own)
    for (std::size_t other = 0; other < choices.size(); ++other) {
      if (own == other) continue;
      EXPECT_NE(polished[own], polished[other]) << choices[own].first << " vs " << choices[other].first;
      // The other choice's codes are no local minimum of this choice's error: its polish moves on from them.
      std::array<int, kBaseCoordinateCount> codes = polished[other];
      double value = std::numeric_limits<double>::infinity();
      EXPECT_TRUE(polish_log_error_full(errors[own], 1, &codes, &value))
          << choices[own].first << "'s polish from " << choices[other].first << "'s codes";
    }
}

TEST(MunkbergLogErrorContract, EqualsTheDecodedBlocksLog2ErrorAtLatticePoints) {
  std::mt19937_64 random(3);
  for (int trial = 0; trial < 50; ++trial) {
    Params p;
    p.mode = trial % 2 == 0 ? Mode::shape_i : Mode::shape_ii;
    p.shape = static_cast<int>(random() % kShapeCount);
    for (int& c : p.base) c = static_cast<int>(random() % 128);
    p.lum = {static_cast<int>(60 + random() % 100), static_cast<int>(60 + random() % 100)};
    for (auto& l : p.lum_index) l = static_cast<std::uint8_t>(random() % (lum_levels_minus_one(p.mode) + 1));
    BlockTexels source;
    ChromaLogTargets t;
    const int n = lum_levels_minus_one(p.mode);
    for (int i = 0; i < kTexels; ++i) {
      const std::size_t ii = static_cast<std::size_t>(i);
      const std::int64_t q = static_cast<std::int64_t>(n - p.lum_index[ii]) * p.lum[0] + std::int64_t{p.lum_index[ii]} * p.lum[1];
      t.black[ii] = q == 0;
      t.log2_luminance[ii] = log_luminance_of_numerator(q, n);
      for (int c = 0; c < 3; ++c) {
        source.rgba[i][c] = static_cast<float>(std::exp2(-2.0 + 4.0 * static_cast<double>(random() % 1000) / 1000.0));
        t.source_log2[ii][static_cast<std::size_t>(c)] = std::log2(static_cast<double>(source.rgba[i][c]));
      }
      source.rgba[i][3] = 1.0f;
    }
    const auto problem = make_chroma_log_problem(p.mode, default_shape_set().shapes[static_cast<std::size_t>(p.shape)], t);
    double x[4];
    for (int k = 0; k < 4; ++k) x[k] = base_value(p.base[static_cast<std::size_t>(k)]);
    // The problem takes the best landmark per group: the decoded block with those indices has the same error.
    Params best = p;
    assign_chroma_indices_log2(source, default_shape_set(), &best);
    const double decoded_error = block_log2_error(source, decode_params(best, default_shape_set()));
    EXPECT_NEAR(problem.eval(x), decoded_error, 1e-5 * (1.0 + decoded_error)) << "trial " << trial;
  }
}

}  // namespace
}  // namespace blocklab::munkberg
