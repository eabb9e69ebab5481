// The colour spaces of Wang et al. 2007 ("Rendering from compressed high dynamic range textures on programmable
// graphics hardware", I3D 2007): the forward conversions the encoder runs (section 3.1 eq. 1, section 4.1 eq. 10)
// and the inverse the pixel shader runs (eq. 8), the latter templated on the scalar type.
//
//   luvw (eq. 1)   L = sqrt(R^2 + G^2 + B^2), (U, V, W) = (R, G, B) / L          inverse: RGB = UVW * L (eq. 8)
//   luv  (eq. 10)  L = R + 2 G + B, U = R / L, V = 2 G / L                       inverse: R = U L, G = V L / 2,
//                                                                                 B = max(1 - U - V, 0) L
// The LUV inverse is not printed in the paper; it follows from eq. 10 (B = L - R - 2 G). Its max(., 0) keeps a
// quantised U + V > 1 from producing negative blue.
// Black texels (L = 0) have no chromaticity; the encoder gives them the grey direction (LUVW: 1/sqrt(3) each, LUV:
// U = 1/4, V = 1/2), which any L' * chroma turns back into black when L' = 0.
#pragma once

#include <cmath>

#include "core/scalar.h"

namespace blocklab {
namespace wang {

enum class ColorSpace { luvw, luv };

struct LuminanceChroma {
  double luminance = 0.0;
  double chroma[3] = {0.0, 0.0, 0.0};   // tex0.rgb targets in [0, 1]; LUV leaves chroma[2] = 0 (unused channel)
};

// Encoder side, in double. `rgb` must be finite and non-negative (the input policy's guarantee).
inline LuminanceChroma to_luminance_chroma(ColorSpace space, const float rgb[3]) {
  const double r = rgb[0], g = rgb[1], b = rgb[2];
  LuminanceChroma out;
  if (space == ColorSpace::luvw) {
    out.luminance = std::sqrt(r * r + g * g + b * b);
    if (!(out.luminance > 0.0)) {
      out.chroma[0] = out.chroma[1] = out.chroma[2] = 1.0 / std::sqrt(3.0);
      return out;
    }
    for (int channel = 0; channel < 3; ++channel)
      out.chroma[channel] = std::fmin(1.0, static_cast<double>(rgb[channel]) / out.luminance);
    return out;
  }
  out.luminance = r + 2.0 * g + b;
  if (!(out.luminance > 0.0)) {
    out.chroma[0] = 0.25;
    out.chroma[1] = 0.5;
    return out;
  }
  out.chroma[0] = std::fmin(1.0, r / out.luminance);
  out.chroma[1] = std::fmin(1.0, 2.0 * g / out.luminance);
  return out;
}

// Shader side (eq. 8 and the LUV inverse), any scalar type; `chroma` are the fetched tex0.rgb values.
template <typename T>
void to_rgb(ColorSpace space, const T chroma[3], const T& luminance, T rgb[3]) {
  if (space == ColorSpace::luvw) {
    for (int channel = 0; channel < 3; ++channel) rgb[channel] = chroma[channel] * luminance;
    return;
  }
  rgb[0] = chroma[0] * luminance;
  rgb[1] = (chroma[1] * luminance) * T(0.5);
  rgb[2] = max((T(1.0) - chroma[0]) - chroma[1], T(0.0)) * luminance;
}

}  // namespace wang
}  // namespace blocklab
