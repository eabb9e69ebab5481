// The `munkberg` chroma reconstruction error (formats/munkberg/munkberg_log_error.h) holds the Problem contract
// (tests/contract/problem_contract.h): double, Jet and Interval evaluations agree, intervals enclose sampled errors,
// Jet gradients match finite differences where the error is smooth; and at lattice points it equals the log2[RGB]
// error of the decoded block up to the float rounding of decoded values.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "formats/munkberg/munkberg_encoder.h"
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
