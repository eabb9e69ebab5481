// The clamp of the LDR PSNR metrics (SPECS.md section 1d): inputs are code values scaled to [0, 1] (8/16-bit PNG
// are read that way, core/image.h); anything outside [0, 1] — an HDR image passed to an LDR metric, or a decoder
// overshoot — is clamped before the error is measured, and the number of clamped values is reported.
#pragma once

#include <cstddef>

namespace blocklab {

// Returns value clamped to [0, 1] and counts every value that was changed. NaN -> 0.
inline double clamp_code_value(float value, std::size_t& clamped_count) {
  const double x = static_cast<double>(value);
  if (x >= 0.0 && x <= 1.0) return x;
  ++clamped_count;
  return x > 1.0 ? 1.0 : 0.0;   // NaN fails both comparisons and lands on 0, like a negative value
}

}  // namespace blocklab
