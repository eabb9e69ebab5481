// The decoder of Wang et al. 2007: the texture unit's 8-bit DXT5 output and the section 3.4 pixel shader (Table 1),
// templated on the scalar type so that one function is the Format's decoder (float), the search-time error
// (double, ceres::Jet) and its enclosure (blocklab::Interval).
//
// DECODING CONVENTION (what every blocklab metric of this format measures)
//   1. Each of the two BC3 blocks is decoded with blocklab's BC3 reference decoding (formats/bc3/bc3_block.h,
//      formats/common/s3tc_common.h): exact fractions v of the bit-replicated 565 colour endpoints (4-colour palette
//      for every endpoint order) and of the 8-bit alpha endpoints (8- or 6-value palette by the endpoint order).
//   2. The texture unit returns 8-bit UNORM channels: t = round(255 v) / 255 (float). BC3 interpolants are thirds,
//      fifths or sevenths of integers, never halves, so the rounding has no ties and this is the D3D9-style rounding
//      decoder for every block (formats/common/s3tc_common.h lists the vendor rules; each is within one 8-bit step).
//   3. The shader of Table 1 in float (IEEE single, no fused multiply-add), evaluated left to right:
//        dot(a, b) = (a.r b.r + a.g b.g) + a.b b.b
//        residual s:     L = ((t0.a high + t1.a low) + min_plus_rmin) + dot(t1.rgb, r_ranges)     (eq. 7)
//        residual ratio: Lp = (t0.a high + t1.a low) + tmin;  L = Lp + Lp (dot(t1.rgb, r_ranges) + rmin)  (eq. 11)
//        residual none:  L = (t0.a high + t1.a low) + tmin                                              (eq. 4)
//        RGB = colour-space inverse of (t0.rgb, max(L, 0))                      (eq. 8; wang_color_space.h)
//      with the shader constants of shader_constants() below, each computed in double from the side data and
//      rounded once to float (the values an application would upload as g_LRangeLowHigh, g_LMinPlusRMin,
//      g_RRangeLowMidHigh). The max(L, 0) is the one addition to Table 1: a decoded texel is never negative light.
#pragma once

#include "core/scalar.h"
#include "formats/common/s3tc_common.h"
#include "formats/wang/wang_color_space.h"

namespace blocklab {
namespace wang {

enum class Residual { s, ratio, none };
// l_bits: 2x6 = two uniform zones (eq. 3, the paper's choice); 1x12 = one uniform range whose 12-bit code is split
// 6 + 6 over tex0.a (high bits) and tex1.a (low bits), the alternative of section 4.3 / Fig. 4.
enum class LuminanceSplit { two_zones, one_range };

// The per-texture constants (EncodedTexture::side_data, wang_side_data.h).
struct Zones {
  double tmin = 0.0, t1 = 0.0, tmax = 0.0;                 // eq. 3 zones [tmin, t1], [t1, tmax] (t1 unused for 1x12)
  double smin = 0.0, s1 = 0.0, s2 = 0.0, smax = 0.0;       // eq. 6 zones of S (or T for ratio); all 0 for none
};

// The shader's uniform constants, as float.
struct ShaderConstants {
  float l_high = 0.0f;          // multiplies t0.a: tmax - t1 (2x6), (tmax - tmin) 4032 / 4095 (1x12)
  float l_low = 0.0f;           // multiplies t1.a: t1 - tmin (2x6), (tmax - tmin) 63 / 4095 (1x12)
  float tmin = 0.0f;            // eq. 4 offset
  float min_plus_rmin = 0.0f;   // g_LMinPlusRMin = tmin + smin (residual s)
  float rmin = 0.0f;            // smin (residual ratio)
  float r_ranges[3] = {0.0f, 0.0f, 0.0f};   // g_RRangeLowMidHigh = (s1 - smin, s2 - s1, smax - s2)
};

// 12-bit code of the 1x12 split: q = 64 hi + lo with hi, lo in 0..63 stored as hi / 63 and lo / 63.
constexpr double kOneRangeHighWeight = 4032.0 / 4095.0;   // 64 * 63 / 4095
constexpr double kOneRangeLowWeight = 63.0 / 4095.0;

inline ShaderConstants shader_constants(const Zones& zones, LuminanceSplit split, Residual residual) {
  ShaderConstants c;
  if (split == LuminanceSplit::two_zones) {
    c.l_high = static_cast<float>(zones.tmax - zones.t1);
    c.l_low = static_cast<float>(zones.t1 - zones.tmin);
  } else {
    c.l_high = static_cast<float>((zones.tmax - zones.tmin) * kOneRangeHighWeight);
    c.l_low = static_cast<float>((zones.tmax - zones.tmin) * kOneRangeLowWeight);
  }
  c.tmin = static_cast<float>(zones.tmin);
  if (residual != Residual::none) {
    c.min_plus_rmin = static_cast<float>(zones.tmin + zones.smin);
    c.rmin = static_cast<float>(zones.smin);
    c.r_ranges[0] = static_cast<float>(zones.s1 - zones.smin);
    c.r_ranges[1] = static_cast<float>(zones.s2 - zones.s1);
    c.r_ranges[2] = static_cast<float>(zones.smax - zones.s2);
  }
  return c;
}

// A float shader constant as a scalar of type T (through double, the one constructor every scalar type has).
template <typename T>
T as_scalar(float value) {
  return T(static_cast<double>(value));
}

// Step 2: the texture unit's 8-bit value of an exact palette value v in [0, 1]. floor(255 v + 1/2) is
// round-to-nearest because 255 v is never within 1/14 of a half-integer for BC3 (see above).
template <typename T>
T texture_unit_value(const T& exact) {
  return floor_scalar(exact * T(255.0) + T(0.5)) / T(255.0);
}

// The residual part of step 3: dot(t1.rgb, r_ranges).
template <typename T>
T residual_dot(const ShaderConstants& c, const T t1_rgb[3]) {
  return (t1_rgb[0] * as_scalar<T>(c.r_ranges[0]) + t1_rgb[1] * as_scalar<T>(c.r_ranges[1])) +
         t1_rgb[2] * as_scalar<T>(c.r_ranges[2]);
}

// Step 3 without the colour-space inverse: the decoded luminance L from the fetched texel values.
template <typename T>
T shader_luminance(const ShaderConstants& c, Residual residual, const T& t0_alpha, const T& t1_alpha,
                   const T t1_rgb[3]) {
  const T zones = t0_alpha * as_scalar<T>(c.l_high) + t1_alpha * as_scalar<T>(c.l_low);
  switch (residual) {
    case Residual::s:
      return (zones + as_scalar<T>(c.min_plus_rmin)) + residual_dot(c, t1_rgb);
    case Residual::ratio: {
      const T base = zones + as_scalar<T>(c.tmin);
      return base + base * (residual_dot(c, t1_rgb) + as_scalar<T>(c.rmin));
    }
    case Residual::none:
      break;
  }
  return zones + as_scalar<T>(c.tmin);
}

// The whole shader for one texel: fetched tex0 (rgba) and tex1 (rgba) -> RGB.
template <typename T>
void shade_texel(const ShaderConstants& c, ColorSpace space, Residual residual, const T t0[4], const T t1[4],
                 T rgb[3]) {
  const T luminance = max(shader_luminance(c, residual, t0[3], t1[3], t1), T(0.0));
  to_rgb(space, t0, luminance, rgb);
}

}  // namespace wang
}  // namespace blocklab
