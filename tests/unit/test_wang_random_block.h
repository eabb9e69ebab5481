// A random `wang` block with the two block errors of its joint code choice (wang_joint_codes.h), shared by the tests
// of that choice: canonical alpha and colour blocks from random bytes, random eq. 4 constants and residual ranges,
// and luminances `scale` x U x U with eq. 9 weights 1 / (L + c).
#pragma once

#include <cstdint>
#include <random>

#include "formats/bc4/bc4_block.h"
#include "formats/wang/wang_block.h"
#include "formats/wang/wang_block_problem.h"

namespace blocklab {
namespace test_wang {

struct RandomJointBlock {
  wang::BlockParams params;
  wang::LuminanceBlockError luminance;
  wang::ResidualBlockError residual;
};

// `rmin_scale`: smin is drawn from [-rmin_scale, 0] (below -L' the decode can be black); `c` is both the residual
// error's c and the weights' c.
inline RandomJointBlock random_joint_block(std::mt19937& rng, double rmin_scale, bool ratio, double c, double scale) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  RandomJointBlock block;
  std::uint8_t bytes[wang::kBlockBytes];
  for (auto& byte : bytes) byte = static_cast<std::uint8_t>(rng() & 0xffu);
  block.params = wang::unpack_block(bytes);
  block.params.tex0.alpha = canonicalise_bc4(block.params.tex0.alpha);
  block.params.tex1.alpha = canonicalise_bc4(block.params.tex1.alpha);
  block.params.tex1.color = canonicalise_bc3_color(block.params.tex1.color);
  block.luminance.high = 50.0 * unit(rng);
  block.luminance.low = 2.0 * unit(rng);
  block.luminance.tmin = 0.01 * unit(rng);
  block.residual.ranges = {unit(rng), unit(rng), 3.0 * unit(rng)};
  block.residual.rmin = -rmin_scale * unit(rng);
  block.residual.ratio = ratio;
  block.residual.c = c;
  for (int texel = 0; texel < 16; ++texel) {
    block.residual.luminance[texel] = block.luminance.luminance[texel] = scale * unit(rng) * unit(rng);
    block.residual.weight[texel] = block.luminance.weight[texel] = 1.0 / (block.luminance.luminance[texel] + c);
  }
  return block;
}

}  // namespace test_wang
}  // namespace blocklab
