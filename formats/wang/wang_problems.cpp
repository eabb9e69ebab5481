// The `wang` block problems, drawn from one HDR block as if it were the whole texture (Wang et al. 2007):
//   luminance  the two alpha endpoints of tex0 and tex1 (eq. 4, two zones), with the block's own zones: tmin, tmax
//              its smallest and largest L = |RGB| (eq. 1) and t1 by eq. 2's linear search over its texels;
//   residual   the RGB565 endpoints of tex1's colour block carrying S = L - L' (eqs. 6-7), with L' the block's L
//              quantised to its zones' 8-bit alpha steps (what an exact alpha fit decodes) and the three S zones
//              split evenly over the block's residual range.
// Both use the log-domain error of eq. 9 with the format's default c = 2^-14 and the texture unit's 8-bit rounding.
#include "formats/wang/wang_problems.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "formats/wang/wang_block_problem.h"
#include "formats/wang/wang_color_space.h"
#include "formats/wang/wang_shader.h"
#include "formats/wang/wang_zone_split.h"

namespace blocklab {

namespace {

constexpr double kErrorC = 1.0 / 16384.0;   // the format's default error_c

struct BlockLuminance {
  std::array<double, 16> luminance{}, weight{};
  wang::Zones zones;
};

BlockLuminance block_luminance(const BlockTexels& block) {
  BlockLuminance out;
  std::vector<double> values(16), weights(16);
  for (int texel = 0; texel < kBlockTexels; ++texel) {
    const double l = wang::to_luminance_chroma(wang::ColorSpace::luvw, block.rgba[texel]).luminance;
    out.luminance[static_cast<std::size_t>(texel)] = values[static_cast<std::size_t>(texel)] = l;
    out.weight[static_cast<std::size_t>(texel)] = weights[static_cast<std::size_t>(texel)] = 1.0 / (l + kErrorC);
  }
  out.zones.tmin = *std::min_element(values.begin(), values.end());
  out.zones.tmax = *std::max_element(values.begin(), values.end());
  const wang::SplitResult split = wang::fit_luminance_split(values, weights, wang::SplitSearch{});
  out.zones.t1 = std::clamp(split.split[0], out.zones.tmin, out.zones.tmax);
  return out;
}

std::unique_ptr<Problem> luminance_problem(const BlockTexels& block) {
  const BlockLuminance data = block_luminance(block);
  const wang::ShaderConstants constants =
      wang::shader_constants(data.zones, wang::LuminanceSplit::two_zones, wang::Residual::none);
  wang::LuminanceBlockError error;
  error.luminance = data.luminance;
  error.weight = data.weight;
  error.high = constants.l_high;
  error.low = constants.l_low;
  error.tmin = constants.tmin;
  return std::make_unique<ErrorProblem<wang::LuminanceBlockError>>(wang::make_luminance_block_problem(error));
}

std::unique_ptr<Problem> residual_problem(const BlockTexels& block) {
  BlockLuminance data = block_luminance(block);
  wang::ResidualBlockError error;
  error.luminance = data.luminance;
  error.weight = data.weight;
  error.c = kErrorC;
  double low = 0.0, high = 0.0;
  for (std::size_t texel = 0; texel < 16; ++texel) {
    const double l = data.luminance[texel];
    // The zone a texel falls in, and L rounded to that zone's 8-bit step (a flat zone decodes its lower end).
    const bool in_low = l <= data.zones.t1;
    const double start = in_low ? data.zones.tmin : data.zones.t1;
    const double width = in_low ? data.zones.t1 - data.zones.tmin : data.zones.tmax - data.zones.t1;
    const double decoded = width > 0.0 ? start + std::round((l - start) / width * 255.0) / 255.0 * width : start;
    error.decoded[texel] = decoded;
    const double s = l - decoded;
    low = texel == 0 ? s : std::min(low, s);
    high = texel == 0 ? s : std::max(high, s);
  }
  data.zones.smin = low;
  data.zones.s1 = low + (high - low) / 3.0;
  data.zones.s2 = low + 2.0 * (high - low) / 3.0;
  data.zones.smax = high;
  const wang::ShaderConstants constants =
      wang::shader_constants(data.zones, wang::LuminanceSplit::two_zones, wang::Residual::s);
  for (int channel = 0; channel < 3; ++channel) error.ranges[channel] = constants.r_ranges[channel];
  error.rmin = constants.rmin;
  return std::make_unique<ErrorProblem<wang::ResidualBlockError>>(wang::make_residual_block_problem(error));
}

}  // namespace

std::vector<BlockProblem> wang_block_problems() {
  return {
      {"luminance",
       "tex0.a and tex1.a endpoints (4 parameters on [0, 255]), eq. 4 luminance, log-domain error |L - L'| / (L + c)",
       BlockImageKind::hdr, [](const BlockTexels& block, std::uint64_t) { return luminance_problem(block); }},
      {"residual",
       "tex1.rgb RGB565 endpoints (6 parameters) carrying the residual S (eqs. 6-7), log-domain error "
       "|L - D| / (min(L, D) + c) of the shown D = max(L', 0)",
       BlockImageKind::hdr, [](const BlockTexels& block, std::uint64_t) { return residual_problem(block); }},
  };
}

}  // namespace blocklab
