// The Problem contract (tests/contract/problem_contract.h: double / Jet / Interval agree, intervals enclose dense
// samples of random boxes, Jet gradients match finite differences where the error is differentiable) for the `wang`
// format's Problems: the zone splits (wang_zone_problem.h) and the 1D codec's block errors (wang_block_problem.h),
// with and without the texture unit's 8-bit rounding.
#include <gtest/gtest.h>

#include <random>

#include "formats/wang/wang_block_problem.h"
#include "formats/wang/wang_zone_problem.h"
#include "tests/contract/problem_contract.h"

namespace blocklab {
namespace {

wang::LuminanceBlockError luminance_error(bool texture_unit, Bc4Mode mode1) {
  std::mt19937 rng(31);
  std::lognormal_distribution<double> luminance(0.0, 1.5);
  wang::LuminanceBlockError error;
  error.high = 120.0;
  error.low = 2.5;
  error.tmin = 0.002;
  error.modes = {Bc4Mode::eight_value, mode1};
  error.texture_unit = texture_unit;
  for (int texel = 0; texel < 16; ++texel) {
    error.luminance[texel] = luminance(rng);
    error.weight[texel] = 1.0 / (error.luminance[texel] + 1e-3);
  }
  return error;
}

wang::ResidualBlockError residual_error(bool texture_unit, bool ratio) {
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  wang::ResidualBlockError error;
  error.ranges = {0.8, 0.3, 2.5};
  error.rmin = -0.9;
  error.ratio = ratio;
  error.texture_unit = texture_unit;
  for (int texel = 0; texel < 16; ++texel) {
    error.luminance[texel] = 0.5 + 4.0 * unit(rng);
    error.decoded[texel] = error.luminance[texel] * (0.8 + 0.4 * unit(rng));
    error.weight[texel] = 1.0 / error.luminance[texel];
  }
  return error;
}

contract::ContractOptions light_options() {
  contract::ContractOptions options;
  options.point_count = 60;
  options.box_count = 40;
  options.samples_per_box = 30;
  return options;
}

TEST(WangProblems, LuminanceBlockErrorMeetsTheProblemContractWithAndWithoutTextureUnitRounding) {
  for (const bool texture_unit : {false, true})
    for (const Bc4Mode mode : {Bc4Mode::eight_value, Bc4Mode::six_value}) {
      SCOPED_TRACE(texture_unit ? "8-bit texture unit" : "exact fractions");
      contract::check_problem_contract(wang::make_luminance_block_problem(luminance_error(texture_unit, mode)),
                                       light_options());
    }
}

TEST(WangProblems, ResidualBlockErrorMeetsTheProblemContractForSAndRatio) {
  for (const bool texture_unit : {false, true})
    for (const bool ratio : {false, true}) {
      SCOPED_TRACE(std::string(texture_unit ? "8-bit" : "exact") + (ratio ? " ratio" : " s"));
      contract::check_problem_contract(wang::make_residual_block_problem(residual_error(texture_unit, ratio)),
                                       light_options());
    }
}

TEST(WangProblems, ZoneSplitErrorsMeetTheProblemContract) {
  std::mt19937 rng(33);
  std::lognormal_distribution<double> value(0.0, 2.0);
  wang::ZoneSplitError<2> two;
  wang::ZoneSplitError<3> three;
  // Few samples: every sample adds a rounding step in x, and the gradient check needs stable finite differences.
  for (int k = 0; k < 12; ++k) {
    const double v = value(rng);
    two.samples.push_back({v, 1.0 / (v + 1e-3)});
    three.samples.push_back({v - 3.0, 1.0});
  }
  two.low = 0.0;
  two.high = 60.0;
  two.levels = {255.0, 255.0};
  three.low = -3.0;
  three.high = 57.0;
  three.levels = {31.0, 63.0, 31.0};
  contract::check_problem_contract(wang::make_zone_split_problem(two, 4097), light_options());
  contract::check_problem_contract(wang::make_zone_split_problem(three, 1025), light_options());
}

}  // namespace
}  // namespace blocklab
