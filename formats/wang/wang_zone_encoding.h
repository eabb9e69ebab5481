// The channel assignments of Wang et al. 2007 section 3.3: how the encoder spreads one luminance over tex0.a and
// tex1.a (eq. 3, so that eq. 4 decodes it without a branch, Claim 3.1) and one residual over tex1.rgb (eq. 6,
// decoded by eq. 7). These are the targets the BC3 encoders (codec=bc3) are given; the 1D codec
// (wang_luminance_codec.h, wang_residual_codec.h) fits the decoded sum directly.
//
//   eq. 3 (2x6):  L in [tmin, t1]:  tex0.a = 0,                         tex1.a = (L - tmin) / (t1 - tmin)
//                 L in [t1, tmax]:  tex0.a = (L - t1) / (tmax - t1),     tex1.a = 1
//   so L = tex0.a (tmax - t1) + tex1.a (t1 - tmin) + tmin in both zones (eq. 4). The printed eq. 3 / eq. 4 and the
//   shader of Table 1 agree on this assignment (t0.a multiplies the high range g_LRangeLowHigh.y); Appendix A's
//   proof swaps the two textures (tex0.a for the low zone), which contradicts eq. 4 and the shader; we follow those.
//   1x12:         q = round((L - tmin) / (tmax - tmin) 4095), tex0.a = floor(q / 64) / 63, tex1.a = (q mod 64) / 63.
//   eq. 6:        S in [smin, s1]: (r, g, b) = ((S - smin) / (s1 - smin), 0, 0)
//                 S in [s1, s2]:   (1, (S - s1) / (s2 - s1), 0)
//                 S in [s2, smax]: (1, 1, (S - s2) / (smax - s2))
//   so S = r (s1 - smin) + g (s2 - s1) + b (smax - s2) + smin (eq. 7). A zone of zero width contributes 0.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "formats/wang/wang_shader.h"

namespace blocklab {
namespace wang {

// (value - low) / (high - low) clamped to [0, 1]; 0 for an empty zone.
inline double zone_fraction(double value, double low, double high) {
  if (!(high > low)) return 0.0;
  return std::clamp((value - low) / (high - low), 0.0, 1.0);
}

// tex0.a and tex1.a of one luminance, in [0, 1].
inline std::array<double, 2> luminance_targets(double luminance, const Zones& zones, LuminanceSplit split) {
  if (split == LuminanceSplit::one_range) {
    const double q = std::nearbyint(zone_fraction(luminance, zones.tmin, zones.tmax) * 4095.0);
    const double high = std::floor(q / 64.0);
    return {high / 63.0, (q - 64.0 * high) / 63.0};
  }
  if (luminance <= zones.t1) return {0.0, zone_fraction(luminance, zones.tmin, zones.t1)};
  return {zone_fraction(luminance, zones.t1, zones.tmax), 1.0};
}

// tex1.rgb of one residual, in [0, 1].
inline std::array<double, 3> residual_targets(double residual, const Zones& zones) {
  if (residual <= zones.s1) return {zone_fraction(residual, zones.smin, zones.s1), 0.0, 0.0};
  if (residual <= zones.s2) return {1.0, zone_fraction(residual, zones.s1, zones.s2), 0.0};
  return {1.0, 1.0, zone_fraction(residual, zones.s2, zones.smax)};
}

}  // namespace wang
}  // namespace blocklab
