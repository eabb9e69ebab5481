// The exposure tone curve of multi-exposure PSNR (Munkberg et al. 2006; SPECS.md section 1b), shared by `mpsnr`
// (fixed stops, astcenc) and `mpsnr_auto` (HDR_Toolbox automatic stops):
//     T(X, c) = clamp(255 * (2^c * X)^(1/gamma), 0, 255),  gamma = 2.2, per channel,
// optionally rounded to the nearest integer (half away from zero, like MATLAB's round) before the clamp.
//
// Evaluated as 255 * 2^(c/gamma) * X^(1/gamma): mathematically identical to (2^c X)^(1/gamma) (different only in the
// last bits), and it needs one pow per channel value instead of one per value and stop, which matters on 4k images.
#pragma once

#include <algorithm>
#include <cmath>

namespace blocklab {

inline constexpr double kExposureGamma = 2.2;        // display gamma of T (Munkberg 2006, astcenc, HDR_Toolbox)
inline constexpr double kExposureCodeMax = 255.0;    // 8-bit code range of T

// X^(1/gamma) for one channel value. Negative values and NaN become 0 before the power (a negative base has no real
// power; the toolbox refuses negative input and astcenc clamps to 0).
inline double exposure_gamma_base(float value) {
  const double x = static_cast<double>(value);
  if (!(x > 0.0)) return 0.0;   // zero, negative or NaN
  return std::pow(x, 1.0 / kExposureGamma);
}

// 2^(stop/gamma): the exposure 2^stop moved through the power.
inline double exposure_stop_scale(int stop) { return std::pow(2.0, static_cast<double>(stop) / kExposureGamma); }

// T for one channel value at one stop, from its gamma base and the stop's scale.
inline double exposure_code(double gamma_base, double stop_scale, bool quantise) {
  double code = kExposureCodeMax * (stop_scale * gamma_base);
  if (quantise) code = std::round(code);          // halves round away from zero (MATLAB round)
  return std::min(code, kExposureCodeMax);        // +Inf inputs saturate at 255 here; the base is never negative
}

}  // namespace blocklab
